#include "formats/scenario_file.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "formats/model_file.hpp"
#include "formats/scenario_loads.hpp"
#include "formats/scenario_reader.hpp"
#include "geometry/error.hpp"
#include "io/file_names.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "io/mesh_io.hpp"
#include "io/shape_spec.hpp"
#include "volume/contact.hpp"

namespace vcontact::formats {
namespace {

using detail::Reader;
using detail::readPose;
using detail::resolve;

constexpr const char* kFormat = "vcontact.scenario/1";

bool isPrimitive(const std::string& text) {
  for (const char* prefix : {"sphere:", "cylinder:", "box:"}) {
    if (text.rfind(prefix, 0) == 0) return true;
  }
  return text == "halfspace";
}

Eigen::Matrix3d readInertia(const Reader& r) {
  const auto v = r.numbers("inertia");
  if (v.size() == 3) return Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
  if (v.size() != 9) r.fail("inertia", "expected 3 (diagonal) or 9 numbers, kg m^2 about the COM");
  Eigen::Matrix3d I;
  I << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  if (!I.isApprox(I.transpose())) r.fail("inertia", "expected a symmetric matrix");
  return I;
}

// A rigid body's inertia about its centre of mass is positive definite, and its principal
// moments obey the triangle inequality I1 + I2 >= I3 (equality for a flat plate). The
// tolerance, 1e-9 of the trace, lets a plate's moments computed in double pass.
void checkInertia(const Reader& r, const Eigen::Matrix3d& I) {
  const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  std::ostringstream s;
  s.precision(6);
  if (!(m.minCoeff() > 0.0)) {
    s << "expected a positive definite tensor (kg m^2), principal moments are " << m.x() << ", "
      << m.y() << ", " << m.z();
    r.fail("inertia", s.str());
  }
  const double slack = 1e-9 * m.sum();
  if (m.x() + m.y() < m.z() - slack) {
    s << "principal moments " << m.x() << ", " << m.y() << ", " << m.z()
      << " violate the triangle inequality (the two smaller must add up to the largest); no "
         "rigid body has them";
    r.fail("inertia", s.str());
  }
}

dynamics::PrescribedMotion readPrescribed(const Reader& r) {
  r.allowOnly({"velocity", "angular_velocity", "amplitude", "frequency"});
  dynamics::PrescribedMotion m;
  m.v_W = r.vector3("velocity", Eigen::Vector3d::Zero(), io::kMaxSpeed, "m/s");
  m.w_W = r.vector3("angular_velocity", Eigen::Vector3d::Zero(), io::kMaxAngularSpeed, "rad/s");
  m.amplitude_W = r.vector3("amplitude", Eigen::Vector3d::Zero(), io::kMaxPosition, "m");
  m.frequency_hz = r.number("frequency", 0.0, 0.0, io::kRateRange.upper);
  return m;
}

void readMass(const Reader& r, dynamics::RigidBody& body) {
  if (r.has("density") == r.has("mass")) {
    r.fail("", "a free body needs either \"density\" (kg/m^3) or \"mass\" and \"inertia\"");
  }
  if (r.has("density")) {
    try {
      dynamics::setMassFromDensity(body, r.inRange("density", 0.0, io::kDensityRange));
    } catch (const InputError& e) {
      r.fail("density", e.message());
    }
    return;
  }
  if (!r.has("inertia")) r.fail("inertia", "expected with \"mass\"");
  body.mass = r.inRange("mass", 0.0, io::kMassRange);
  body.I_BBcm_B = readInertia(r);
  checkInertia(r, body.I_BBcm_B);
  body.p_BBcm = r.vector3("com", Eigen::Vector3d::Zero());
}

/// A mesh body whose density gives less than a milligram was most likely scaled twice
/// (io::lightPartWarning names the likely scale); the bounding-box check ran when it was read.
void warnIfLight(const Reader& r, const dynamics::RigidBody& body,
                 std::vector<std::string>& warnings) {
  const auto* mesh = std::get_if<geometry::Mesh>(&body.shape);
  if (mesh == nullptr || !r.has("density")) return;
  const auto w = io::lightPartWarning(*mesh->mesh, r.positive("density", 0.0));
  if (w) warnings.push_back(body.name + ": " + *w);
}

// A mesh file's own error names the file; the scenario's key is added, so that a missing or
// broken mesh is found in the scenario too (issue 20).
io::ParsedShape readShape(const Reader& r, const std::string& shape,
                          const io::MeshReadOptions& mesh) {
  const std::string source = r.source() + ": " + r.at("shape");
  try {
    return io::parseShape(shape, source, mesh);
  } catch (const InputError& e) {
    if (e.source() == source) throw;
    r.fail("shape", e.what());
  }
}

// "surface": "mesh" (the polyhedron, default) or "recovered": the surfaces the mesh was
// tessellated from, recognised here once (docs/SURFACES.md, docs/SCENARIO.md).
void readSurface(const Reader& r, dynamics::RigidBody& body) {
  if (!r.has("surface")) return;
  const std::string surface = r.text("surface");
  if (surface == "mesh") return;
  if (surface != "recovered") {
    r.fail("surface",
           "expected \"mesh\" (the polyhedron, default) or \"recovered\" (the analytic "
           "surfaces the mesh was tessellated from)");
  }
  const auto* mesh = std::get_if<geometry::Mesh>(&body.shape);
  if (mesh == nullptr) {
    r.fail("surface", "\"recovered\" applies to a mesh body; a " + geometry::shapeKind(body.shape) +
                          " is its own true surface");
  }
  try {
    body.surface = volume::recoverSurface(mesh->mesh);
  } catch (const InputError& e) {
    r.fail("surface", std::string("the mesh's surfaces cannot be recognised: ") + e.what());
  }
}

dynamics::RigidBody readBody(const Reader& r, const std::string& base_dir,
                             std::vector<std::string>& warnings) {
  r.allowOnly({"name", "shape", "motion", "pose", "velocity", "angular_velocity", "density", "mass",
               "inertia", "com", "prescribed", "repair", "surface"});
  dynamics::RigidBody body;
  body.name = r.name("name");
  std::string shape = r.text("shape");
  if (!isPrimitive(shape)) shape = resolve(shape, base_dir);
  io::MeshReadOptions mesh;
  mesh.repair = r.flag("repair", false);
  io::ParsedShape parsed = readShape(r, shape, mesh);
  body.shape = std::move(parsed.shape);
  for (const auto& w : parsed.warnings) warnings.push_back(body.name + ": " + w);
  readSurface(r, body);
  body.X_WB0 = readPose(r, "pose");
  if (r.has("motion") && r["motion"].is_object()) {  // a trajectory from a table
    for (const char* key : {"pose", "velocity", "angular_velocity", "prescribed"}) {
      if (r.has(key)) r.fail(key, "the trajectory gives the pose and velocities; leave it out");
    }
    body.motion = dynamics::BodyMotion::kPrescribed;
    body.prescribed.trajectory = detail::readTrajectoryMotion(r.child("motion"), base_dir);
    body.X_WB0 = body.prescribed.trajectory->at(0.0).X_WB;
    return body;
  }
  const std::string motion = r.has("motion") ? r.text("motion") : "free";
  if (motion == "fixed") {
    body.motion = dynamics::BodyMotion::kFixed;
  } else if (motion == "prescribed") {
    body.motion = dynamics::BodyMotion::kPrescribed;
    body.prescribed = readPrescribed(r.child("prescribed"));
  } else if (motion == "free") {
    body.motion = dynamics::BodyMotion::kFree;
    readMass(r, body);
    warnIfLight(r, body, warnings);
    body.w_WB0 =
        r.vector3("angular_velocity", Eigen::Vector3d::Zero(), io::kMaxAngularSpeed, "rad/s");
    // "velocity" is that of the body frame origin; store that of the centre of mass.
    const Eigen::Vector3d v_WBo =
        r.vector3("velocity", Eigen::Vector3d::Zero(), io::kMaxSpeed, "m/s");
    body.v_WBcm0 = v_WBo + body.w_WB0.cross(body.X_WB0.linear() * body.p_BBcm);
  } else {
    r.fail("motion",
           "expected \"free\", \"fixed\" or \"prescribed\", or a trajectory {\"csv\": PATH}");
  }
  return body;
}

dynamics::Model readPairModel(const Reader& r, const std::map<std::string, dynamics::Model>& named,
                              const std::string& base_dir) {
  if (!r.has("model")) r.fail("model", "expected a model name, a model file or a model object");
  const auto& m = r["model"];
  if (m.is_object()) return modelFromJson(m, r.source(), r.at("model"));
  const std::string name = r.text("model");
  if (const auto it = named.find(name); it != named.end()) return it->second;
  const std::string path = resolve(name, base_dir);
  if (!std::filesystem::exists(path)) {
    r.fail("model", "'" + name + "' is neither a name in \"models\" nor an existing model file");
  }
  return readModelFile(path);
}

std::size_t bodyIndex(const Reader& r, const std::string& key,
                      const std::vector<dynamics::RigidBody>& bodies) {
  const std::string name = r.text(key);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return i;
  }
  r.fail(key, "no body named '" + name + "'");
}

// "sleep": false, true (the defaults) or {"speed": m/s, "time": s} (docs/SCENARIO.md).
dynamics::SleepSettings readSleep(const Reader& r) {
  dynamics::SleepSettings s;
  const nlohmann::json& v = r["sleep"];
  if (v.is_boolean()) {
    s.enabled = v.get<bool>();
    return s;
  }
  if (!v.is_object()) r.fail("sleep", "expected false, true or an object {\"speed\", \"time\"}");
  const Reader o = r.child("sleep");
  o.allowOnly({"speed", "time"});
  // 1 m/s is far above any resting creep; a quiet time beyond a day means "never"
  s.speed = o.number("speed", s.speed, 1e-12, 1.0);
  if (!(s.speed > 0.0)) o.fail("speed", "expected a positive number");
  s.time = o.number("time", s.time, 0.0, 86400.0);
  return s;
}

dynamics::SimulationSettings readSettings(const Reader& r) {
  dynamics::SimulationSettings s;
  s.duration = r.inRange("duration", s.duration, io::kDurationRange);
  s.output_rate_hz = r.inRange("output_rate", s.output_rate_hz, io::kRateRange);
  if (r.has("integrator")) {
    const std::string name = r.text("integrator");
    if (name == "dopri5") {
      s.integrator = dynamics::Integrator::kDopri5;
    } else if (name == "bdf") {
      s.integrator = dynamics::Integrator::kBdf;
    } else if (name == "discrete") {
      s.integrator = dynamics::Integrator::kDiscrete;
    } else {
      r.fail("integrator", "expected \"dopri5\", \"bdf\" or \"discrete\"");
    }
  }
  s.step = r.number("step", s.step, dynamics::kMinDiscreteStep, dynamics::kMaxDiscreteStep);
  if (r.has("impacts")) {
    const std::string mode = r.text("impacts");
    if (mode == "auto") {
      s.impacts = dynamics::ImpactMode::kAuto;
    } else if (mode == "resolve") {
      s.impacts = dynamics::ImpactMode::kResolve;
    } else if (mode == "implicit") {
      s.impacts = dynamics::ImpactMode::kImplicit;
    } else {
      r.fail("impacts", "expected \"auto\", \"resolve\" or \"implicit\"");
    }
  }
  if (r.has("restitution_threshold")) {
    if (s.impacts != dynamics::ImpactMode::kAuto) {
      r.fail("restitution_threshold",
             "applies to \"impacts\": \"auto\" only (\"resolve\" resolves every impact, "
             "\"implicit\" none)");
    }
    s.restitution_threshold = r.number("restitution_threshold", s.restitution_threshold, 0.0, 1e3);
  }
  if (r.has("sleep")) s.sleep = readSleep(r);
  if (!r.has("tolerances")) return s;
  const Reader t = r.child("tolerances");
  t.allowOnly({"abs", "rel", "initial_step", "max_step", "min_step", "max_penetration_fraction"});
  s.abs_tol = t.positive("abs", s.abs_tol);
  s.rel_tol = t.positive("rel", s.rel_tol);
  s.initial_step = t.positive("initial_step", s.initial_step);
  s.max_step = t.positive("max_step", s.max_step);
  s.min_step = t.positive("min_step", s.min_step);
  s.max_penetration_fraction =
      t.number("max_penetration_fraction", s.max_penetration_fraction, 1e-12, 1.0);
  return s;
}

/// "friction" ("lumped" or "distributed") and, for distributed, "columns" (lines per side of
/// the fixed grid). Distributed friction integrates over the columns method's δ map: the
/// method defaults to columns and may not be another, and the model must allow it.
void readFriction(const Reader& p, dynamics::ContactPair& pair) {
  if (p.has("friction")) {
    const std::string friction = p.text("friction");
    if (friction == "distributed") {
      pair.friction = dynamics::FrictionMode::kDistributed;
    } else if (friction != "lumped") {
      p.fail("friction", "expected \"lumped\" or \"distributed\", got \"" + friction + "\"");
    }
  }
  const std::string pairName = "pair '" + pair.name + "': ";
  if (pair.friction != dynamics::FrictionMode::kDistributed) {
    if (p.has("columns")) {
      p.fail("columns", pairName +
                            "the column grid applies to \"friction\": \"distributed\" "
                            "only");
    }
    return;
  }
  if (!pair.method) pair.method = volume::Method::kColumns;
  if (*pair.method != volume::Method::kColumns) {
    p.fail("friction", pairName +
                           "distributed friction integrates over the columns method's "
                           "δ map; set \"method\": \"columns\" (or leave it out), not \"" +
                           volume::methodName(*pair.method) + "\"");
  }
  if (p.has("columns")) {
    const auto& v = p["columns"];
    const bool integer = v.is_number_integer() || v.is_number_unsigned();
    const auto lines = integer ? v.get<long long>() : 0;
    if (!integer || lines < dynamics::kMinColumnResolution ||
        lines > dynamics::kMaxColumnResolution) {
      p.fail("columns", pairName + "expected an integer number of grid lines per side in [" +
                            std::to_string(dynamics::kMinColumnResolution) + ", " +
                            std::to_string(dynamics::kMaxColumnResolution) + "], got " + v.dump());
    }
    pair.column_resolution = static_cast<int>(lines);
  }
  try {
    pair.model.checkDistributedFriction();
  } catch (const InputError& e) {
    p.fail("friction", pairName + e.message());
  }
}

/// "max_patches": the pair's state slots for its contact patches (docs/SCENARIO.md,
/// "Contact patches"), an integer in [kMinMaxPatches, kMaxMaxPatches].
void readMaxPatches(const Reader& p, dynamics::ContactPair& pair) {
  if (!p.has("max_patches")) return;
  const auto& v = p["max_patches"];
  const bool integer = v.is_number_integer() || v.is_number_unsigned();
  const auto slots = integer ? v.get<long long>() : 0;
  if (!integer || slots < dynamics::kMinMaxPatches || slots > dynamics::kMaxMaxPatches) {
    p.fail("max_patches", "pair '" + pair.name + "': expected an integer number of patch " +
                              "state slots in [" + std::to_string(dynamics::kMinMaxPatches) + ", " +
                              std::to_string(dynamics::kMaxMaxPatches) + "], got " + v.dump());
  }
  pair.max_patches = static_cast<int>(slots);
}

// A pair's model, method, friction and patch keys (a listed pair, or "contacts").
void readPairContact(const Reader& p, const std::map<std::string, dynamics::Model>& models,
                     const std::string& base_dir, dynamics::ContactPair& pair) {
  pair.model = readPairModel(p, models, base_dir);
  if (p.has("method")) {
    try {
      pair.method = volume::parseMethod(p.text("method"));
    } catch (const InputError& e) {
      p.fail("method", e.message());
    }
  }
  readFriction(p, pair);
  readMaxPatches(p, pair);
}

// The pair's method (given, or columns for distributed friction) handles its bodies' shapes.
void checkPairMethod(const Reader& p, const dynamics::ContactPair& pair,
                     const std::vector<dynamics::RigidBody>& bodies) {
  if (!pair.method) return;
  try {
    volume::requireHandles(*pair.method, bodies[pair.a].shape, bodies[pair.b].shape);
  } catch (const InputError& e) {
    p.fail(p.has("method") ? "method" : "friction", "bodies '" + bodies[pair.a].name + "' and '" +
                                                        bodies[pair.b].name + "': " + e.message());
  }
}

// "contacts": one pair for every two bodies not already a pair, at least one of them moving
// (free or prescribed). The payload a is the free one of the two, else the prescribed one,
// and the later one in "bodies" between two of a kind; the method, if not given, is the best
// each pair allows, and a pair no method handles is an error.
void addDefaultContacts(const Reader& c, const std::map<std::string, dynamics::Model>& models,
                        const std::string& base_dir, dynamics::Scenario& sc) {
  c.allowOnly({"model", "method", "friction", "columns", "max_patches"});
  const auto rank = [&](std::size_t i) {  // free 2, prescribed 1, fixed 0
    const dynamics::BodyMotion m = sc.bodies[i].motion;
    return m == dynamics::BodyMotion::kFree ? 2 : m == dynamics::BodyMotion::kPrescribed ? 1 : 0;
  };
  const std::vector<dynamics::ContactPair> listed = sc.pairs;
  for (std::size_t j = 1; j < sc.bodies.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (rank(i) == 0 && rank(j) == 0) continue;
      if (std::any_of(listed.begin(), listed.end(), [&](const dynamics::ContactPair& q) {
            return std::minmax(q.a, q.b) == std::minmax(i, j);
          })) {
        continue;
      }
      dynamics::ContactPair pair;
      pair.a = rank(j) >= rank(i) ? j : i;
      pair.b = rank(j) >= rank(i) ? i : j;
      pair.name = sc.bodies[pair.a].name + "-" + sc.bodies[pair.b].name;
      readPairContact(c, models, base_dir, pair);
      checkPairMethod(c, pair, sc.bodies);
      const geometry::Shape& a = sc.bodies[pair.a].shape;
      const geometry::Shape& b = sc.bodies[pair.b].shape;
      if (!pair.method) {
        try {
          volume::defaultMethod(a, b);
        } catch (const InputError& e) {
          c.fail("", "bodies '" + sc.bodies[pair.a].name + "' and '" + sc.bodies[pair.b].name +
                         "': " + e.message() +
                         "; give them meshes, or list the pairs that can "
                         "touch in \"pairs\"");
        }
      }
      sc.pairs.push_back(std::move(pair));
    }
  }
}

