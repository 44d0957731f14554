#include "io/shape_json.hpp"

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <variant>

#include "geometry/error.hpp"
#include "io/mesh_io.hpp"
#include "io/shape_spec.hpp"

namespace vcontact::io {

double requireNumber(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where, "missing \"" + key + "\"");
  const auto& v = j.at(key);
  if (!v.is_number()) throw InputError(where, "\"" + key + "\" must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(where, "\"" + key + "\" is not finite");
  return x;
}

namespace {

// "scale": a number, or a unit name ("mm").
double meshScale(const nlohmann::json& j, const std::string& where) {
  if (!j.contains("scale")) return 1.0;
  if (!j.at("scale").is_string()) return requireNumber(j, "scale", where);
  const auto unit = unitScale(j.at("scale").get<std::string>());
  if (!unit) {
    throw InputError(where, "\"scale\" must be a number or one of m, cm, mm, um, in, ft, got " +
                                j.at("scale").dump());
  }
  return *unit;
}

MeshReadOptions meshReadOptions(const nlohmann::json& j, const std::string& where) {
  MeshReadOptions options;
  if (!j.contains("repair")) return options;
  if (!j.at("repair").is_boolean()) throw InputError(where, "\"repair\" must be true or false");
  options.repair = j.at("repair").get<bool>();
  return options;
}

}  // namespace

JsonShape parseShapeJson(const nlohmann::json& j, const std::string& where,
                         const std::string& baseDir) {
  if (!j.is_object()) throw InputError(where, "a shape must be a JSON object, got " + j.dump());
  JsonShape out;
  if (j.contains("mesh")) {
    if (!j.at("mesh").is_string()) throw InputError(where, "\"mesh\" must be a file name");
    std::filesystem::path path = j.at("mesh").get<std::string>();
    if (path.is_relative()) path = std::filesystem::path(baseDir) / path;
    const double scale = meshScale(j, where);
    const MeshReadOptions options = meshReadOptions(j, where);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {  // named by the field, not only by its path
      throw InputError(where, "\"mesh\": \"" + j.at("mesh").get<std::string>() +
                                  "\": no such file (looked for " + path.string() + ")");
    }
    auto read = readMesh(path.string(), scale, options);
    out.warnings = std::move(read.warnings);
    out.shape = geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(std::move(read.mesh)),
                               path.string()};
    return out;
  }
  if (!j.contains("shape") || !j.at("shape").is_string()) {
    throw InputError(where, "expected \"shape\" (sphere, cylinder, box, halfspace) or \"mesh\"");
  }
  const std::string kind = j.at("shape").get<std::string>();
  if (kind == "sphere") {
    out.shape = geometry::Sphere{requireNumber(j, "radius", where)};
  } else if (kind == "cylinder") {
    out.shape =
        geometry::Cylinder{requireNumber(j, "radius", where), requireNumber(j, "length", where)};
  } else if (kind == "box") {
    const auto& s = j.contains("size") ? j.at("size") : nlohmann::json();
    if (!s.is_array() || s.size() != 3 || !s[0].is_number() || !s[1].is_number() ||
        !s[2].is_number()) {
      throw InputError(where, "a box needs \"size\": [x, y, z] in metres");
    }
    out.shape =
        geometry::Box{Eigen::Vector3d(s[0].get<double>(), s[1].get<double>(), s[2].get<double>())};
  } else if (kind == "halfspace") {
    out.shape = geometry::HalfSpace{};
  } else {
    throw InputError(where, "unknown shape \"" + kind +
                                "\"; expected sphere, cylinder, box, halfspace, or a \"mesh\"");
  }
  geometry::validate(out.shape, where);
  checkShapeLengths(out.shape, where);
  return out;
}

nlohmann::json shapeJson(const geometry::Shape& shape, const std::string& which) {
  return std::visit(
      [&](const auto& s) -> nlohmann::json {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, geometry::Sphere>) {
          return {{"shape", "sphere"}, {"radius", s.radius}};
        } else if constexpr (std::is_same_v<T, geometry::Cylinder>) {
          return {{"shape", "cylinder"}, {"radius", s.radius}, {"length", s.length}};
        } else if constexpr (std::is_same_v<T, geometry::Box>) {
          return {{"shape", "box"}, {"size", {s.size.x(), s.size.y(), s.size.z()}}};
        } else if constexpr (std::is_same_v<T, geometry::HalfSpace>) {
          return {{"shape", "halfspace"}};
        } else {
          throw InputError(which, "a mesh shape cannot be written into a synthetic dataset");
        }
      },
      shape);
}

}  // namespace vcontact::io
