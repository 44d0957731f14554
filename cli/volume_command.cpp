#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"
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
};

/// The contact by the chosen method; with --field, the column method and its δ map.
volume::ContactVolume compute(const VolumeOptions& o, const io::ParsedShape& a,
                              const Eigen::Isometry3d& X_WA, const io::ParsedShape& b,
                              const Eigen::Isometry3d& X_WB) {
  std::optional<volume::Method> method;
  if (!o.method.empty()) method = volume::parseMethod(o.method);
  if (o.field.empty()) return volume::computeContact(a.shape, X_WA, b.shape, X_WB, method);
  if (method && *method != volume::Method::kColumns) {
    throw InputError("--field", "the δ map comes from the column method; use --method columns");
  }
  volume::ColumnField field;
  const volume::ContactVolume cv = volume::columnsContact(a.shape, X_WA, b.shape, X_WB, &field);
  io::writeDepthMapCsv(field, o.field);
  return cv;
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
  const volume::ContactVolume cv = compute(o, a, X_WA, b, X_WB);

  nlohmann::json j = io::toJson(cv);
  j["a"] = {{"shape", geometry::describe(a.shape)}, {"pose", o.poseA}};
  j["b"] = {{"shape", geometry::describe(b.shape)}, {"pose", o.poseB}};
  if (!o.out.empty()) io::writeJson(j, o.out);
  if (o.json) {
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << "A: " << geometry::describe(a.shape) << " at " << o.poseA << '\n'
              << "B: " << geometry::describe(b.shape) << " at " << o.poseB << '\n'
              << io::toTable(cv);
  }
}

}  // namespace

void addVolumeCommand(CLI::App& app) {
  auto opts = std::make_shared<VolumeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "volume",
      "Interference of body A (payload, B1) with body B (plate, B2): volume, centroid, "
      "normal (out of B into A), inertia tensors J_v and J_s, area, r_gyr.");
  cmd->add_option("A", opts->a, "shape of body A")->required();
  cmd->add_option("B", opts->b, "shape of body B")->required();
  cmd->add_option("--pose-a", opts->poseA, "pose of A in the world")->capture_default_str();
  cmd->add_option("--pose-b", opts->poseB, "pose of B in the world")->capture_default_str();
  cmd->add_option("--method", opts->method,
                  "analytic | halfspace | cgal | fast | columns (default: the best the pair "
                  "allows: analytic for a primitive on a half-space, halfspace for a mesh on a "
                  "half-space, fast (exact local surface integration) for two meshes)");
  cmd->add_option("--field", opts->field,
                  "write the penetration-depth map of the column method to this CSV");
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->add_flag("--repair", opts->repair, "repair mesh files first (as mesh-repair does)");
  cmd->add_option("--out", opts->out, "also write the JSON to this file");
  cmd->callback([opts] { runVolume(*opts); });
}

}  // namespace vcontact::cli
