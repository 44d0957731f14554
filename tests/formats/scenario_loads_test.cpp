// The scenario keys of prescribed motion from a table, loads and springs
// (docs/SCENARIO.md): they build the engine's objects, paths are relative to the scenario,
// bad tables name the file, line and column, and "contacts" pairs a prescribed body with a
// fixed one, whose contact force the run reports.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "dynamics/dynamics_fixtures.hpp"
#include "formats/scenario_file.hpp"
#include "support/test_support.hpp"

namespace vcontact::formats {
namespace {

namespace fs = std::filesystem;

// A folder of its own per test, with the given files in it.
fs::path folderWith(const std::string& name,
                    const std::vector<std::pair<std::string, std::string>>& files) {
  const fs::path dir = fs::temp_directory_path() / ("vcontact_scenario_loads_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& [file, text] : files) std::ofstream(dir / file) << text;
  return dir;
}

nlohmann::json scene() {
  return nlohmann::json::parse(R"({
    "format": "vcontact.scenario/1", "duration": 0.002, "output_rate": 1000, "gravity": [0, 0, 0],
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "motion": {"csv": "path/ball.csv"}},
               {"name": "puck", "shape": "cylinder:0.01,0.005", "density": 7900,
                "pose": "0.1,0,0.01"}],
    "pairs": [{"a": "ball", "b": "plate", "method": "analytic",
               "model": {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e11}}}}],
    "loads": [{"name": "push", "body": "puck", "force": [0.1, 0, 0], "point": [0, 0, 0.002]},
              {"body": "puck", "csv": "forces.csv"},
              {"body": "puck", "target": {"pose": "0.1,0,0.01", "velocity": [0, 0, -0.1]},
               "stiffness": [10, 10, 100], "damping": 1, "max_force": 2}],
    "springs": [{"a": "ball", "b": "puck", "point_b": [0, 0, 0.0025], "stiffness": 5,
                 "torsional_stiffness": 0.01}]})");
}

const char* kBallCsv =
    "t,x,y,z,qw,qx,qy,qz\n"
    "0,0,0,0.0099,1,0,0,0\n"
    "0.001,0,0,0.0098,1,0,0,0\n"
    "0.003,0,0,0.0097,1,0,0,0\n";
const char* kForcesCsv = "t,fx,fy,fz,tx,ty,tz\n0,0,0,-1,0,0,0\n0.002,0,0,-2,0,0,0.001\n";

fs::path sceneFolder(const std::string& name, const std::string& ball_csv = kBallCsv) {
  const fs::path dir = folderWith(name, {{"forces.csv", kForcesCsv}});
  fs::create_directories(dir / "path");
  std::ofstream(dir / "path" / "ball.csv") << ball_csv;
  return dir;
}

TEST(ScenarioLoads, KeysBuildTheScenario) {
  const fs::path dir = sceneFolder("keys");
  const dynamics::Scenario s = scenarioFromJson(scene(), "s.json", dir.string()).scenario;
  ASSERT_EQ(s.loads.size(), 3u);
  EXPECT_EQ(s.loads[0].name, "push");
  EXPECT_EQ(s.loads[1].name, "load1");
  EXPECT_EQ(s.loads[0].kind, dynamics::LoadKind::kConstant);
  EXPECT_EQ(s.loads[1].kind, dynamics::LoadKind::kTable);
  EXPECT_EQ(s.loads[2].kind, dynamics::LoadKind::kDrive);
  EXPECT_EQ(s.loads[2].drive.stiffness, Eigen::Vector3d(10, 10, 100));
  EXPECT_EQ(s.loads[2].drive.max_force, 2.0);
  ASSERT_EQ(s.springs.size(), 1u);
  EXPECT_EQ(s.springs[0].name, "ball-puck");
  // rest length: the points' initial distance, (0.1, 0, 0.0125) − (0, 0, 0.0099)
  EXPECT_NEAR(s.springs[0].rest_length, std::hypot(0.1, 0.0026), 1e-15);
  // the ball's initial pose is its trajectory's first row
  EXPECT_NEAR(s.bodies[1].X_WB0.translation().z(), 0.0099, 1e-15);
}

