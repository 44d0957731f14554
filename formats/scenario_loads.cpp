#include "formats/scenario_loads.hpp"

#include <map>

#include "io/csv_table.hpp"

namespace vcontact::formats::detail {
namespace {

// The limits of springs and drives (docs/SCENARIO.md "Loads", "Springs"), kept beside the
// keys they bound rather than in io/input_ranges.hpp, which every layer includes: zero (none)
// up to about the axial stiffness of a steel bar a metre long and a square metre across
// (~2e11 N/m), dampings and torsional values as wide; a stiffer spring is a joint, which
// vcontact does not model.
constexpr io::Range kStiffnessRange{0.0, 1e12, "N/m"};
constexpr io::Range kDampingRange{0.0, 1e9, "N s/m"};
constexpr io::Range kTorsionalStiffnessRange{0.0, 1e9, "N m/rad"};
constexpr io::Range kTorsionalDampingRange{0.0, 1e9, "N m s/rad"};

// A unit quaternion read from a table may carry the rounding of its printed digits; beyond
// this distance of |q| from 1 it is no rotation the writer meant.
constexpr double kQuaternionNormSlack = 1e-3;

// The table at `key` (a path relative to base_dir), its columns checked against `required`
// and `optional` (each a name; optional ones come in threes, all or none).
io::CsvTable readTable(const Reader& r, const std::string& key, const std::string& base_dir,
                       const std::vector<std::string>& required,
                       const std::vector<std::string>& optional) {
  const std::string path = resolve(r.text(key), base_dir);
  io::CsvTable table;
  try {
    table = io::readCsvTable(path);
  } catch (const InputError& e) {
    r.fail(key, e.what());
  }
  const auto has = [&](const std::string& n) {
    return std::find(table.names.begin(), table.names.end(), n) != table.names.end();
  };
  for (const std::string& n : table.names) {
    if (std::find(required.begin(), required.end(), n) == required.end() &&
        std::find(optional.begin(), optional.end(), n) == optional.end()) {
      r.fail(key, path + ": line 1: unknown column '" + n + "'");
    }
  }
  for (const std::string& n : required) {
    if (!has(n)) r.fail(key, path + ": line 1: expected a column '" + n + "'");
  }
  for (std::size_t i = 0; i + 2 < optional.size(); i += 3) {
    const int count = has(optional[i]) + has(optional[i + 1]) + has(optional[i + 2]);
    if (count != 0 && count != 3) {
      r.fail(key, path + ": line 1: expected the columns " + optional[i] + ", " + optional[i + 1] +
                      ", " + optional[i + 2] + " together or none of them");
    }
  }
  if (table.rowCount() == 0) r.fail(key, path + ": expected at least one row after the header");
  const std::vector<double>& t = table.columns[std::size_t(
      std::find(table.names.begin(), table.names.end(), "t") - table.names.begin())];
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::ostringstream s;
    if (std::abs(t[i]) > io::kMaxTime) {
      s << path << ": line " << table.lineOf[i] << ", column t: expected |t| <= " << io::kMaxTime
        << " s, got " << t[i];
    } else if (i > 0 && !(t[i] > t[i - 1])) {
      s << path << ": line " << table.lineOf[i] << ", column t: " << t[i] << " s does not follow "
        << t[i - 1] << " s; expected strictly increasing times";
    } else if (i > 0 && t[i] - t[i - 1] < io::kMinSampleInterval) {
      // rows 1e-300 s apart made a speed of 1e300 m/s out of a millimetre
      s << path << ": line " << table.lineOf[i] << ", column t: " << t[i] - t[i - 1]
        << " s after the previous row; expected at least " << io::kMinSampleInterval
        << " s (a 1 GHz rate)";
    }
    if (!s.str().empty()) r.fail(key, s.str());
  }
  return table;
}

const std::vector<double>* column(const io::CsvTable& t, const std::string& name) {
  for (std::size_t c = 0; c < t.names.size(); ++c) {
    if (t.names[c] == name) return &t.columns[c];
  }
  return nullptr;
}

std::vector<Eigen::Vector3d> vectors(const io::CsvTable& t, const char* x, const char* y,
                                     const char* z) {
  std::vector<Eigen::Vector3d> out;
  const auto *cx = column(t, x), *cy = column(t, y), *cz = column(t, z);
  if (cx == nullptr) return out;
  for (std::size_t i = 0; i < t.rowCount(); ++i) out.emplace_back((*cx)[i], (*cy)[i], (*cz)[i]);
  return out;
}

// A value that is a number or an array of 3 (per axis), each in `range`.
Eigen::Vector3d perAxis(const Reader& r, const std::string& key, const io::Range& range) {
  if (!r.has(key)) return Eigen::Vector3d::Zero();
  Eigen::Vector3d v;
  if (r[key].is_number()) {
    v.setConstant(r[key].get<double>());
  } else {
    const auto n = r.numbers(key);
    if (n.size() != 3) r.fail(key, "expected a number or an array of 3 numbers (per axis)");
    v = Eigen::Vector3d(n[0], n[1], n[2]);
  }
  for (int i = 0; i < 3; ++i) {
    const std::string why = io::outOfRange(v[i], range, "a number");
    if (!why.empty()) r.fail(key, why);
  }
  return v;
}

std::size_t bodyNamed(const Reader& r, const std::string& key, const dynamics::Scenario& sc) {
  const std::string name = r.text(key);
  for (std::size_t i = 0; i < sc.bodies.size(); ++i) {
    if (sc.bodies[i].name == name) return i;
  }
  r.fail(key, "no body named '" + name + "'");
}

Eigen::Vector3d point(const Reader& r, const std::string& key) {
  return r.vector3(key, Eigen::Vector3d::Zero(), io::kMaxPosition, "m");
}

// A drive's target: a pose and an analytic motion, or a trajectory ("csv").
void readTarget(const Reader& r, const std::string& base_dir, dynamics::TargetDrive& d) {
  if (r.has("csv")) {
    if (r.has("pose")) r.fail("pose", "the trajectory gives the pose; leave \"pose\" out");
    d.motion.trajectory = readTrajectoryMotion(r, base_dir);
    d.X_WT0 = d.motion.trajectory->at(0.0).X_WB;
    return;
  }
  r.allowOnly({"pose", "velocity", "angular_velocity", "amplitude", "frequency"});
  d.X_WT0 = readPose(r, "pose");
  d.motion.v_W = r.vector3("velocity", Eigen::Vector3d::Zero(), io::kMaxSpeed, "m/s");
  d.motion.w_W =
      r.vector3("angular_velocity", Eigen::Vector3d::Zero(), io::kMaxAngularSpeed, "rad/s");
  d.motion.amplitude_W = r.vector3("amplitude", Eigen::Vector3d::Zero(), io::kMaxPosition, "m");
  d.motion.frequency_hz = r.number("frequency", 0.0, 0.0, io::kRateRange.upper);
}

void readDrive(const Reader& r, const std::string& base_dir, dynamics::ExternalLoad& load) {
  load.kind = dynamics::LoadKind::kDrive;
  dynamics::TargetDrive& d = load.drive;
  readTarget(r.child("target"), base_dir, d);
  if (!r.has("stiffness")) r.fail("stiffness", "a drive needs a stiffness (N/m)");
  d.stiffness = perAxis(r, "stiffness", kStiffnessRange);
  d.damping = perAxis(r, "damping", kDampingRange);
  d.torsional_stiffness = perAxis(r, "torsional_stiffness", kTorsionalStiffnessRange);
  d.torsional_damping = perAxis(r, "torsional_damping", kTorsionalDampingRange);
  if (r.has("max_force")) d.max_force = r.number("max_force", 0.0, 0.0, io::kMaxForce);
  if (r.has("max_torque")) d.max_torque = r.number("max_torque", 0.0, 0.0, io::kMaxTorque);
  if (!(d.max_force > 0.0)) r.fail("max_force", "expected a positive force limit (N)");
  if (!(d.max_torque > 0.0)) r.fail("max_torque", "expected a positive torque limit (N m)");
}

dynamics::ExternalLoad readLoad(const Reader& r, const std::string& base_dir,
                                const dynamics::Scenario& sc, std::size_t index) {
  r.allowOnly({"name", "body", "point", "force", "torque", "csv", "target", "stiffness", "damping",
               "torsional_stiffness", "torsional_damping", "max_force", "max_torque"});
  dynamics::ExternalLoad load;
  load.body = bodyNamed(r, "body", sc);
  load.name = r.has("name") ? r.name("name") : "load" + std::to_string(index);
  load.p_BP = point(r, "point");
  const int kinds = (r.has("force") || r.has("torque")) + r.has("csv") + r.has("target");
  if (kinds != 1) {
    r.fail("",
           "expected one of \"force\"/\"torque\" (constant), \"csv\" (a table) or "
           "\"target\" (a spring–damper drive)");
  }
  const bool drive = r.has("target");
  for (const char* k : {"stiffness", "damping", "torsional_stiffness", "torsional_damping",
                        "max_force", "max_torque"}) {
    if (!drive && r.has(k)) r.fail(k, "belongs to a drive (with \"target\") only");
  }
  if (drive) {
    readDrive(r, base_dir, load);
  } else if (r.has("csv")) {
    load.kind = dynamics::LoadKind::kTable;
    const io::CsvTable t =
        readTable(r, "csv", base_dir, {"t", "fx", "fy", "fz", "tx", "ty", "tz"}, {});
    auto table = std::make_shared<dynamics::WrenchTable>();
    table->t = *column(t, "t");
    table->f_W = vectors(t, "fx", "fy", "fz");
    table->tau_W = vectors(t, "tx", "ty", "tz");
    load.table = std::move(table);
  } else {
    load.kind = dynamics::LoadKind::kConstant;
    load.constant.f_W = r.vector3("force", Eigen::Vector3d::Zero(), io::kMaxForce, "N");
    load.constant.tau_W = r.vector3("torque", Eigen::Vector3d::Zero(), io::kMaxTorque, "N m");
  }
  return load;
}

dynamics::BodySpring readSpring(const Reader& r, const dynamics::Scenario& sc) {
  r.allowOnly({"name", "a", "b", "point_a", "point_b", "rest_length", "stiffness", "damping",
               "torsional_stiffness", "torsional_damping"});
  dynamics::BodySpring s;
  s.a = bodyNamed(r, "a", sc);
  s.b = bodyNamed(r, "b", sc);
  if (s.a == s.b) r.fail("b", "a spring joins two different bodies");
  s.name = r.has("name") ? r.name("name") : sc.bodies[s.a].name + "-" + sc.bodies[s.b].name;
  s.p_AP = point(r, "point_a");
  s.p_BQ = point(r, "point_b");
  const Eigen::Isometry3d& X_WA = sc.bodies[s.a].X_WB0;
  const Eigen::Isometry3d& X_WB = sc.bodies[s.b].X_WB0;
  const double initial = (X_WB * s.p_BQ - X_WA * s.p_AP).norm();
  s.rest_length = r.number("rest_length", initial, 0.0, io::kMaxPosition);
  s.stiffness = r.inRange("stiffness", 0.0, kStiffnessRange);
  s.damping = r.inRange("damping", 0.0, kDampingRange);
  s.torsional_stiffness = r.inRange("torsional_stiffness", 0.0, kTorsionalStiffnessRange);
  s.torsional_damping = r.inRange("torsional_damping", 0.0, kTorsionalDampingRange);
  s.q_AB_rest = Eigen::Quaterniond(X_WA.linear().transpose() * X_WB.linear());
  return s;
}

// The speeds a trajectory gives its body, between rows (interval slopes: the linear
// interpolation's velocities and what the cubic's tangents are estimated from) and in its
// velocity columns, within io::kMaxSpeed and io::kMaxAngularSpeed.
void checkSpeeds(const dynamics::TrajectoryRows& rows, const io::CsvTable& t,
                 const std::string& path, const Reader& r) {
  const auto fail = [&](std::size_t i, const char* what, double value, double limit,
                        const char* unit) {
    std::ostringstream s;
    s << path << ": line " << t.lineOf[i] << ", " << what << ": " << value << " " << unit
      << "; expected at most " << limit << " " << unit;
    r.fail("csv", s.str());
  };
  for (std::size_t i = 0; i < rows.t.size(); ++i) {
    if (!rows.v_WBo.empty() && !(rows.v_WBo[i].norm() <= io::kMaxSpeed))
      fail(i, "columns vx..vz: speed", rows.v_WBo[i].norm(), io::kMaxSpeed, "m/s");
    if (!rows.w_WB.empty() && !(rows.w_WB[i].norm() <= io::kMaxAngularSpeed))
      fail(i, "columns wx..wz: angular speed", rows.w_WB[i].norm(), io::kMaxAngularSpeed, "rad/s");
    if (i == 0) continue;
    const double dt = rows.t[i] - rows.t[i - 1];
    const double v = (rows.p_WB[i] - rows.p_WB[i - 1]).norm() / dt;
    if (!(v <= io::kMaxSpeed))
      fail(i, "columns x..z: speed from the previous row", v, io::kMaxSpeed, "m/s");
    const double angle = rows.q_WB[i].normalized().angularDistance(rows.q_WB[i - 1].normalized());
    if (!(angle / dt <= io::kMaxAngularSpeed))
      fail(i, "columns qw..qz: angular speed from the previous row", angle / dt,
           io::kMaxAngularSpeed, "rad/s");
  }
}

}  // namespace