// "bodies": a non-empty array of bodies with distinct names.
void readBodies(const Reader& r, const std::string& source, const std::string& base_dir,
                ScenarioFile& file) {
  if (!r.has("bodies") || !r["bodies"].is_array() || r["bodies"].empty()) {
    r.fail("bodies", "expected a non-empty array of bodies");
  }
  std::vector<dynamics::RigidBody>& bodies = file.scenario.bodies;
  for (std::size_t i = 0; i < r["bodies"].size(); ++i) {
    const Reader b(r["bodies"][i], source, "bodies[" + std::to_string(i) + "]");
    bodies.push_back(readBody(b, base_dir, file.warnings));
    for (std::size_t k = 0; k < i; ++k) {
      if (bodies[k].name == bodies[i].name) {
        b.fail("name", "'" + bodies[i].name + "' is the name of bodies[" + std::to_string(k) +
                           "] already; expected a name of its own");
      }
    }
  }
}

// "models": each given inline or as a model file's path.
std::map<std::string, dynamics::Model> readModels(const Reader& r, const std::string& source,
                                                  const std::string& base_dir) {
  std::map<std::string, dynamics::Model> models;
  if (!r.has("models")) return models;
  const Reader m = r.child("models");
  for (const auto& [name, value] : r["models"].items()) {
    models[name] = value.is_object() ? modelFromJson(value, source, m.at(name))
                                     : readModelFile(resolve(m.text(name), base_dir));
  }
  return models;
}

