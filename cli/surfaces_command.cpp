// `vcontact surfaces MESH`: the analytic surfaces a mesh was tessellated from
// (docs/SURFACES.md), and the recovered-surface contact `volume --surface recovered` uses.

#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "geometry/surface_recognition.hpp"
#include "io/json_file.hpp"
#include "io/shape_spec.hpp"
#include "volume/recovered_surface.hpp"

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

void runSurfaces(const SurfacesOptions& o) {
  const io::ParsedShape parsed = io::parseShape(o.mesh, "MESH (" + o.mesh + ")");
  printWarnings(parsed.warnings);
  const auto* mesh = std::get_if<geometry::Mesh>(&parsed.shape);
  if (!mesh) throw InputError("MESH (" + o.mesh + ")", "expected a mesh file, not a primitive");
  geometry::RecognitionOptions options;
  options.tolerance = o.tolerance;
  geometry::SurfaceRecognition r;
  try {
    r = geometry::recogniseSurfaces(*mesh->mesh, options);
  } catch (const InputError& e) {
    throw e.withSource(o.mesh);
  }
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
