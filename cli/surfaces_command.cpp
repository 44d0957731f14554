// `vcontact surfaces MESH`: the analytic surfaces a mesh was tessellated from
// (docs/SURFACES.md), and the recovered-surface contact `volume --surface recovered` uses.

#include <chrono>
#include <condition_variable>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "geometry/surface_recognition.hpp"
#include "io/json_file.hpp"
#include "io/progress.hpp"
#include "io/shape_spec.hpp"
#include "volume/contact.hpp"

namespace vcontact::cli {
namespace {

struct SurfacesOptions {
  std::string mesh;
  double tolerance = geometry::RecognitionOptions{}.tolerance;
  bool json = false;
  std::string out;
};

nlohmann::json vectorJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json surfaceJson(const geometry::RecognisedSurface& s) {
  nlohmann::json j = {{"kind", geometry::surfaceKindName(s.kind)},
                      {"convex", s.convex},
                      {"faces", s.faces.size()},
                      {"area_m2", s.area},
                      {"rms_residual_m", s.rms_residual},
                      {"max_residual_m", s.max_residual}};
  switch (s.kind) {
    case geometry::SurfaceKind::kPlane:
      j["point_m"] = vectorJson(s.point);
      j["normal"] = vectorJson(s.axis);
      break;
    case geometry::SurfaceKind::kSphere:
      j["centre_m"] = vectorJson(s.point);
      j["radius_m"] = s.radius;
      break;
    case geometry::SurfaceKind::kCylinder:
      j["axis_point_m"] = vectorJson(s.point);
      j["axis"] = vectorJson(s.axis);
      j["radius_m"] = s.radius;
      break;
    case geometry::SurfaceKind::kCone:
      j["apex_m"] = vectorJson(s.point);
      j["axis"] = vectorJson(s.axis);
      j["half_angle_rad"] = s.angle;
      break;
    case geometry::SurfaceKind::kTorus:
      j["centre_m"] = vectorJson(s.point);
      j["axis"] = vectorJson(s.axis);
      j["major_radius_m"] = s.radius;
      j["minor_radius_m"] = s.minor_radius;
      break;
  }
  return j;
}

// A line on a terminal naming the stage and the seconds it has taken, rewritten every
// io::Progress::kProgressIntervalS (io/progress.hpp: a terminal, CI unset): reading and
// recognising a 2M-triangle mesh take about a minute, and neither reports an amount done.
class StageTicker {
 public:
  explicit StageTicker(std::string stage) : stage_(std::move(stage)) {
    if (io::progressWanted()) thread_ = std::thread([this] { tick(); });
  }
  ~StageTicker() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  StageTicker(const StageTicker&) = delete;
  StageTicker& operator=(const StageTicker&) = delete;

  void stage(std::string name) {
    const std::lock_guard<std::mutex> lock(mutex_);
    stage_ = std::move(name);
    start_ = std::chrono::steady_clock::now();
  }

 private:
  void tick() {
    io::Progress progress("surfaces", 0.0, "");
    const auto interval = std::chrono::duration<double>(io::Progress::kProgressIntervalS);
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, interval, [this] { return done_; })) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      progress.update(
          "surfaces: " + stage_ + " (" + std::to_string(static_cast<int>(seconds)) + " s)", 0.0,
          0.0);
    }
  }

  std::string stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  bool done_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

void runSurfaces(const SurfacesOptions& o) {
  std::optional<StageTicker> ticker(std::in_place, "reading " + o.mesh);
  const io::ParsedShape parsed = io::parseShape(o.mesh, "MESH (" + o.mesh + ")");
  printWarnings(parsed.warnings);
  const auto* mesh = std::get_if<geometry::Mesh>(&parsed.shape);
  if (!mesh) throw InputError("MESH (" + o.mesh + ")", "expected a mesh file, not a primitive");
  ticker->stage("recognising the surfaces of " + std::to_string(mesh->mesh->triangleCount()) +
                " triangles");
  geometry::RecognitionOptions options;
  options.tolerance = o.tolerance;
  geometry::SurfaceRecognition r;
  try {
    r = geometry::recogniseSurfaces(*mesh->mesh, options);
  } catch (const InputError& e) {
    throw e.withSource(o.mesh);
  }
  ticker.reset();  // its line ends before the table
  nlohmann::json j = {{"mesh", o.mesh},
                      {"triangles", mesh->mesh->triangleCount()},
                      {"tolerance_m", r.tolerance},
                      {"free_form_faces", r.free_form_faces},
                      {"free_form_area_m2", r.free_form_area},
                      {"surfaces", nlohmann::json::array()}};
  for (const geometry::RecognisedSurface& s : r.surfaces) j["surfaces"].push_back(surfaceJson(s));
  if (!o.out.empty()) io::writeJson(j, o.out);
  if (o.json) {
    std::cout << io::jsonText(j) << '\n';
    return;
  }
  std::cout << o.mesh << ": " << mesh->mesh->triangleCount() << " triangles, " << r.surfaces.size()
            << " surfaces (vertex tolerance " << r.tolerance << " m)\n";
  for (const geometry::RecognisedSurface& s : r.surfaces) std::cout << "  " << describe(s) << '\n';
  std::cout << "  free-form: " << r.free_form_faces << " faces, area " << r.free_form_area
            << " m^2\n";
}

}  // namespace

void addSurfacesCommand(CLI::App& app) {
  auto opts = std::make_shared<SurfacesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "surfaces",
      "Recognise the planes, spheres, cylinders, cones and tori a mesh was tessellated from "
      "(docs/SURFACES.md): kind, parameters, faces, area and fit residual of each.");
  cmd->add_option("MESH", opts->mesh, "mesh file, MESHFILE[@SCALE]")->required();
  cmd->add_option("--tolerance", opts->tolerance,
                  "a vertex lies on a surface within this fraction of the bounding-box diagonal")
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->add_option("--out", opts->out, "also write the JSON to this file");
  cmd->callback([opts] { runSurfaces(*opts); });
}

}  // namespace vcontact::cli