// "pairs"[i]: two different bodies not already a pair.
dynamics::ContactPair readListedPair(const Reader& p,
                                     const std::map<std::string, dynamics::Model>& models,
                                     const std::string& base_dir, const dynamics::Scenario& sc) {
  p.allowOnly({"name", "a", "b", "model", "method", "friction", "columns", "max_patches"});
  dynamics::ContactPair pair;
  pair.a = bodyIndex(p, "a", sc.bodies);
  pair.b = bodyIndex(p, "b", sc.bodies);
  if (pair.a == pair.b) p.fail("b", "a body cannot touch itself");
  for (const dynamics::ContactPair& q : sc.pairs) {
    if (std::minmax(q.a, q.b) == std::minmax(pair.a, pair.b)) {
      p.fail("b", "bodies '" + sc.bodies[pair.a].name + "' and '" + sc.bodies[pair.b].name +
                      "' are already a pair ('" + q.name + "')");
    }
  }
  pair.name =
      p.has("name") ? p.name("name") : sc.bodies[pair.a].name + "-" + sc.bodies[pair.b].name;
  readPairContact(p, models, base_dir, pair);
  checkPairMethod(p, pair, sc.bodies);
  return pair;
}

// The files a pair's output may take: pair_NAME.csv and pair_NAME_patches.csv, NAME made
// file-safe (io::fileSafe).
std::vector<std::string> pairFileNames(const dynamics::ContactPair& pair) {
  const std::string base = "pair_" + io::fileSafe(pair.name);
  return {base + ".csv", base + "_patches.csv"};
}