// "contacts" pairs the prescribed ball with the fixed plate (it used to leave out pairs
// without a free body), the ball as the payload although the plate is listed later.
TEST(ScenarioLoads, ContactsPairAPrescribedBodyWithAFixedOne) {
  const fs::path dir = sceneFolder("contacts");
  nlohmann::json j = scene();
  for (const char* key : {"loads", "springs"}) j.erase(key);
  j["bodies"].erase(2);
  std::swap(j["bodies"][0], j["bodies"][1]);
  j["contacts"] = j["pairs"][0];
  for (const char* key : {"a", "b"}) j["contacts"].erase(key);
  j.erase("pairs");
  const dynamics::Scenario s = scenarioFromJson(j, "s.json", dir.string()).scenario;
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].name, "ball-plate");
  EXPECT_EQ(s.pairs[0].a, 0u);
  EXPECT_EQ(s.pairs[0].b, 1u);
  // two fixed bodies are still no pair
  j["bodies"][0]["motion"] = "fixed";
  EXPECT_TRUE(scenarioFromJson(j, "s.json", dir.string()).scenario.pairs.empty());
}

// The ball is held 0.1 mm into the plate at t = 0 and 0.2 mm at 1 ms; the pair reports
// kv V on it, V = π d² (3R − d)/3, as a force sensor would.
TEST(ScenarioLoads, PrescribedBallOnAFixedPlateReportsItsContactForce) {
  const fs::path dir = sceneFolder("run");
  const dynamics::Scenario s = scenarioFromJson(scene(), "s.json", dir.string()).scenario;
  const std::vector<dynamics::Snapshot> out = test::run(s);
  ASSERT_EQ(out.size(), 3u);
  for (const auto& [k, d] : {std::pair{0, 1e-4}, std::pair{1, 2e-4}}) {
    const double V = std::numbers::pi * d * d * (3 * 0.01 - d) / 3.0;
    // the analytic cap volume, exact to round-off
    EXPECT_NEAR(out[std::size_t(k)].pairs[0].result.wrench.f_W.z(), 1e11 * V, 1e-9 * 1e11 * V);
  }
  // the table's force at 1 ms, half-way: (0, 0, −1.5) N
  EXPECT_NEAR(out[1].loads[1].wrench.f_W.z(), -1.5, 1e-12);
}

