#include "formats/dataset_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "dynamics/rigid_body.hpp"
#include "geometry/error.hpp"
#include "io/csv_table.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "io/output_file.hpp"
#include "io/shape_json.hpp"
#include "io/shape_spec.hpp"
#include "validation/free_flight.hpp"
#include "volume/contact.hpp"

namespace vcontact::formats {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kFormat = "vcontact.dataset/1";
const std::vector<std::string> kRequired = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
// Three samples are the fewest a second-order derivative needs.
constexpr std::size_t kMinimumSamples = 3;

bool isWrench(const std::string& c) {
  return std::find(validation::kWrenchColumns.begin(), validation::kWrenchColumns.end(), c) !=
         validation::kWrenchColumns.end();
}

std::string requireString(const json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where, "missing \"" + key + "\"");
  if (!j.at(key).is_string()) throw InputError(where, "\"" + key + "\" must be a string");
  return j.at(key).get<std::string>();
}

using Table = io::CsvTable;

// The largest magnitude a column may hold (io/input_ranges.hpp) and its unit; a column of
// another name (a quaternion part, an extra column) is only checked finite. The table reader
// checks every value as it reads it.
io::ColumnLimit columnLimit(const std::string& name) {
  if (name == "t") return {io::kMaxTime, "s"};
  if (name == "x" || name == "y" || name == "z") return {io::kMaxPosition, "m"};
  if (name == "vx" || name == "vy" || name == "vz") return {io::kMaxSpeed, "m/s"};
  if (name == "wx" || name == "wy" || name == "wz") return {io::kMaxAngularSpeed, "rad/s"};
  if (name == "fx" || name == "fy" || name == "fz") return {io::kMaxForce, "N"};
  if (name == "tx" || name == "ty" || name == "tz") return {io::kMaxTorque, "N m"};
  return {};
}

io::CsvTable readTable(const std::string& path) { return io::readCsvTable(path, columnLimit); }

std::size_t columnIndex(const Table& t, const std::string& name) {
  return static_cast<std::size_t>(std::find(t.names.begin(), t.names.end(), name) -
                                  t.names.begin());
}

// Either all three of a vector's columns or none.
bool hasTriple(const Table& t, const std::string& path, const std::array<std::string, 3>& cols) {
  int present = 0;
  for (const auto& c : cols) present += columnIndex(t, c) < t.names.size();
  if (present == 0) return false;
  if (present < 3) {
    throw InputError(path, "line 1: columns " + cols[0] + ", " + cols[1] + ", " + cols[2] +
                               " come together; some are missing");
  }
  return true;
}

// The columns PREFIXx, PREFIXy, PREFIXz (present: hasTriple), and row i of them.
struct Triple {
  Triple(const Table& t, const std::string& prefix)
      : x(t.columns[columnIndex(t, prefix + "x")]),
        y(t.columns[columnIndex(t, prefix + "y")]),
        z(t.columns[columnIndex(t, prefix + "z")]) {}
  Eigen::Vector3d operator[](std::size_t i) const { return {x[i], y[i], z[i]}; }
  const std::vector<double>&x, &y, &z;
};

// Velocities differentiated from the rows within the bounds a velocity column has: samples
// 1e-9 s apart a millimetre apart would give 1e6 m/s.
void checkDifferentiatedSpeeds(const Table& t, const std::string& path,
                               const validation::Dataset& d) {
  for (std::size_t i = 0; i < d.samples.size(); ++i) {
    const validation::Sample& s = d.samples[i];
    const bool fast = d.velocityFromPositions && !(s.v_BA.norm() <= io::kMaxSpeed);
    const bool spinning = d.omegaFromAttitude && !(s.w_BA.norm() <= io::kMaxAngularSpeed);
    if (!fast && !spinning) continue;
    std::ostringstream os;
    os << "line " << t.lineOf[i] << ": "
       << (fast ? "speed differentiated from x, y, z "
                : "angular speed differentiated from the "
                  "quaternions ")
       << (fast ? s.v_BA.norm() : s.w_BA.norm()) << (fast ? " m/s" : " rad/s")
       << "; expected at most " << (fast ? io::kMaxSpeed : io::kMaxAngularSpeed)
       << (fast ? " m/s" : " rad/s") << " (rows too close in time, or a jump in the motion)";
    throw InputError(path, os.str());
  }
}