// Every pair's output files its own: two pairs whose names differ only in bytes a file name
// does not keep ("ball a", "ball_a"), or one of whose names is the other's with "_patches",
// would write one file (issue 36: one pair's rows were lost). The first `listed` pairs are
// from "pairs", the rest from "contacts".
void checkPairNames(const Reader& r, const std::vector<dynamics::ContactPair>& pairs,
                    std::size_t listed) {
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    for (std::size_t k = 0; k < i; ++k) {
      for (const std::string& a : pairFileNames(pairs[i])) {
        for (const std::string& b : pairFileNames(pairs[k])) {
          if (a != b) continue;
          const std::string where =
              i < listed ? "pairs[" + std::to_string(i) + "].name" : std::string("contacts");
          const std::string same = pairs[k].name == pairs[i].name
                                       ? "the pair name '" + pairs[i].name + "' is used twice"
                                       : "the pairs '" + pairs[k].name + "' and '" + pairs[i].name +
                                             "' would write the same file";
          r.fail(where, same + " (" + a + "); give each pair a name of its own");
        }
      }
    }
  }
}

OutputSelection readOutputs(const Reader& o) {
  o.allowOnly({"bodies", "pairs", "shares", "loads"});
  OutputSelection outputs;
  outputs.bodies = o.flag("bodies", true);
  outputs.pairs = o.flag("pairs", true);
  outputs.shares = o.flag("shares", true);
  outputs.loads = o.flag("loads", true);
  return outputs;
}

}  // namespace

