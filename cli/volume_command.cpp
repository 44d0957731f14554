#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "io/output_file.hpp"
#include "io/shape_spec.hpp"
#include "report/contact_volume_format.hpp"
#include "report/depth_map_csv.hpp"
#include "volume/contact.hpp"

namespace vcontact::cli {

void printWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "vcontact: warning: " << w << '\n';
}

namespace {

struct VolumeOptions {
  std::string a, b;
  std::string poseA = "0,0,0", poseB = "0,0,0";
  std::string method;
  bool json = false;
  bool repair = false;
  std::string out;
  std::string field;
  std::string surface = "mesh";
};

/// The table's methods whose `pick` is true, as "a | b | c".
template <class Pick>
std::string methodNames(Pick pick) {
  std::string names;
  for (const volume::MethodDescription& row : volume::describeMethods()) {
    if (pick(row)) names += (names.empty() ? "" : " | ") + std::string(row.name);
  }
  return names;
}

/// --method as a method that takes the pair, or none; its errors are reported against --method.
std::optional<volume::Method> chosenMethod(const VolumeOptions& o, const io::ParsedShape& a,
                                           const io::ParsedShape& b) {
  if (o.method.empty()) return std::nullopt;
  try {
    const volume::Method method = volume::parseMethod(o.method);
    volume::requireHandles(method, a.shape, b.shape);
    return method;
  } catch (const InputError& e) {
    throw e.withSource("--method " + o.method);
  }
}

/// The contact by the chosen method; with --field, by a method that samples the δ map (by
/// default the first the pair allows) and the map in `field`. The table and --json print the
/// depth, so the query asks for it (DepthMode::kDeepest: for `fast`, a few milliseconds at
/// most, next to reading and checking the meshes).
volume::ContactPatches compute(const VolumeOptions& o, const io::ParsedShape& a,
                               const Eigen::Isometry3d& X_WA, const io::ParsedShape& b,
                               const Eigen::Isometry3d& X_WB, volume::DepthField& field) {
  const volume::QueryOptions query{chosenMethod(o, a, b), 0, volume::DepthMode::kDeepest};
  if (o.field.empty()) return volume::computeContact(a.shape, X_WA, b.shape, X_WB, query);
  if (query.method && !volume::fillsDepthField(*query.method)) {
    throw InputError("--field",
                     "the δ map comes from a method that samples it; use --method " +
                         methodNames([](const auto& row) { return row.fills_depth_field; }));
  }
  return volume::computeContact(a.shape, X_WA, b.shape, X_WB, query, &field);
}

/// --method's help, from the method table.
std::string methodHelp() {
  std::string help = methodNames([](const auto&) { return true; }) + " (default: the first of " +
                     methodNames([](const auto& row) { return row.is_default; }) +
                     " that takes the pair). Per method:";
  for (const volume::MethodDescription& row : volume::describeMethods()) {
    help += "\n  " + std::string(row.name) + ": " + std::string(row.scope) + "; " +
            (row.exact ? "exact" : "approximate") + ", relative_error " +
            std::string(row.error_estimate);
  }
  return help;
}

/// --surface recovered: the method table's `recovered` row, refining where no closed form
/// applies (QueryOptions::refine), with the depth (the table and --json show it).
volume::ContactPatches recoveredContact(const VolumeOptions& o, const io::ParsedShape& a,
                                        const Eigen::Isometry3d& X_WA, const io::ParsedShape& b,
                                        const Eigen::Isometry3d& X_WB) {
  if (!volume::handles(volume::Method::kRecovered, a.shape, b.shape) || !o.method.empty() ||
      !o.field.empty()) {
    throw InputError("--surface recovered",
                     "takes a mesh and a half-space, or two meshes, without --method or --field");
  }
  volume::QueryOptions query{volume::Method::kRecovered, 0, volume::DepthMode::kDeepest};
  query.refine = true;
  try {
    return volume::computeContact(a.shape, X_WA, b.shape, X_WB, query);
  } catch (const InputError& e) {  // recognition refused a mesh
    throw e.withSource("--surface recovered");
  }
}

/// "refined" when any part of the body was refined, else "mesh" (its faces as they are).
std::string bodyRepresentation(const volume::SurfaceUse& r, const std::string& body) {
  for (const volume::PatchPart& p : r.parts)
    if (p.body == body && p.representation == "refined") return "refined";
  return "mesh";
}

nlohmann::json recoveredJson(const volume::SurfaceUse& r) {
  nlohmann::json j = {{"representation", volume::representationName(r.representation)},
                      {"volume_error_bound_m3", r.volume_error_bound}};
  if (!r.reason.empty()) j["reason"] = r.reason;
  if (r.representation == volume::Representation::kRefined || !r.parts.empty()) {
    j["level"] = r.level;
    j["converged"] = r.converged;
    j["bodies"] = {{"a", bodyRepresentation(r, "A")}, {"b", bodyRepresentation(r, "B")}};
    nlohmann::json parts = nlohmann::json::array();
    for (const volume::PatchPart& p : r.parts)
      parts.push_back({{"body", p.body},
                       {"surface", p.surface},
                       {"faces", p.faces},
                       {"representation", p.representation}});
    j["parts"] = parts;
  }
  return j;
}

void printRecovered(const volume::SurfaceUse& r) {
  std::cout << "surface: " << volume::representationName(r.representation)
            << (r.reason.empty() ? "" : " (" + r.reason + ")")
            << ", |V error| <= " << r.volume_error_bound << " m^3\n";
  if (r.parts.empty()) return;
  std::cout << "  refinement level " << r.level << (r.converged ? "" : " (level cap reached)")
            << "; A: " << bodyRepresentation(r, "A") << ", B: " << bodyRepresentation(r, "B")
            << '\n';
  for (const volume::PatchPart& p : r.parts)
    std::cout << "  " << p.body << ": " << p.surface << ", " << p.faces << " faces, "
              << p.representation << '\n';
}

void runVolume(const VolumeOptions& o) {
  io::MeshReadOptions mesh;
  mesh.repair = o.repair;
  const io::ParsedShape a = io::parseShape(o.a, "A (" + o.a + ")", mesh);
  const io::ParsedShape b = io::parseShape(o.b, "B (" + o.b + ")", mesh);
  printWarnings(a.warnings);
  printWarnings(b.warnings);
  const Eigen::Isometry3d X_WA = io::parsePose(o.poseA, "--pose-a");
  const Eigen::Isometry3d X_WB = io::parsePose(o.poseB, "--pose-b");
  volume::DepthField field;
  const bool recovered = o.surface == "recovered";
  const volume::ContactPatches contact =
      recovered ? recoveredContact(o, a, X_WA, b, X_WB) : compute(o, a, X_WA, b, X_WB, field);

  nlohmann::json j = report::toJson(contact);
  if (recovered) j["surface"] = recoveredJson(contact.surface);
  j["a"] = {{"shape", geometry::describe(a.shape)}, {"pose", o.poseA}};
  j["b"] = {{"shape", geometry::describe(b.shape)}, {"pose", o.poseB}};
  io::OutputSet files;  // --field and --out: both files or neither
  if (!o.field.empty()) {
    files.add(o.field, [&](std::ostream& out) { report::putDepthMapCsv(field, out); });
  }
  if (!o.out.empty()) files.add(o.out, [&](std::ostream& out) { io::putJson(j, out); });
  files.commit();
  if (o.json) {
    std::cout << io::jsonText(j) << '\n';
  } else {
    std::cout << "A: " << geometry::describe(a.shape) << " at " << o.poseA << '\n'
              << "B: " << geometry::describe(b.shape) << " at " << o.poseB << '\n'
              << report::toTable(contact);
    if (recovered) printRecovered(contact.surface);
  }
}

}  // namespace