// `needWrench`: a dataset's CSV needs a wrench column, a motion CSV (synth --motion) not.
void fillSamples(const Table& t, const std::string& path, validation::Dataset& d,
                 bool needWrench = true) {
  for (const auto& r : kRequired) {
    if (columnIndex(t, r) == t.names.size()) {
      throw InputError(path, "line 1: missing required column '" + r + "'");
    }
  }
  if (needWrench && std::none_of(t.names.begin(), t.names.end(), isWrench)) {
    throw InputError(path,
                     "line 1: no wrench column; expected at least one of fx, fy, fz, tx, ty, tz");
  }
  if (t.rowCount() < kMinimumSamples) {
    throw InputError(path, "only " + std::to_string(t.rowCount()) + " samples; at least " +
                               std::to_string(kMinimumSamples) + " are needed");
  }
  const bool hasV = hasTriple(t, path, {"vx", "vy", "vz"});
  const bool hasW = hasTriple(t, path, {"wx", "wy", "wz"});
  for (std::size_t c = 0; c < t.names.size(); ++c) {
    d.columns[t.names[c]] = Eigen::Map<const Eigen::VectorXd>(
        t.columns[c].data(), static_cast<Eigen::Index>(t.rowCount()));
  }
  // The columns of the named quantities, looked up once.
  const auto column = [&](const std::string& n) -> const std::vector<double>& {
    return t.columns[columnIndex(t, n)];
  };
  const auto& ct = column("t");
  const auto &qw = column("qw"), &qx = column("qx"), &qy = column("qy"), &qz = column("qz");
  const Triple p(t, "");
  std::optional<Triple> v, w;
  if (hasV) v.emplace(t, "v");
  if (hasW) w.emplace(t, "w");
  d.samples.resize(t.rowCount());
  for (std::size_t i = 0; i < t.rowCount(); ++i) {
    const auto where = [&] { return "line " + std::to_string(t.lineOf[i]); };
    validation::Sample& s = d.samples[i];
    s.t = ct[i];
    if (i > 0 && !(s.t > d.samples[i - 1].t)) {
      std::ostringstream os;
      os << where() << ", column 't': time " << s.t << " is not after the previous sample's "
         << d.samples[i - 1].t << " (time must increase strictly)";
      throw InputError(path, os.str());
    }
    if (i > 0 && s.t - d.samples[i - 1].t < io::kMinSampleInterval) {
      std::ostringstream os;
      os << where() << ", column 't': time step " << s.t - d.samples[i - 1].t << " s is below "
         << io::kMinSampleInterval << " s (a 1 GHz sampling rate)";
      throw InputError(path, os.str());
    }
    const Eigen::Vector4d q(qw[i], qx[i], qy[i], qz[i]);
    if (std::abs(q.norm() - 1.0) > kDatasetQuaternionTolerance) {
      std::ostringstream os;
      os << where() << ", columns 'qw'..'qz': quaternion length " << q.norm()
         << " is far from 1 (tolerance " << kDatasetQuaternionTolerance << ")";
      throw InputError(path, os.str());
    }
    s.X_BA.linear() = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
    s.X_BA.translation() = p[i];
    if (v) s.v_BA = (*v)[i];
    if (w) s.w_BA = (*w)[i];
  }
  d.velocityFromPositions = !hasV;
  d.omegaFromAttitude = !hasW;
  if (!hasV) validation::differentiatePositions(d.samples);
  if (!hasW) validation::differentiateAttitudes(d.samples);
  checkDifferentiatedSpeeds(t, path, d);
}

void readOutputsAndNoise(const json& j, const std::string& where, const std::string& csv,
                         validation::Dataset& d) {
  if (!j.contains("outputs") || !j.at("outputs").is_array() || j.at("outputs").empty()) {
    throw InputError(where, "\"outputs\" must be a non-empty list of wrench columns");
  }
  for (const auto& o : j.at("outputs")) {
    if (!o.is_string() || !isWrench(o.get<std::string>())) {
      throw InputError(where, "outputs: " + o.dump() + " is not one of fx, fy, fz, tx, ty, tz");
    }
    const std::string name = o.get<std::string>();
    if (!d.columns.count(name)) {
      throw InputError(where, "outputs: \"" + name + "\" is not a column of " + csv);
    }
    d.outputs.push_back(name);
  }
  if (!j.contains("noise")) return;
  if (!j.at("noise").is_object())
    throw InputError(where, "\"noise\" must be an object {output: sigma}");
  for (const auto& [key, value] : j.at("noise").items()) {
    if (std::find(d.outputs.begin(), d.outputs.end(), key) == d.outputs.end()) {
      throw InputError(where, "noise: \"" + key + "\" is not one of the outputs");
    }
    if (!value.is_number() || !(value.get<double>() > 0.0) || !std::isfinite(value.get<double>())) {
      throw InputError(where,
                       "noise: \"" + key + "\" must be a positive number, got " + value.dump());
    }
    d.noise[key] = value.get<double>();
  }
}

