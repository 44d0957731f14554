#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <variant>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/tessellate.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "io/mesh_io.hpp"
#include "io/output_folder.hpp"
#include "io/shape_spec.hpp"

namespace vcontact::cli {
namespace {

struct MeshInfoOptions {
  std::string shape;
  double density = 7900.0;
  bool repair = false;
  bool fillHoles = false;
  bool removeSelfIntersections = false;
  bool json = false;
};

io::MeshReadOptions meshReadOptions(bool repair, bool fillHoles, bool removeSelfIntersections) {
  io::MeshReadOptions options;
  options.repair = repair || fillHoles || removeSelfIntersections;
  options.repairOptions.fillHoles = fillHoles;
  options.repairOptions.removeSelfIntersections = removeSelfIntersections;
  return options;
}

std::vector<std::string> densityWarnings(const io::ParsedShape& s, double density) {
  std::vector<std::string> out;
  if (!(density > 0.0)) {
    std::ostringstream os;
    os << "density is " << density << " kg/m^3: the mass and inertia below are zero or negative";
    out.push_back(os.str());
  }
  if (const auto* m = std::get_if<geometry::Mesh>(&s.shape)) {
    if (auto w = io::lightPartWarning(*m->mesh, density)) out.push_back(m->name + ": " + *w);
  }
  return out;
}

nlohmann::json row(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json meshInfoJson(const io::ParsedShape& s, const geometry::MassProperties& p,
                            double volume, double density,
                            const std::vector<std::string>& warnings) {
  nlohmann::json j = {
      {"ok", true},
      {"shape", geometry::describe(s.shape)},
      {"watertight", true},
      {"shells", 1},
      {"repairs", nlohmann::json::array()},
      {"warnings", warnings},
      {"volume", volume},
      {"centroid", row(p.com)},
      {"density", density},
      {"mass", p.mass},
      {"inertia_com", {row(p.inertia.row(0)), row(p.inertia.row(1)), row(p.inertia.row(2))}}};
  if (const auto* m = std::get_if<geometry::Mesh>(&s.shape)) {
    const geometry::Aabb box = geometry::bounds(*m->mesh);
    j["file"] = m->name;
    j["precision"] = s.mesh.precision;
    j["vertices"] = m->mesh->vertexCount();
    j["triangles"] = m->mesh->triangleCount();
    j["bounds"] = {row(box.min), row(box.max)};
    j["shells"] = s.mesh.shells;
    j["repairs"] = s.mesh.repairs;
  }
  return j;
}

void printMeshInfo(const io::ParsedShape& s, const geometry::MassProperties& p, double volume,
                   double density) {
  std::cout.precision(10);
  std::cout << geometry::describe(s.shape) << "\n";
  if (const auto* m = std::get_if<geometry::Mesh>(&s.shape)) {
    const geometry::Aabb box = geometry::bounds(*m->mesh);
    std::cout << "  vertices       " << m->mesh->vertexCount() << "\n"
              << "  triangles      " << m->mesh->triangleCount() << "\n"
              << "  bounds         (" << box.min.transpose() << ") .. (" << box.max.transpose()
              << ")  m\n"
              << "  checks         closed, consistently oriented, outward, no degenerate faces\n"
              << "  shells         " << s.mesh.shells << "\n"
              << "  precision      " << s.mesh.precision << "\n"
              << "  repairs        " << s.mesh.repairs.size() << "\n";
  }
  std::cout << "  volume         " << volume << "  m^3\n"
            << "  centroid       (" << p.com.transpose() << ")  m\n"
            << "  density        " << density << "  kg/m^3\n"
            << "  mass           " << p.mass << "  kg\n"
            << "  inertia (com)  " << p.inertia.row(0) << "\n"
            << "                 " << p.inertia.row(1) << "\n"
            << "                 " << p.inertia.row(2) << "  kg m^2\n";
}

void runMeshInfo(const MeshInfoOptions& o) {
  // 0 asks for the volume alone (warned below); any other density is a material's.
  if (o.density != 0.0) {
    const std::string why = io::outOfRange(o.density, io::kDensityRange, "a density");
    if (!why.empty()) throw InputError("--density", why + " (or 0 for the volume alone)");
  }
  const io::ParsedShape s = io::parseShape(
      o.shape, o.shape, meshReadOptions(o.repair, o.fillHoles, o.removeSelfIntersections));
  std::vector<std::string> warnings = s.warnings;
  const auto more = densityWarnings(s, o.density);
  warnings.insert(warnings.end(), more.begin(), more.end());
  printWarnings(warnings);
  const geometry::Moments M = geometry::solidMoments(s.shape);
  const geometry::MassProperties p = geometry::massProperties(M, o.density);
  if (o.json) {
    std::cout << io::jsonText(meshInfoJson(s, p, M.m0, o.density, warnings)) << "\n";
  } else {
    printMeshInfo(s, p, M.m0, o.density);
  }
}

/// With --json, every failure is bad input (exit 2) and is also printed as JSON on stdout.
void runMeshInfoJson(const MeshInfoOptions& o) {
  try {
    runMeshInfo(o);
  } catch (const std::exception& e) {
    std::cout << io::jsonText(nlohmann::json{{"ok", false}, {"error", e.what()}}) << "\n";
    if (const auto* input = dynamic_cast<const InputError*>(&e)) throw *input;
    throw InputError(o.shape, e.what());
  }
}

// Largest --weld-tolerance, a fraction of the bounding-box diagonal. Coordinates printed with
// 4 significant digits (a coarse ASCII export) are within 5e-5 of their magnitude, well inside
// it; a thousandth of the part is the size of a chamfer or a thin wall, and welding more
// closes real features (0.3 halves a sphere).
constexpr double kMaxWeldTolerance = 1e-3;

struct MeshRepairOptions {
  std::string in, out;
  bool fillHoles = false;
  bool removeSelfIntersections = false;
  double weldTolerance = geometry::kDefaultWeldTolerance;
};

void runMeshRepair(const MeshRepairOptions& o) {
  if (!(o.weldTolerance >= 0.0 && o.weldTolerance <= kMaxWeldTolerance)) {
    std::ostringstream s;
    s << "expected a fraction of the bounding-box diagonal in [0, " << kMaxWeldTolerance
      << "], got " << o.weldTolerance
      << " (a larger weld closes real features: 0.3 halves a sphere)";
    throw InputError("--weld-tolerance", s.str());
  }
  io::MeshReadOptions options = meshReadOptions(true, o.fillHoles, o.removeSelfIntersections);
  options.repairOptions.weldTolerance = o.weldTolerance;
  const auto [path, scale] = io::splitMeshScale(o.in);
  io::refuseOverwritingInputs({o.out}, {{path, "the mesh to repair"}}, "--out");
  const io::MeshReadResult r = io::readMesh(path, scale, options);
  for (const auto& change : r.report.repairs) std::cout << "repaired: " << change << "\n";
  if (r.report.repairs.empty()) std::cout << "no repair needed\n";
  for (const auto& doubt : r.report.doubts) printWarnings({path + ": " + doubt});
  io::writeMesh(r.mesh, o.out);
  std::cout << "wrote " << o.out << ": " << r.mesh.vertexCount() << " vertices, "
            << r.mesh.triangleCount() << " triangles, " << r.report.shells
            << (r.report.shells == 1 ? " shell" : " shells") << ", volume "
            << geometry::meshMoments(r.mesh).m0 << " m^3\n";
}

/// The most triangles `tessellate` writes: 10 million make a 500 MB binary STL and about 1 GB
/// in memory while built, far beyond what a contact query needs (faceting error, README).
constexpr std::int64_t kMaxTessellationTriangles = 10'000'000;

// Refuses a tessellation beyond kMaxTessellationTriangles before any memory is taken, with
// the count: 2 · segments · (rings − 1) for a sphere, 4 · segments for a cylinder.
void checkTriangleCount(const geometry::Shape& shape, int segments, int rings) {
  std::int64_t triangles = 12;  // a box
  if (std::holds_alternative<geometry::Sphere>(shape)) {
    triangles = 2 * std::int64_t{segments} * (std::int64_t{rings} - 1);
  } else if (std::holds_alternative<geometry::Cylinder>(shape)) {
    triangles = 4 * std::int64_t{segments};
  }
  if (triangles <= kMaxTessellationTriangles) return;
  throw InputError("--segments/--rings", "the mesh would have " + std::to_string(triangles) +
                                             " triangles, more than the limit of " +
                                             std::to_string(kMaxTessellationTriangles));
}

struct TessellateOptions {
  std::string shape, out;
  int segments = 64;
  int rings = 32;
};

void runTessellate(const TessellateOptions& o) {
  if (o.segments < 3 || o.rings < 2) {
    throw InputError("--segments/--rings", "need at least 3 segments and 2 rings");
  }
  const io::ParsedShape s = io::parseShape(o.shape, o.shape);
  checkTriangleCount(s.shape, o.segments, o.rings);
  geometry::TriangleMesh mesh;
  if (const auto* sp = std::get_if<geometry::Sphere>(&s.shape)) {
    mesh = geometry::tessellateSphere(sp->radius, o.segments, o.rings);
  } else if (const auto* c = std::get_if<geometry::Cylinder>(&s.shape)) {
    mesh = geometry::tessellateCylinder(c->radius, c->length, o.segments);
  } else if (const auto* b = std::get_if<geometry::Box>(&s.shape)) {
    mesh = geometry::tessellateBox(b->size);
  } else {
    throw InputError(o.shape, "only a sphere, cylinder or box can be tessellated");
  }
  io::writeMesh(mesh, o.out);
  std::cout << "wrote " << o.out << ": " << mesh.triangleCount() << " triangles, volume "
            << geometry::meshMoments(mesh).m0 << " m^3\n";
}

}  // namespace

void addMeshInfoCommand(CLI::App& app) {
  auto opts = std::make_shared<MeshInfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-info", "Check a shape or mesh file and print its volume, centre of mass and inertia.");
  cmd->add_option("SHAPE", opts->shape, "shape or mesh file")->required();
  cmd->add_option("--density", opts->density, "kg/m^3")->capture_default_str();
  cmd->add_flag("--repair", opts->repair, "repair the mesh first (as mesh-repair does)");
  cmd->add_flag("--fill-holes", opts->fillHoles, "repair, and fill small holes");
  cmd->add_flag("--remove-self-intersections", opts->removeSelfIntersections,
                "repair, and cut a surface that passes through itself along the intersections, "
                "keeping the outer layer");
  cmd->add_flag("--json", opts->json,
                "print JSON (also on failure, with \"ok\": false; exit 2 for bad input)");
  cmd->callback([opts] { opts->json ? runMeshInfoJson(*opts) : runMeshInfo(*opts); });
}

void addMeshRepairCommand(CLI::App& app) {
  auto opts = std::make_shared<MeshRepairOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-repair",
      "Repair a mesh file (weld seams, drop zero-area and duplicate faces, orient, optionally "
      "fill small holes), print each change and write the result in metres.");
  cmd->add_option("IN", opts->in, "mesh file, MESHFILE[@SCALE]")->required();
  cmd->add_option("--out", opts->out, "output file (.obj full precision, or binary .stl)")
      ->required();
  cmd->add_flag("--fill-holes", opts->fillHoles,
                "fill holes shorter around than half the part's diagonal");
  cmd->add_flag("--remove-self-intersections", opts->removeSelfIntersections,
                "cut a surface that passes through itself along the intersections and keep the "
                "outer layer (CGAL's autorefinement)");
  cmd->add_option("--weld-tolerance", opts->weldTolerance,
                  "weld vertices closer than this fraction of the bounding-box diagonal, at "
                  "most 1e-3 (a thousandth of the part is a chamfer; more closes real features)")
      ->capture_default_str();
  cmd->callback([opts] { runMeshRepair(*opts); });
}

void addTessellateCommand(CLI::App& app) {
  auto opts = std::make_shared<TessellateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tessellate", "Write a triangle mesh of a sphere, cylinder or box (binary STL, or OBJ).");
  cmd->add_option("SHAPE", opts->shape, "sphere:R | cylinder:R,L | box:X,Y,Z")->required();
  cmd->add_option("--out", opts->out, "output file (.stl or .obj)")->required();
  cmd->add_option("--segments", opts->segments, "segments around the axis")->capture_default_str();
  cmd->add_option("--rings", opts->rings, "rings pole to pole (sphere)")->capture_default_str();
  cmd->callback([opts] { runTessellate(*opts); });
}

}  // namespace vcontact::cli