void addVolumeCommand(CLI::App& app) {
  auto opts = std::make_shared<VolumeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "volume",
      "Interference of body A (payload, B1) with body B (plate, B2): volume, centroid, "
      "normal (out of B into A), inertia tensors J_v and J_s, area, r_gyr, depth (the deepest "
      "column, MODEL.md §1).");
  cmd->add_option("A", opts->a, "shape of body A")->required();
  cmd->add_option("B", opts->b, "shape of body B")->required();
  cmd->add_option("--pose-a", opts->poseA, "pose of A in the world")->capture_default_str();
  cmd->add_option("--pose-b", opts->poseB, "pose of B in the world")->capture_default_str();
  cmd->add_option("--method", opts->method, methodHelp());
  cmd->add_option("--field", opts->field,
                  "write the penetration-depth map to this CSV (" +
                      methodNames([](const auto& row) { return row.fills_depth_field; }) +
                      ", the first that takes the pair unless --method says)");
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->add_option("--surface", opts->surface,
                  "mesh: the polyhedron; recovered: the method `recovered`, a mesh on its "
                  "recognised surfaces against a half-space or another mesh (closed forms for a "
                  "sphere, capped cylinder or solid of revolution on a plane and a solid of "
                  "revolution in a bore, else local refinement; docs/SURFACES.md)")
      ->check(CLI::IsMember({"mesh", "recovered"}))
      ->capture_default_str();
  cmd->add_flag("--repair", opts->repair, "repair mesh files first (as mesh-repair does)");
  cmd->add_option("--out", opts->out, "also write the JSON to this file");
  cmd->callback([opts] { runVolume(*opts); });
}

}  // namespace vcontact::cli
