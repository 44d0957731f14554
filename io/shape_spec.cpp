#include "io/shape_spec.hpp"

#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "geometry/error.hpp"
#include "io/input_ranges.hpp"
#include "io/mesh_io.hpp"

namespace vcontact::io {
namespace {

// A quaternion typed with six or more digits is unit to 1e-6; further off, the user most
// likely wrote something else (Euler angles, a wrong order) and is told so.
constexpr double kUnitQuaternionTolerance = 1e-6;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Positions within the workspace, roll, pitch and yaw within one turn (io/input_ranges.hpp).
void checkPoseRanges(const std::vector<double>& v, const std::string& source) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool angle = v.size() == 6 && i >= 3;
    const double limit = i < 3 ? kMaxPosition : (angle ? kMaxAngleDegrees : HUGE_VAL);
    if (std::abs(v[i]) <= limit) continue;
    static const char* const kNames[] = {"x", "y", "z", "roll", "pitch", "yaw"};
    std::ostringstream os;
    os << kNames[i] << " = " << v[i] << " is beyond +-" << limit
       << (angle ? " degrees (one turn)" : " m (the workspace)");
    throw InputError(source, os.str());
  }
}

}  // namespace

void checkShapeLengths(const geometry::Shape& shape, const std::string& source) {
  auto check = [&](double value, const char* name) {
    const std::string why = outOfRange(value, kLengthRange, name);
    if (!why.empty()) throw InputError(source, why);
  };
  if (const auto* s = std::get_if<geometry::Sphere>(&shape)) check(s->radius, "the radius");
  if (const auto* c = std::get_if<geometry::Cylinder>(&shape)) {
    check(c->radius, "the radius");
    check(c->length, "the length");
  }
  if (const auto* b = std::get_if<geometry::Box>(&shape)) {
    for (int k = 0; k < 3; ++k) check(b->size[k], "a box edge");
  }
}

std::vector<double> parseNumberList(const std::string& text, const std::string& source) {
  std::vector<double> values;
  std::size_t begin = 0;
  // Every comma separates two numbers: "1,2," and ",1" hold an empty one and are refused.
  while (true) {
    const std::size_t comma = text.find(',', begin);
    const std::string t =
        trim(text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    double v = 0.0;
    std::string why;
    if (!parseDecimal(t, v, why)) {
      throw InputError(source, "'" + t + "' in '" + text + "' is " + why);
    }
    values.push_back(v);
    if (comma == std::string::npos) return values;
    begin = comma + 1;
  }
}

Eigen::Isometry3d poseFromRpyDegrees(const Eigen::Vector3d& t, const Eigen::Vector3d& rpy) {
  const Eigen::Vector3d r = rpy * (M_PI / 180.0);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  X.translation() = t;
  return X;
}

Eigen::Isometry3d poseFromQuaternion(const Eigen::Vector3d& t, const Eigen::Vector4d& wxyz,
                                     const std::string& source) {
  const double norm = wxyz.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > kUnitQuaternionTolerance) {
    std::ostringstream os;
    os << "quaternion (w, x, y, z) must be unit length, |q| = " << norm;
    throw InputError(source, os.str());
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() =
      Eigen::Quaterniond(wxyz(0), wxyz(1), wxyz(2), wxyz(3)).normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

Eigen::Isometry3d parsePose(const std::string& text, const std::string& source) {
  const std::vector<double> v = parseNumberList(text, source);
  checkPoseRanges(v, source);
  const Eigen::Vector3d t =
      v.size() >= 3 ? Eigen::Vector3d(v[0], v[1], v[2]) : Eigen::Vector3d::Zero();
  switch (v.size()) {
    case 3: {
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = t;
      return X;
    }
    case 6:
      return poseFromRpyDegrees(t, Eigen::Vector3d(v[3], v[4], v[5]));
    case 7:
      return poseFromQuaternion(t, Eigen::Vector4d(v[3], v[4], v[5], v[6]), source);
    default:
      throw InputError(source,
                       "a pose is x,y,z or x,y,z,roll,pitch,yaw (degrees) or "
                       "x,y,z,qw,qx,qy,qz; got " +
                           std::to_string(v.size()) + " numbers");
  }
}

std::pair<std::string, double> splitMeshScale(const std::string& text) {
  const auto at = text.rfind('@');
  if (at == std::string::npos) return {text, 1.0};
  // A file of that very name is a path, whatever follows its '@'.
  std::error_code ec;
  if (std::filesystem::exists(text, ec)) return {text, 1.0};
  const std::string suffix = text.substr(at + 1);
  if (const auto unit = unitScale(suffix)) return {text.substr(0, at), *unit};
  double scale = 0.0;
  std::string why;
  if (parseDecimal(suffix, scale, why)) return {text.substr(0, at), scale};
  return {text, 1.0};  // not a scale: the '@' belongs to the path
}

ParsedShape parseShape(const std::string& text, const std::string& source,
                       const MeshReadOptions& mesh) {
  if (trim(text).empty()) {
    throw InputError(source,
                     "expected a shape (sphere:R, cylinder:R,L, box:X,Y,Z, halfspace or a mesh "
                     "file), got an empty text");
  }
  const auto colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string args = colon == std::string::npos ? "" : text.substr(colon + 1);
  auto numbers = [&](std::size_t count, const char* form) {
    const auto v = args.empty() ? std::vector<double>{} : parseNumberList(args, source);
    if (v.size() != count) {
      throw InputError(source, std::string("expected ") + form + ", got '" + text + "'");
    }
    return v;
  };
  ParsedShape out;
  if (kind == "sphere") {
    out.shape = geometry::Sphere{numbers(1, "sphere:R")[0]};
  } else if (kind == "cylinder") {
    const auto v = numbers(2, "cylinder:R,L");
    out.shape = geometry::Cylinder{v[0], v[1]};
  } else if (kind == "box") {
    const auto v = numbers(3, "box:X,Y,Z");
    out.shape = geometry::Box{Eigen::Vector3d(v[0], v[1], v[2])};
  } else if (kind == "halfspace" && args.empty()) {
    out.shape = geometry::HalfSpace{};
  } else {
    const auto [path, scale] = splitMeshScale(text);
    auto read = readMesh(path, scale, mesh);
    out.warnings = std::move(read.warnings);
    out.mesh = std::move(read.report);
    out.shape =
        geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(std::move(read.mesh)), path};
  }
  geometry::validate(out.shape, source);
  checkShapeLengths(out.shape, source);
  return out;
}

}  // namespace vcontact::io