// A JSON number that is finite (and ≥ 0 when nonNegative), or the error naming `key`.
double finiteNumber(const json& v, const std::string& where, const std::string& key,
                    bool nonNegative) {
  if (!v.is_number() || !std::isfinite(v.get<double>()) || (nonNegative && v.get<double>() < 0)) {
    throw InputError(where, "payload_inertia." + key + " must be a finite" +
                                (nonNegative ? " non-negative" : "") + " number, got " + v.dump());
  }
  return v.get<double>();
}

Eigen::Matrix3d readInertiaMatrix(const json& v, const std::string& where) {
  const std::string expect =
      "payload_inertia.inertia must be [Ixx, Iyy, Izz] or a 3×3 symmetric matrix (kg·m²), got ";
  if (!v.is_array() || v.size() != 3) throw InputError(where, expect + v.dump());
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (!v[0].is_array()) {
    for (int k = 0; k < 3; ++k) I(k, k) = finiteNumber(v[k], where, "inertia", true);
    return I;
  }
  for (int r = 0; r < 3; ++r) {
    if (!v[r].is_array() || v[r].size() != 3) throw InputError(where, expect + v.dump());
    for (int c = 0; c < 3; ++c) I(r, c) = finiteNumber(v[r][c], where, "inertia", false);
  }
  // symmetric to round-off of written digits; a tensor of a body has no negative moment
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * I.cwiseAbs().maxCoeff() ||
      I.diagonal().minCoeff() < 0.0) {
    throw InputError(where,
                     "payload_inertia.inertia is not symmetric with non-negative "
                     "diagonal: " +
                         v.dump());
  }
  return I;
}

// "payload_inertia": {"density": kg/m³}: the mass properties of the payload's shape.
validation::PayloadInertia inertiaFromDensity(const json& e, const std::string& where,
                                              const geometry::Shape& payload) {
  const json& rho = e.at("density");
  if (e.size() != 1 || !rho.is_number() || !(rho.get<double>() > 0.0) ||
      !std::isfinite(rho.get<double>())) {
    throw InputError(where,
                     "payload_inertia: {\"density\": kg/m^3} must stand alone with a positive "
                     "number, got " +
                         e.dump());
  }
  dynamics::RigidBody body;
  body.shape = payload;
  dynamics::setMassFromDensity(body, rho.get<double>());
  return {body.mass, body.I_BBcm_B, body.p_BBcm};
}

// outputs ⊂ {position, attitude}, noise {output: σ} in m and rad.
void readTrajectoryOutputs(const json& j, const std::string& where, validation::Dataset& d) {
  const auto& names = validation::kTrajectoryOutputs;
  const auto known = [&](const std::string& o) {
    return std::find(names.begin(), names.end(), o) != names.end();
  };
  if (!j.contains("outputs") || !j.at("outputs").is_array() || j.at("outputs").empty()) {
    throw InputError(where, "\"outputs\" must be a non-empty list of \"position\", \"attitude\"");
  }
  for (const auto& o : j.at("outputs")) {
    if (!o.is_string() || !known(o.get<std::string>()))
      throw InputError(where, "outputs: " + o.dump() + " is not \"position\" or \"attitude\"");
    if (std::find(d.outputs.begin(), d.outputs.end(), o.get<std::string>()) != d.outputs.end())
      throw InputError(where, "outputs: " + o.dump() + " is listed twice");
    d.outputs.push_back(o.get<std::string>());
  }
  if (!j.contains("noise")) return;
  if (!j.at("noise").is_object())
    throw InputError(where, "\"noise\" must be an object {\"position\": m, \"attitude\": rad}");
  for (const auto& [key, value] : j.at("noise").items()) {
    if (std::find(d.outputs.begin(), d.outputs.end(), key) == d.outputs.end())
      throw InputError(where, "noise: \"" + key + "\" is not one of the outputs");
    if (!value.is_number() || !(value.get<double>() > 0.0) || !std::isfinite(value.get<double>()))
      throw InputError(where,
                       "noise: \"" + key + "\" must be a positive number, got " + value.dump());
    d.noise[key] = value.get<double>();
  }
}