std::shared_ptr<const dynamics::Trajectory> readTrajectoryMotion(const Reader& r,
                                                                 const std::string& base_dir) {
  r.allowOnly({"csv", "interpolation"});
  dynamics::Interpolation interpolation = dynamics::Interpolation::kCubic;
  if (r.has("interpolation")) {
    const std::string name = r.text("interpolation");
    if (name == "linear") {
      interpolation = dynamics::Interpolation::kLinear;
    } else if (name != "cubic") {
      r.fail("interpolation", "expected \"linear\" or \"cubic\", got \"" + name + "\"");
    }
  }
  const io::CsvTable t = readTable(r, "csv", base_dir, {"t", "x", "y", "z", "qw", "qx", "qy", "qz"},
                                   {"vx", "vy", "vz", "wx", "wy", "wz"});
  dynamics::TrajectoryRows rows;
  rows.t = *column(t, "t");
  rows.p_WB = vectors(t, "x", "y", "z");
  rows.v_WBo = vectors(t, "vx", "vy", "vz");
  rows.w_WB = vectors(t, "wx", "wy", "wz");
  const auto& qw = *column(t, "qw");
  const std::vector<Eigen::Vector3d> qv = vectors(t, "qx", "qy", "qz");
  const std::string path = resolve(r.text("csv"), base_dir);
  for (std::size_t i = 0; i < t.rowCount(); ++i) {
    const Eigen::Quaterniond q(qw[i], qv[i].x(), qv[i].y(), qv[i].z());
    if (std::abs(q.norm() - 1.0) > kQuaternionNormSlack) {
      std::ostringstream s;
      s << path << ": line " << t.lineOf[i] << ", columns qw..qz: expected a unit quaternion, "
        << "its norm is " << q.norm();
      r.fail("csv", s.str());
    }
    if (std::abs(rows.p_WB[i].maxCoeff()) > io::kMaxPosition ||
        std::abs(rows.p_WB[i].minCoeff()) > io::kMaxPosition) {
      r.fail("csv", path + ": line " + std::to_string(t.lineOf[i]) +
                        ", columns x..z: expected positions within +-1000 m");
    }
    rows.q_WB.push_back(q);
  }
  checkSpeeds(rows, t, path, r);
  if (interpolation == dynamics::Interpolation::kLinear &&
      (!rows.v_WBo.empty() || !rows.w_WB.empty())) {
    r.fail("interpolation", path +
                                " has velocity columns: they need \"cubic\" interpolation (a "
                                "linear one takes its velocities from the rows)");
  }
  return std::make_shared<dynamics::Trajectory>(std::move(rows), interpolation);
}

void readLoads(const Reader& r, const std::string& base_dir, dynamics::Scenario& sc) {
  if (!r.has("loads")) return;
  if (!r["loads"].is_array()) r.fail("loads", "expected an array of loads");
  for (std::size_t i = 0; i < r["loads"].size(); ++i) {
    const Reader l(r["loads"][i], r.source(), "loads[" + std::to_string(i) + "]");
    sc.loads.push_back(readLoad(l, base_dir, sc, i));
  }
}

void readSprings(const Reader& r, dynamics::Scenario& sc) {
  if (!r.has("springs")) return;
  if (!r["springs"].is_array()) r.fail("springs", "expected an array of springs");
  for (std::size_t i = 0; i < r["springs"].size(); ++i) {
    const Reader s(r["springs"][i], r.source(), "springs[" + std::to_string(i) + "]");
    sc.springs.push_back(readSpring(s, sc));
  }
}

}  // namespace vcontact::formats::detail