TEST(ScenarioLoads, BadTablesNameTheFileLineAndColumn) {
  const std::string backwards = "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.01,1,0,0,0\n-1,0,0,0.01,1,0,0,0\n";
  const fs::path dir = sceneFolder("bad", backwards);
  const std::string e =
      test::inputErrorMessage([&] { scenarioFromJson(scene(), "s.json", dir.string()); });
  EXPECT_NE(e.find("s.json: bodies[1].motion.csv: "), std::string::npos) << e;
  EXPECT_NE(e.find("ball.csv: line 3, column t: -1 s does not follow 0 s"), std::string::npos) << e;
  const fs::path dir2 = sceneFolder("bad_q", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.01,0.5,0,0,0\n");
  const std::string q =
      test::inputErrorMessage([&] { scenarioFromJson(scene(), "s.json", dir2.string()); });
  EXPECT_NE(q.find("line 2, columns qw..qz: expected a unit quaternion, its norm is 0.5"),
            std::string::npos)
      << q;
  nlohmann::json linear = scene();
  linear["bodies"][1]["motion"]["interpolation"] = "linear";
  const fs::path dir3 =
      sceneFolder("linear_v", "t,x,y,z,qw,qx,qy,qz,vx,vy,vz\n0,0,0,0.01,1,0,0,0,0,0,0\n");
  const std::string l =
      test::inputErrorMessage([&] { scenarioFromJson(linear, "s.json", dir3.string()); });
  EXPECT_NE(l.find("bodies[1].motion.interpolation"), std::string::npos) << l;
}

// Rows 1e-300 s apart made 1e300 m/s of a millimetre (issue 36): a time step below a 1 GHz
// rate is refused, and so is a speed or an angular speed beyond io::kMaxSpeed (1e3 m/s) and
// io::kMaxAngularSpeed (1e4 rad/s), from the rows or from the velocity columns.
TEST(ScenarioLoads, ImpossibleSpeedsOfATrajectoryNameTheLine) {
  struct Case {
    const char* name;
    const char* csv;
    const char* fragment;
  };
  const Case cases[] = {
      {"tiny_step", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.01,1,0,0,0\n1e-300,0,0,0.011,1,0,0,0\n",
       "ball.csv: line 3, column t: 1e-300 s after the previous row; expected at least 1e-09 s"},
      {"fast", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.01,1,0,0,0\n1e-6,0,0,0.02,1,0,0,0\n",
       "ball.csv: line 3, columns x..z: speed from the previous row: 10000 m/s; expected at most "
       "1000 m/s"},
      // a quarter turn (pi/2 rad) in 1e-5 s: 1.6e5 rad/s
      {"spin", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.01,1,0,0,0\n1e-5,0,0,0.01,0.70710678,0,0,0.70710678\n",
       "line 3, columns qw..qz: angular speed from the previous row: 157080 rad/s"},
      {"v_column",
       "t,x,y,z,qw,qx,qy,qz,vx,vy,vz\n0,0,0,0.01,1,0,0,0,0,0,0\n1,0,0,0.01,1,0,0,0,0,2e3,0\n",
       "line 3, columns vx..vz: speed: 2000 m/s; expected at most 1000 m/s"},
  };
  for (const Case& c : cases) {
    const fs::path dir = sceneFolder(c.name, c.csv);
    const std::string e =
        test::inputErrorMessage([&] { scenarioFromJson(scene(), "s.json", dir.string()); });
    EXPECT_NE(e.find("s.json: bodies[1].motion.csv: "), std::string::npos) << e;
    EXPECT_NE(e.find(c.fragment), std::string::npos) << c.name << ": " << e;
  }
}

TEST(ScenarioLoads, BadKeysNameThePlace) {
  const fs::path dir = sceneFolder("keys_bad");
  const auto error = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json j = scene();
    change(j);
    return test::inputErrorMessage([&] { scenarioFromJson(j, "s.json", dir.string()); });
  };
  EXPECT_NE(
      error([](auto& j) { j["loads"][0]["csv"] = "forces.csv"; }).find("loads[0]: expected one of"),
      std::string::npos);
  EXPECT_NE(error([](auto& j) {
              j["loads"][0]["stiffness"] = 3;
            }).find("loads[0].stiffness: belongs to a drive"),
            std::string::npos);
  EXPECT_NE(error([](auto& j) {
              j["loads"][2]["max_force"] = 0;
            }).find("loads[2].max_force: expected a positive force limit"),
            std::string::npos);
  EXPECT_NE(error([](auto& j) {
              j["loads"][2]["stiffness"] = {1, 2};
            }).find("loads[2].stiffness: expected a number or an array of 3"),
            std::string::npos);
  EXPECT_NE(error([](auto& j) {
              j["springs"][0]["b"] = "ball";
            }).find("springs[0].b: a spring joins two different bodies"),
            std::string::npos);
  EXPECT_NE(error([](auto& j) {
              j["bodies"][1]["pose"] = "0,0,1";
            }).find("bodies[1].pose: the trajectory gives the pose"),
            std::string::npos);
}

// The bundled peg insertion (assets/scenarios/peg_insertion.json): the chamfer guides the
// peg, started 0.6 mm off the axis, into the 10.2 mm hole, and the drive pushes it to the floor
// 8 mm down, where its force saturates at the 5 N limit and the floor carries that plus the
// peg's weight.
TEST(ScenarioLoads, PegInsertionReachesTheFloor) {
  const ScenarioFile f =
      readScenarioFile(std::string(VCONTACT_ASSETS_DIR) + "/scenarios/peg_insertion.json");
  const dynamics::Scenario& s = f.scenario;
  const std::vector<dynamics::Snapshot> out = test::run(s);
  const dynamics::BodyKinematics& peg = out.back().bodies[1];
  const double depth = 0.015 - peg.X_WB.translation().z();  // the tip below the block's top
  // the floor at 8 mm; the contact's mean penetration there is V/A ≈ 0.7 um
  EXPECT_NEAR(depth, 0.008, 5e-6);
  // inside the hole: within the 0.1 mm radial clearance of its axis (the 64-gons' flats
  // leave 0.094 mm to 0.1 mm)
  EXPECT_LT(peg.X_WB.translation().head<2>().norm(), 1.01e-4);
  EXPECT_NEAR(out.back().loads[0].wrench.f_W.norm(), 5.0, 1e-9);
  const double weight = s.bodies[1].mass * 9.81;
  // at rest on the floor, up to the lateral spring's friction share (a few mN) of fz
  EXPECT_NEAR(out.back().pairs[0].result.wrench.f_W.z(), 5.0 + weight, 5e-3);
}

}  // namespace
}  // namespace vcontact::formats
