// vcontact friction-map: where the lumped Coulomb + spin + contensou friction (MODEL.md §3)
// departs from pointwise Coulomb friction integrated over the contact (dynamics/
// DISTRIBUTED_FRICTION.md), swept over ε = v/(ωR) for combined sliding and spinning.

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <variant>

#include "cli/commands.hpp"
#include "dynamics/distributed_friction.hpp"
#include "dynamics/model.hpp"
#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "io/shape_spec.hpp"
#include "volume/columns.hpp"
#include "volume/contact.hpp"

namespace vcontact::cli {
namespace {

// A 512-gon's area is within 2.5e-5 of the circle's, below the column grid's error (~1e-3).
constexpr int kPunchSegments = 512;
constexpr int kSphereSegments = 256, kSphereRings = 128;
constexpr int kMaxRows = 2000;
// The plate is tilted by these angles (degrees): the column method finds the region with
// passes along the world axes, which miss a micrometre-thin slab lying exactly in a
// coordinate plane (reported to volume/). The friction is frame-invariant.
const Eigen::Vector3d kPlateRpyDeg(17.0, 29.0, 0.0);

struct FrictionMapOptions {
  double radius = 0.01;  // m: a 20 mm steel punch
  double load = 10.0;    // N
  double mu = 0.2;       // MODEL.md §4
  double kv = 5.17e12;   // N/m³, MODEL.md §4
  double epsMin = 1e-3, epsMax = 1e3;
  int perDecade = 4;
  double speed = 1.0;   // m/s, |v| + ... scale of the slip, see --speed
  std::string shape;    // empty: the flat punch
  double depth = 2e-6;  // m, for --shape
  std::string out = "friction_map.csv";
};

/// The contact the sweep runs on: the columns δ map of the shape on a half-space (plate
/// z ≤ 0), the reference length R of ε, and whether the punch closed form applies.
struct SweepContact {
  Eigen::Isometry3d X_WH;  // the plate's frame, its z along n
  volume::ContactVolume cv;
  volume::DepthField field;
  double R = 0.0;  // m
  bool punch = false;
  std::string description;
};

void check(bool ok, const std::string& option, const std::string& expected) {
  if (!ok) throw InputError(option, expected);
}

geometry::TriangleMesh meshOf(const geometry::Shape& shape, const std::string& source) {
  if (const auto* m = std::get_if<geometry::Mesh>(&shape)) return *m->mesh;
  if (const auto* c = std::get_if<geometry::Cylinder>(&shape)) {
    return geometry::tessellateCylinder(c->radius, c->length, kPunchSegments);
  }
  if (const auto* b = std::get_if<geometry::Box>(&shape)) return geometry::tessellateBox(b->size);
  if (const auto* s = std::get_if<geometry::Sphere>(&shape)) {
    return geometry::tessellateSphere(s->radius, kSphereSegments, kSphereRings);
  }
  throw InputError(source, "expected a mesh file, cylinder, box or sphere to press on the plate");
}

/// The body pressed `depth` into the plate z_H ≤ 0 (its lowest vertex at z_H = −depth).
SweepContact press(geometry::TriangleMesh mesh, double depth) {
  const geometry::Aabb box = geometry::bounds(mesh);
  SweepContact c;
  c.X_WH = io::poseFromRpyDegrees(Eigen::Vector3d::Zero(), kPlateRpyDeg);
  const Eigen::Isometry3d X_WB = c.X_WH * Eigen::Translation3d(0.0, 0.0, -box.min.z() - depth);
  const geometry::Mesh body{std::make_shared<geometry::TriangleMesh>(std::move(mesh)), "payload"};
  c.cv = volume::columnsContact(body, X_WB, geometry::HalfSpace{}, c.X_WH, &c.field);
  if (!c.cv.inContact()) throw InputError("--depth", "the body does not reach the plate");
  return c;
}

SweepContact sweepContact(const FrictionMapOptions& o) {
  if (o.shape.empty()) {
    // Flat punch: depth from the load, f_n = kv π R² d (MODEL.md §5).
    const double depth = o.load / (o.kv * std::numbers::pi * o.radius * o.radius);
    SweepContact c = press(geometry::tessellateCylinder(o.radius, o.radius, kPunchSegments), depth);
    c.R = o.radius;
    c.punch = true;
    std::ostringstream s;
    s << "flat punch R = " << o.radius << " m, depth " << depth << " m";
    c.description = s.str();
    return c;
  }
  const io::ParsedShape parsed = io::parseShape(o.shape, "--shape (" + o.shape + ")");
  printWarnings(parsed.warnings);
  SweepContact c = press(meshOf(parsed.shape, "--shape (" + o.shape + ")"), o.depth);
  c.R = std::sqrt(2.0) * c.cv.r_gyr;  // the flat punch of the same r_gyr
  std::ostringstream s;
  s << geometry::describe(parsed.shape) << ", depth " << o.depth
    << " m, R = sqrt(2) r_gyr = " << c.R << " m";
  c.description = s.str();
  return c;
}

struct Row {
  double eps, v, w;                              // –, m/s, rad/s
  double fLumped, fDist, mLumped, mDist;         // N, N·m (magnitudes)
  std::optional<dynamics::PunchFriction> exact;  // F/μN, M/μNR
};

/// Slip speed v and spin ω for ε with √(v² + (ωR)²) = speed, so that neither falls far below
/// the regularisation speed v_ε at the ends of the sweep.
Row evaluate(const SweepContact& c, const dynamics::Model& lumped, const FrictionMapOptions& o,
             double eps) {
  Row r{};
  r.eps = eps;
  const double scale = std::isinf(eps) ? 0.0 : 1.0 / std::hypot(eps, 1.0);
  r.v = std::isinf(eps) ? o.speed : o.speed * eps * scale;
  r.w = o.speed * scale / c.R;
  const dynamics::RelativeMotion m{r.v * c.X_WH.linear().col(0), r.w * c.cv.normal};
  const dynamics::ContactResult l = lumped.evaluate(c.cv, m, dynamics::PairState{});
  const Eigen::Vector3d n = c.cv.normal;
  r.fLumped = (l.wrench.f_W - l.wrench.f_W.dot(n) * n).norm();
  r.mLumped = std::abs(l.wrench.tau_W.dot(n));
  const dynamics::DistributedFriction d =
      dynamics::distributedFriction(c.cv, c.field, {o.kv, 0.0}, m, o.mu, lumped.settings.v_eps);
  r.fDist = d.wrench.f_W.norm();
  r.mDist = std::abs(d.wrench.tau_W.dot(n));
  if (c.punch) r.exact = dynamics::flatPunchFriction(eps);
  return r;
}

/// a / b; NaN where the lumped value a is exactly 0 (its force in pure spin, its torque in pure
/// sliding), since the distributed one is then 0 up to the grid's asymmetry or round-off.
double ratio(double a, double b) { return a != 0.0 && b != 0.0 ? a / b : std::nan(""); }

std::vector<double> sweep(const FrictionMapOptions& o) {
  std::vector<double> eps = {0.0};
  const double decades = std::log10(o.epsMax / o.epsMin);
  const int steps = static_cast<int>(std::ceil(decades * o.perDecade - 1e-9));
  for (int i = 0; i <= steps; ++i) eps.push_back(o.epsMin * std::pow(10.0, decades * i / steps));
  eps.push_back(INFINITY);
  return eps;
}

void validate(const FrictionMapOptions& o) {
  check(std::isfinite(o.radius) && o.radius > 0.0, "--radius", "a radius > 0 in metres");
  check(std::isfinite(o.load) && o.load > 0.0, "--load", "a load > 0 in newtons");
  check(std::isfinite(o.mu) && o.mu > 0.0, "--mu", "a friction coefficient > 0");
  check(std::isfinite(o.kv) && o.kv > 0.0, "--kv", "a volumetric stiffness > 0 in N/m^3");
  check(std::isfinite(o.depth) && o.depth > 0.0, "--depth", "a depth > 0 in metres");
  check(std::isfinite(o.speed) && o.speed > 0.0, "--speed", "a speed > 0 in m/s");
  check(std::isfinite(o.epsMin) && o.epsMin > 0.0 && std::isfinite(o.epsMax) && o.epsMax > o.epsMin,
        "--eps-min/--eps-max", "0 < eps-min < eps-max, finite");
  check(o.perDecade >= 1 && std::log10(o.epsMax / o.epsMin) * o.perDecade < kMaxRows,
        "--per-decade", "at least 1, and fewer than 2000 rows in all");
}

void writeCsv(const std::string& path, const std::vector<Row>& rows, const SweepContact& c,
              const FrictionMapOptions& o) {
  std::ofstream f(path);
  if (!f) throw InputError(path, "cannot open for writing");
  f.precision(12);
  f << "eps,v_mps,omega_radps,f_n_N,F_lumped_N,F_distributed_N,F_exact_N,M_lumped_Nm,"
       "M_distributed_Nm,M_exact_Nm,F_lumped_over_distributed,M_lumped_over_distributed\n";
  const double fn = o.kv * c.cv.volume;
  for (const Row& r : rows) {
    f << r.eps << ',' << r.v << ',' << r.w << ',' << fn << ',' << r.fLumped << ',' << r.fDist
      << ',';
    if (r.exact) f << o.mu * fn * r.exact->force;
    f << ',' << r.mLumped << ',' << r.mDist << ',';
    if (r.exact) f << o.mu * fn * c.R * r.exact->torque;
    f << ',' << ratio(r.fLumped, r.fDist) << ',' << ratio(r.mLumped, r.mDist) << '\n';
  }
}

void printTable(const std::vector<Row>& rows, const SweepContact& c, const FrictionMapOptions& o) {
  const double fn = o.kv * c.cv.volume;
  std::cout << "vcontact friction-map: " << c.description << "\n  f_n = " << fn
            << " N, mu = " << o.mu << ", r_gyr = " << c.cv.r_gyr << " m, column grid error "
            << c.cv.relative_error << "\n  F in mu f_n, M in mu f_n R; ratio = lumped / "
            << "distributed\n";
  std::cout << std::setw(12) << "eps" << std::setw(10) << "F_lumped" << std::setw(10) << "F_dist"
            << std::setw(10) << "F_exact" << std::setw(9) << "F_ratio" << std::setw(10)
            << "M_lumped" << std::setw(10) << "M_dist" << std::setw(10) << "M_exact" << std::setw(9)
            << "M_ratio" << '\n';
  std::cout << std::fixed;
  for (const Row& r : rows) {
    const double F = o.mu * fn, M = F * c.R;
    std::cout << std::setprecision(5) << std::scientific << std::setw(12) << r.eps << std::fixed
              << std::setw(10) << r.fLumped / F << std::setw(10) << r.fDist / F << std::setw(10)
              << (r.exact ? r.exact->force : std::nan("")) << std::setw(9)
              << ratio(r.fLumped, r.fDist) << std::setw(10) << r.mLumped / M << std::setw(10)
              << r.mDist / M << std::setw(10) << (r.exact ? r.exact->torque : std::nan(""))
              << std::setw(9) << ratio(r.mLumped, r.mDist) << '\n';
  }
}

void runFrictionMap(const FrictionMapOptions& o) {
  validate(o);
  const SweepContact c = sweepContact(o);
  dynamics::Model lumped =
      dynamics::Model::withEffects({"stiffness", "coulomb", "spin", "contensou"});
  lumped.setParameter("stiffness.kv", o.kv);
  lumped.setParameter("coulomb.mu", o.mu);
  std::vector<Row> rows;
  for (double eps : sweep(o)) rows.push_back(evaluate(c, lumped, o, eps));
  writeCsv(o.out, rows, c, o);
  printTable(rows, c, o);
  std::cout << "wrote " << o.out << '\n';
}

}  // namespace

void addFrictionMapCommand(CLI::App& app) {
  auto o = std::make_shared<FrictionMapOptions>();
  CLI::App* cmd = app.add_subcommand(
      "friction-map",
      "Where the lumped friction fails: sweep eps = v/(omega R) over decades for a body sliding "
      "at v and spinning at omega on a plate, and compare the lumped Coulomb + spin + "
      "contensou friction (MODEL.md section 3) with pointwise Coulomb friction integrated over "
      "the column method's penetration map and, for the flat punch, with the closed form "
      "(dynamics/DISTRIBUTED_FRICTION.md). Writes a CSV (forces in N, torques in N m about the "
      "centroid; rows eps = 0 and inf are pure spin and pure sliding) and prints the table "
      "normalised by mu f_n and mu f_n R. Expect the lumped spin torque 1.06x the exact one at "
      "pure spin and 2x as sliding dominates, the lumped force sqrt(2)x while spin dominates.");
  cmd->add_option("--radius", o->radius, "flat punch radius, m")->capture_default_str();
  cmd->add_option("--load", o->load, "normal load on the punch, N")->capture_default_str();
  cmd->add_option("--mu", o->mu, "Coulomb friction coefficient")->capture_default_str();
  cmd->add_option("--kv", o->kv, "volumetric stiffness, N/m^3")->capture_default_str();
  cmd->add_option("--eps-min", o->epsMin, "smallest eps > 0 of the sweep")->capture_default_str();
  cmd->add_option("--eps-max", o->epsMax, "largest eps of the sweep")->capture_default_str();
  cmd->add_option("--per-decade", o->perDecade, "sweep points per decade of eps")
      ->capture_default_str();
  cmd->add_option("--speed", o->speed,
                  "combined slip speed sqrt(v^2 + (omega R)^2), m/s (far above v_eps = 1e-5)")
      ->capture_default_str();
  cmd->add_option("--shape", o->shape,
                  "instead of the punch: a shape (mesh file, cylinder:R,L, box:X,Y,Z, sphere:R) "
                  "pressed --depth into the plate in its own orientation; R = sqrt(2) r_gyr and "
                  "no closed form");
  cmd->add_option("--depth", o->depth, "penetration of --shape, m")->capture_default_str();
  cmd->add_option("--out", o->out, "CSV file to write")->capture_default_str();
  cmd->callback([o] { runFrictionMap(*o); });
}

}  // namespace vcontact::cli
