// vcontact friction-map: the options of the friction map (validation/friction_map.hpp), its
// CSV, and the table it prints.

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "io/shape_spec.hpp"
#include "report/friction_map_csv.hpp"
#include "validation/friction_map.hpp"

namespace vcontact::cli {
namespace {

struct FrictionMapCommand {
  validation::FrictionMapOptions map;
  std::string shape;  // empty: the flat punch
  std::string out = "friction_map.csv";
};

validation::FrictionMap frictionMap(const FrictionMapCommand& o) {
  validation::FrictionMapOptions options = o.map;
  if (!o.shape.empty()) {
    const io::ParsedShape parsed = io::parseShape(o.shape, "--shape (" + o.shape + ")");
    printWarnings(parsed.warnings);
    options.shape = parsed.shape;
  }
  const std::map<std::string, std::string> optionOf = {{"radius", "--radius"},
                                                       {"load", "--load"},
                                                       {"mu", "--mu"},
                                                       {"kv", "--kv"},
                                                       {"depth", "--depth"},
                                                       {"speed", "--speed"},
                                                       {"epsilon range", "--eps-min/--eps-max"},
                                                       {"points per decade", "--per-decade"},
                                                       {"shape", "--shape (" + o.shape + ")"}};
  return namingOptions(optionOf, [&] { return validation::frictionMap(options); });
}

void printTable(const validation::FrictionMap& map) {
  const double fn = map.f_n;
  std::cout << "vcontact friction-map: " << map.description << "\n  f_n = " << fn
            << " N, mu = " << map.mu << ", r_gyr = " << map.r_gyr << " m, column grid error "
            << map.relative_error << "\n  F in mu f_n, M in mu f_n R; ratio = lumped / "
            << "distributed\n";
  std::cout << std::setw(12) << "eps" << std::setw(10) << "F_lumped" << std::setw(10) << "F_dist"
            << std::setw(10) << "F_exact" << std::setw(9) << "F_ratio" << std::setw(10)
            << "M_lumped" << std::setw(10) << "M_dist" << std::setw(10) << "M_exact" << std::setw(9)
            << "M_ratio" << '\n';
  std::cout << std::fixed;
  for (const validation::FrictionMapRow& r : map.rows) {
    const double F = map.mu * fn, M = F * map.R;
    std::cout << std::setprecision(5) << std::scientific << std::setw(12) << r.eps << std::fixed
              << std::setw(10) << r.f_lumped / F << std::setw(10) << r.f_dist / F << std::setw(10)
              << (r.exact ? r.exact->force : std::nan("")) << std::setw(9)
              << validation::lumpedOverDistributed(r.f_lumped, r.f_dist) << std::setw(10)
              << r.m_lumped / M << std::setw(10) << r.m_dist / M << std::setw(10)
              << (r.exact ? r.exact->torque : std::nan("")) << std::setw(9)
              << validation::lumpedOverDistributed(r.m_lumped, r.m_dist) << '\n';
  }
}

void runFrictionMap(const FrictionMapCommand& o) {
  const validation::FrictionMap map = frictionMap(o);
  report::writeFrictionMapCsv(map, o.out);
  printTable(map);
  std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void addFrictionMapCommand(CLI::App& app) {
  auto o = std::make_shared<FrictionMapCommand>();
  validation::FrictionMapOptions& m = o->map;
  CLI::App* cmd = app.add_subcommand(
      "friction-map",
      "Where the lumped friction fails: sweep eps = v/(omega R) over decades for a body sliding "
      "at v and spinning at omega on a plate, and compare the lumped Coulomb + spin + "
      "contensou friction (MODEL.md section 3) with pointwise Coulomb friction integrated over "
      "the column method's penetration map and, for the flat punch, with the closed form "
      "(docs/DISTRIBUTED_FRICTION.md). Writes a CSV (forces in N, torques in N m about the "
      "centroid; rows eps = 0 and inf are pure spin and pure sliding) and prints the table "
      "normalised by mu f_n and mu f_n R. Expect the lumped spin torque 1.06x the exact one at "
      "pure spin and 2x as sliding dominates, the lumped force sqrt(2)x while spin dominates.");
  cmd->add_option("--radius", m.radius, "flat punch radius, m")->capture_default_str();
  cmd->add_option("--load", m.load, "normal load on the punch, N")->capture_default_str();
  cmd->add_option("--mu", m.mu, "Coulomb friction coefficient")->capture_default_str();
  cmd->add_option("--kv", m.kv, "volumetric stiffness, N/m^3")->capture_default_str();
  cmd->add_option("--eps-min", m.eps_min, "smallest eps > 0 of the sweep")->capture_default_str();
  cmd->add_option("--eps-max", m.eps_max, "largest eps of the sweep")->capture_default_str();
  cmd->add_option("--per-decade", m.per_decade, "sweep points per decade of eps")
      ->capture_default_str();
  cmd->add_option("--speed", m.speed,
                  "combined slip speed sqrt(v^2 + (omega R)^2), m/s (far above v_eps = 1e-5)")
      ->capture_default_str();
  cmd->add_option("--shape", o->shape,
                  "instead of the punch: a shape (mesh file, cylinder:R,L, box:X,Y,Z, sphere:R) "
                  "pressed --depth into the plate in its own orientation; R = sqrt(2) r_gyr and "
                  "no closed form");
  cmd->add_option("--depth", m.depth, "penetration of --shape, m")->capture_default_str();
  cmd->add_option("--out", o->out, "CSV file to write")->capture_default_str();
  cmd->callback([o] { runFrictionMap(*o); });
}

}  // namespace vcontact::cli