// A pose as the scenario files write it: "x,y,z[,roll,pitch,yaw | ,qw,qx,qy,qz]" or an array.
Eigen::Isometry3d readPose(const json& v, const std::string& where) {
  if (v.is_string()) return io::parsePose(v.get<std::string>(), where);
  if (!v.is_array()) throw InputError(where, "expected a pose \"x,y,z[,r,p,y]\" or an array");
  std::string text;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!v[k].is_number()) throw InputError(where, "expected numbers, got " + v.dump());
    std::ostringstream os;
    os.precision(17);
    os << v[k].get<double>();
    text += (k ? "," : "") + os.str();
  }
  return io::parsePose(text, where);
}

Eigen::Vector3d readGravity(const json& v, const std::string& where) {
  Eigen::Vector3d g;
  if (!v.is_array() || v.size() != 3)
    throw InputError(where, "gravity must be [gx, gy, gz] in m/s^2, got " + v.dump());
  for (int k = 0; k < 3; ++k) {
    if (!v[k].is_number() || !std::isfinite(v[k].get<double>()) ||
        std::abs(v[k].get<double>()) > 1e3)
      throw InputError(where,
                       "gravity must be three finite numbers within 1000 m/s^2, got " + v.dump());
    g[k] = v[k].get<double>();
  }
  return g;
}

// Without velocity columns the initial state is estimated from the free flight before the
// first contact (validation/free_flight.hpp); a record that starts in contact has none.
void requireInitialState(const validation::Dataset& d) {
  if (!d.velocityFromPositions && !d.omegaFromAttitude) return;
  const std::size_t first = validation::firstContact(d);
  if (first >= validation::kMinFreeFlightSamples) return;
  std::ostringstream os;
  os << "the payload touches the plate at sample " << first + 1
     << " (t = " << d.samples[std::min(first, d.size() - 1)].t << " s); without "
     << (d.velocityFromPositions ? "vx, vy, vz" : "wx, wy, wz")
     << " columns the initial state is estimated from the free flight before the first contact, "
        "which needs "
     << validation::kMinFreeFlightSamples << " samples; give the velocities at the first sample";
  throw InputError(d.dataPath, os.str());
}

// The payload's optional "surface": "mesh" (default) or "recovered", recognised here once
// (docs/DATASET.md, docs/SURFACES.md).
void readPayloadSurface(const json& payload, const std::string& where, validation::Dataset& d) {
  if (!payload.contains("surface")) return;
  const json& s = payload.at("surface");
  if (!s.is_string() || (s != "mesh" && s != "recovered")) {
    throw InputError(where,
                     "\"surface\" must be \"mesh\" (the polyhedron, default) or "
                     "\"recovered\" (the analytic surfaces the mesh was tessellated "
                     "from), got " +
                         s.dump());
  }
  if (s == "mesh") return;
  const auto* mesh = std::get_if<geometry::Mesh>(&d.payload);
  if (mesh == nullptr) {
    throw InputError(where, "\"surface\": \"recovered\" applies to a mesh payload; a " +
                                geometry::shapeKind(d.payload) + " is its own true surface");
  }
  try {
    d.payload_surface = volume::recoverSurface(mesh->mesh);
  } catch (const InputError& e) {
    throw InputError(where, std::string("the mesh's surfaces cannot be recognised: ") + e.what());
  }
}