ScenarioFile scenarioFromJson(const nlohmann::json& j, const std::string& source,
                              const std::string& base_dir) {
  if (!j.is_object()) throw InputError(source, "top level: expected a scenario object");
  const Reader r(j, source, "");
  r.allowOnly({"format", "duration", "output_rate", "integrator", "step", "impacts",
               "restitution_threshold", "sleep", "gravity", "tolerances", "bodies", "models",
               "pairs", "contacts", "loads", "springs", "outputs", "description"});
  if (!r.has("format") || r["format"] != kFormat) {
    r.fail("format", std::string("expected \"") + kFormat + "\"");
  }
  ScenarioFile file;
  dynamics::Scenario& sc = file.scenario;
  sc.settings = readSettings(r);
  if (r.has("description") && !r["description"].is_string()) {
    r.fail("description", "expected a string");
  }
  sc.gravity_W = r.vector3("gravity", sc.gravity_W, io::kMaxAcceleration, "m/s^2");
  readBodies(r, source, base_dir, file);
  detail::readLoads(r, base_dir, sc);
  detail::readSprings(r, sc);
  const std::map<std::string, dynamics::Model> models = readModels(r, source, base_dir);
  if (r.has("pairs") ? !r["pairs"].is_array() : !r.has("contacts")) {
    r.fail("pairs", "expected an array of pairs (it may be left out when \"contacts\" is given)");
  }
  const std::size_t listed = r.has("pairs") ? r["pairs"].size() : 0;
  for (std::size_t i = 0; i < listed; ++i) {
    const Reader p(r["pairs"][i], source, "pairs[" + std::to_string(i) + "]");
    sc.pairs.push_back(readListedPair(p, models, base_dir, sc));
  }
  if (r.has("contacts")) addDefaultContacts(r.child("contacts"), models, base_dir, sc);
  checkPairNames(r, sc.pairs, listed);
  if (r.has("outputs")) file.outputs = readOutputs(r.child("outputs"));
  return file;
}

ScenarioFile readScenarioFile(const std::string& path) {
  const nlohmann::json j = io::readJsonFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return scenarioFromJson(j, path, dir.empty() ? "." : dir);
}

}  // namespace vcontact::formats