// The optional "payload_inertia": {"mass": kg, "inertia": [...], "com": [x, y, z]}.
void readPayloadInertia(const json& j, const std::string& where, validation::Dataset& d) {
  if (!j.contains("payload_inertia")) return;
  const json& e = j.at("payload_inertia");
  if (e.is_object() && e.contains("density")) {
    d.inertia = inertiaFromDensity(e, where, d.payload);
    return;
  }
  if (!e.is_object() || !e.contains("mass") || !e.contains("inertia")) {
    throw InputError(where,
                     "payload_inertia must be an object with \"mass\" and \"inertia\" "
                     "(and optionally \"com\")");
  }
  validation::PayloadInertia p;
  p.mass = finiteNumber(e.at("mass"), where, "mass", true);
  if (!(p.mass > 0.0)) throw InputError(where, "payload_inertia.mass must be positive (kg)");
  p.inertia = readInertiaMatrix(e.at("inertia"), where);
  if (e.contains("com")) {
    const json& c = e.at("com");
    if (!c.is_array() || c.size() != 3)
      throw InputError(where, "payload_inertia.com must be [x, y, z] in metres, got " + c.dump());
    for (int k = 0; k < 3; ++k) p.com[k] = finiteNumber(c[k], where, "com", false);
  }
  for (const auto& [key, value] : e.items()) {
    if (key != "mass" && key != "inertia" && key != "com")
      throw InputError(where, "payload_inertia: unknown key \"" + key + "\" (mass, inertia, com)");
  }
  d.inertia = p;
}

// The dynamic sidecar's own keys (docs/DATASET.md, "Dynamic datasets"): outputs position and
// attitude, their noise, the payload's mass properties (required), the plate's pose and
// gravity; then whether the record can give an initial state.
void readDynamic(const json& j, const std::string& where, validation::Dataset& d) {
  readTrajectoryOutputs(j, where, d);
  readPayloadInertia(j, where, d);
  if (!d.inertia) {
    throw InputError(where,
                     "a dynamic dataset's payload is free and needs its mass: "
                     "\"payload_inertia\": {\"mass\": kg, \"inertia\": [Ixx, Iyy, Izz]} or "
                     "{\"density\": kg/m^3}");
  }
  if (j.contains("plate_pose")) d.X_BP = readPose(j.at("plate_pose"), where + ": plate_pose");
  if (j.contains("gravity")) d.gravity_B = readGravity(j.at("gravity"), where);
  requireInitialState(d);
}

json payloadInertiaJson(const validation::PayloadInertia& p) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({p.inertia(r, 0), p.inertia(r, 1), p.inertia(r, 2)});
  return {{"mass", p.mass}, {"inertia", rows}, {"com", {p.com.x(), p.com.y(), p.com.z()}}};
}

}  // namespace

DatasetReadResult readDataset(const std::string& sidecarPath) {
  const json j = io::readJsonFile(sidecarPath);
  const std::string& where = sidecarPath;
  if (!j.is_object()) throw InputError(where, "the sidecar must be a JSON object");
  const std::string format = requireString(j, "format", where);
  if (format != kFormat) {
    throw InputError(where,
                     "format must be \"" + std::string(kFormat) + "\", got \"" + format + "\"");
  }
  const std::string mode = requireString(j, "mode", where);
  if (mode != "kinematic" && mode != "dynamic") {
    throw InputError(where, "mode must be \"kinematic\" or \"dynamic\", got \"" + mode + "\"");
  }

  DatasetReadResult result;
  validation::Dataset& d = result.dataset;
  const bool dynamic = mode == "dynamic";
  if (dynamic) d.mode = validation::DatasetMode::kDynamic;
  d.sidecarPath = sidecarPath;
  const fs::path base = fs::path(sidecarPath).parent_path();
  d.name =
      j.contains("name") ? requireString(j, "name", where) : fs::path(sidecarPath).stem().string();
  if (j.contains("notes")) d.notes = requireString(j, "notes", where);
  const std::string data = requireString(j, "data", where);
  d.dataPath = (base / data).string();
  if (!fs::is_regular_file(d.dataPath)) {
    throw InputError(where, "data file \"" + data + "\" not found (looked for " + d.dataPath + ")");
  }
  for (const char* body : {"payload", "plate"}) {
    if (!j.contains(body)) throw InputError(where, std::string("missing \"") + body + "\"");
    io::JsonShape s = io::parseShapeJson(j.at(body), where + ": " + body, base.string());
    result.warnings.insert(result.warnings.end(), s.warnings.begin(), s.warnings.end());
    (std::string(body) == "payload" ? d.payload : d.plate) = std::move(s.shape);
  }
  if (std::holds_alternative<geometry::HalfSpace>(d.payload)) {
    throw InputError(where + ": payload", "the payload must be a bounded body, not a half-space");
  }
  readPayloadSurface(j.at("payload"), where + ": payload", d);
  if (d.payload_surface && !std::holds_alternative<geometry::HalfSpace>(d.plate)) {
    result.warnings.push_back(where +
                              ": payload: \"surface\": \"recovered\" has closed forms "
                              "against a half-space plate only; against this " +
                              geometry::shapeKind(d.plate) + " the polyhedra are used");
  }
  fillSamples(readTable(d.dataPath), d.dataPath, d, /*needWrench=*/!dynamic);
  if (dynamic) {
    readDynamic(j, where, d);
  } else {
    readOutputsAndNoise(j, where, d.dataPath, d);
    readPayloadInertia(j, where, d);
  }
  if (d.velocityFromPositions) {
    result.warnings.push_back(d.dataPath +
                              ": no vx, vy, vz columns; velocities differentiated from x, y, z");
  }
  if (d.omegaFromAttitude) {
    result.warnings.push_back(
        d.dataPath +
        ": no wx, wy, wz columns; angular velocities differentiated from the quaternions");
  }
  return result;
}

MotionReadResult readMotionCsv(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path, "motion file not found");
  MotionReadResult result;
  validation::Dataset& d = result.dataset;
  d.dataPath = path;
  fillSamples(readTable(path), path, d, /*needWrench=*/false);
  for (const auto& c : validation::kWrenchColumns) d.columns.erase(c);  // a motion measures nothing
  const char* names[] = {"vx", "vy", "vz", "wx", "wy", "wz"};
  for (int k = 0; k < 6; ++k) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(d.size()));
    for (std::size_t i = 0; i < d.size(); ++i) {
      const auto& s = d.samples[i];
      v[static_cast<Eigen::Index>(i)] = k < 3 ? s.v_BA[k] : s.w_BA[k - 3];
    }
    d.columns[names[k]] = std::move(v);
  }
  if (d.velocityFromPositions)
    result.warnings.push_back(path + ": no vx, vy, vz columns; differentiated from x, y, z");
  if (d.omegaFromAttitude)
    result.warnings.push_back(path +
                              ": no wx, wy, wz columns; differentiated from the quaternions");
  return result;
}

namespace {

// x, y, z, qw, qx, qy, qz as the reader's plate_pose takes it.
json poseJson(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d p = X.translation();
  return {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()};
}

// The dataset's columns `names` as CSV, a header line first, every number in round-trip form.
void putTable(const validation::Dataset& d, const std::vector<std::string>& names,
              std::ostream& out) {
  out.precision(std::numeric_limits<double>::max_digits10);
  for (std::size_t c = 0; c < names.size(); ++c) out << (c ? "," : "") << names[c];
  out << '\n';
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(d.size()); ++i) {
    for (std::size_t c = 0; c < names.size(); ++c)
      out << (c ? "," : "") << d.columns.at(names[c])[i];
    out << '\n';
  }
}

}  // namespace

void writeDataset(const validation::Dataset& d, const std::string& sidecarPath,
                  const nlohmann::json* payloadEntry) {
  const fs::path sidecar(sidecarPath);
  const fs::path csv = fs::path(sidecar).replace_extension(".csv");
  const bool dynamic = d.mode == validation::DatasetMode::kDynamic;
  json j = {{"format", kFormat},
            {"name", d.name},
            {"data", csv.filename().string()},
            {"mode", dynamic ? "dynamic" : "kinematic"},
            {"payload", payloadEntry ? *payloadEntry : io::shapeJson(d.payload, "payload")},
            {"plate", io::shapeJson(d.plate, "plate")},
            {"outputs", d.outputs},
            {"notes", d.notes}};
  if (!d.noise.empty()) j["noise"] = d.noise;
  if (d.inertia) j["payload_inertia"] = payloadInertiaJson(*d.inertia);
  std::vector<std::string> names = {"t",  "x",  "y",  "z",  "qw", "qx", "qy",
                                    "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
  if (dynamic) {
    j["plate_pose"] = poseJson(d.X_BP);
    j["gravity"] = {d.gravity_B.x(), d.gravity_B.y(), d.gravity_B.z()};
  } else {
    for (const auto& o : d.outputs) names.push_back(o);
  }
  for (const auto& n : names) {
    if (!d.columns.count(n)) throw InputError(sidecarPath, "dataset has no column '" + n + "'");
  }
  // Both files or neither: a sidecar never names a missing or half-written table.
  io::OutputSet files;
  files.add(csv.string(), [&](std::ostream& out) { putTable(d, names, out); });
  files.add(sidecar.string(), [&](std::ostream& out) { io::putJson(j, out); });
  files.commit();
}

}  // namespace vcontact::formats
