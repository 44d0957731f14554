// Scenario files (docs/SCENARIO.md): the bundled scenarios read; bad input names the file,
// the place and what was expected; a failing run stops with time, pair and quantity and keeps
// the output up to the stop.

#include "formats/scenario_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "dynamics/dynamics_fixtures.hpp"
#include "dynamics/simulator.hpp"
#include "geometry/error.hpp"

namespace vcontact::formats {
namespace {

const std::string kScenarios = std::string(VCONTACT_ASSETS_DIR) + "/scenarios";

nlohmann::json ballOnPlate() {
  return nlohmann::json::parse(R"({
    "format": "vcontact.scenario/1", "duration": 0.01, "output_rate": 1000,
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.0105"}],
    "pairs": [{"a": "ball", "b": "plate",
               "model": {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e12}}}}]})");
}

std::string errorOf(const nlohmann::json& j) {
  try {
    scenarioFromJson(j, "s.json", kScenarios);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Issue 36: two pair names that differ only in bytes a file name does not keep wrote one
// pair_*.csv, and one pair's rows were lost; a pair named like another's patch file too.
TEST(ScenarioFile, PairNamesThatWriteTheSameFileAreRefused) {
  nlohmann::json j = ballOnPlate();
  j["bodies"].push_back(
      {{"name", "ball2"}, {"shape", "sphere:0.01"}, {"density", 7900}, {"pose", "0.1,0,0.0105"}});
  j["pairs"][0]["name"] = "ball a";
  j["pairs"].push_back(j["pairs"][0]);
  j["pairs"][1]["a"] = "ball2";
  j["pairs"][1]["name"] = "ball_a";
  EXPECT_EQ(errorOf(j),
            "s.json: pairs[1].name: the pairs 'ball a' and 'ball_a' would write the "
            "same file (pair_ball_a.csv); give each pair a name of its own");
  j["pairs"][1]["name"] = "ball a_patches";
  EXPECT_EQ(errorOf(j),
            "s.json: pairs[1].name: the pairs 'ball a' and 'ball a_patches' would "
            "write the same file (pair_ball_a_patches.csv); give each pair a name of "
            "its own");
  j["pairs"][1]["name"] = "ball b";
  EXPECT_EQ(errorOf(j), "");
}

// Issue 36: commas and line breaks in names split the CSV rows and headers they go into; such
// a name is refused where it is read, naming the JSON place.
TEST(ScenarioFile, NamesThatWouldBreakTheCsvAreRefused) {
  const std::string why =
      "' holds a comma, a double quote or a control character (a line break, a tab); a name "
      "goes into the CSV output unquoted, so it may hold none of them";
  nlohmann::json body = ballOnPlate();
  body["bodies"][1]["name"] = "ball,1";
  body["pairs"][0]["a"] = "ball,1";
  EXPECT_EQ(errorOf(body), "s.json: bodies[1].name: the name 'ball,1" + why);
  body["bodies"][1]["name"] = "ball\n1";
  body["pairs"][0]["a"] = "ball\n1";
  EXPECT_EQ(errorOf(body), "s.json: bodies[1].name: the name 'ball\\x0a1" + why);
  nlohmann::json pair = ballOnPlate();
  pair["pairs"][0]["name"] = "say \"hi\"";
  EXPECT_EQ(errorOf(pair), "s.json: pairs[0].name: the name 'say \"hi\"" + why);
  pair["pairs"][0]["name"] = "";
  EXPECT_EQ(errorOf(pair), "s.json: pairs[0].name: expected a name, got an empty string");
  nlohmann::json load = ballOnPlate();
  load["loads"] =
      nlohmann::json::array({{{"name", "push,pull"}, {"body", "ball"}, {"force", {0, 0, -1}}}});
  EXPECT_EQ(errorOf(load), "s.json: loads[0].name: the name 'push,pull" + why);
  nlohmann::json effect = ballOnPlate();
  effect["pairs"][0]["model"]["effects"]["my,drag"] = {
      {"kind", "expression"}, {"force_t", "0"}, {"parameters", nlohmann::json::object()}};
  const std::string msg = errorOf(effect);
  EXPECT_NE(msg.find("effects: effect id: the name 'my,drag" + why), std::string::npos) << msg;
}

TEST(ScenarioFile, BundledScenariosRead) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenarios)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.find(".model.") != std::string::npos) continue;
    const ScenarioFile f = readScenarioFile(entry.path().string());
    EXPECT_FALSE(f.scenario.pairs.empty()) << name;
    ++count;
  }
  EXPECT_GE(count, 5);
}

// A free mesh body lighter than a milligram at its density was most likely scaled twice: the
// 10 mm ball read "@mm" is a 10 µm ball of 3.3e-11 kg. The bundled scenarios warn about nothing.
TEST(ScenarioFile, AMeshBodyLighterThanAMilligramIsWarnedAbout) {
  nlohmann::json j = ballOnPlate();
  j["bodies"][1]["shape"] = std::string(VCONTACT_ASSETS_DIR) + "/meshes/ball_r10mm.stl@mm";
  const ScenarioFile twice = scenarioFromJson(j, "s.json", kScenarios);
  ASSERT_EQ(twice.warnings.size(), 1u);
  EXPECT_NE(twice.warnings[0].find("ball: the part weighs"), std::string::npos)
      << twice.warnings[0];
  EXPECT_NE(twice.warnings[0].find("less than a milligram"), std::string::npos);

  j["bodies"][1]["shape"] = std::string(VCONTACT_ASSETS_DIR) + "/meshes/ball_r10mm.stl";
  EXPECT_TRUE(scenarioFromJson(j, "s.json", kScenarios).warnings.empty());
  for (const auto& entry : std::filesystem::directory_iterator(kScenarios)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.find(".model.") != std::string::npos) continue;
    EXPECT_TRUE(readScenarioFile(entry.path().string()).warnings.empty()) << name;
  }
}

TEST(ScenarioFile, NamesFilePlaceAndExpectation) {
  struct Case {
    const char* pointer;
    nlohmann::json value;
    const char* fragment;
  };
  const std::vector<Case> cases = {
      {"/format", "vcontact.scenario/0", "s.json: format: expected \"vcontact.scenario/1\""},
      {"/duration", -1.0, "s.json: duration: expected a number in"},
      {"/bodies/1/shape", "sphere:-1", "bodies[1].shape"},
      {"/bodies/1/density", "heavy", "bodies[1].density: expected a number"},
      {"/bodies/1/motion", "floating", "bodies[1].motion: expected \"free\", \"fixed\" or"},
      {"/bodies/1/colour", "red", "bodies[1].colour: unknown key"},
      {"/pairs/0/b", "table", "pairs[0].b: no body named 'table'"},
      {"/pairs/0/method", "magic", "pairs[0].method"},
      {"/pairs/0/method", "fast",
       "s.json: pairs[0].method: bodies 'ball' and 'plate': cannot compute sphere R=0.01 against "
       "halfspace z<=0 with this method; it intersects two meshes"},
      {"/pairs/0/model/effects/glue", nlohmann::json::object(),
       "pairs[0].model.effects.glue: unknown effect"},
      {"/pairs/0/model/effects/stiffness/kv", -5.0,
       "pairs[0].model.effects.stiffness.kv: stiffness.kv = -5 is outside"},
      {"/tolerances", nlohmann::json{{"rel", 0.0}}, "tolerances.rel: expected a positive number"},
      {"/integrator", "euler", "s.json: integrator: expected \"dopri5\", \"bdf\" or \"discrete\""},
      {"/step", 0.1, "s.json: step: expected a number in [1e-06, 0.01]"},
      {"/impacts", "ignore", "s.json: impacts: expected \"auto\", \"resolve\" or \"implicit\""},
      {"/restitution_threshold", -0.1, "s.json: restitution_threshold: expected a number in"},
      {"/sleep", "soon", "s.json: sleep: expected false, true or an object"},
      {"/sleep", nlohmann::json{{"speed", 0.0}}, "s.json: sleep.speed: expected a number in"},
      {"/sleep", nlohmann::json{{"time", -1.0}}, "s.json: sleep.time: expected a number in"},
      {"/sleep", nlohmann::json{{"after", 1.0}}, "s.json: sleep.after: unknown key"},
      // Physical ranges (io/input_ranges.hpp) and types the issue 20 catalogue found accepted.
      {"/bodies/1/density", -7900.0,
       "bodies[1].density: expected a number in [0.1, 100000] kg/m^3, got -7900"},
      {"/bodies/1/density", 1e9, "bodies[1].density: expected a number in [0.1, 100000]"},
      {"/bodies/1/velocity", nlohmann::json::array({0, 0, 2e3}),
       "bodies[1].velocity: expected components within +-1000 m/s"},
      {"/bodies/1/angular_velocity", nlohmann::json::array({1e5, 0, 0}),
       "bodies[1].angular_velocity: expected components within +-10000 rad/s"},
      {"/bodies/1/pose", "0,0,0.015,", "bodies[1].pose: '' in '0,0,0.015,' is not a number"},
      {"/gravity", nlohmann::json::array({0, 0, -1e4}), "gravity: expected components within"},
      {"/duration", 1e7, "duration: expected a number in [1e-09, 1e+06] s, got 1e+07"},
      {"/output_rate", 1e9, "output_rate: expected a number in [1e-06, 1e+06] Hz"},
      {"/description", nlohmann::json{{"a", 1}}, "s.json: description: expected a string"},
  };
  for (const auto& c : cases) {
    nlohmann::json j = ballOnPlate();
    j[nlohmann::json::json_pointer(c.pointer)] = c.value;
    const std::string message = errorOf(j);
    EXPECT_NE(message.find(c.fragment), std::string::npos)
        << c.pointer << ": got \"" << message << "\"";
  }
  nlohmann::json threshold_of_resolve = ballOnPlate();
  threshold_of_resolve["impacts"] = "resolve";
  threshold_of_resolve["restitution_threshold"] = 0.1;
  EXPECT_NE(errorOf(threshold_of_resolve)
                .find("restitution_threshold: applies to \"impacts\": \"auto\" only"),
            std::string::npos);
  nlohmann::json mass_only = ballOnPlate();
  mass_only["bodies"][1].erase("density");
  EXPECT_NE(errorOf(mass_only).find("bodies[1]: a free body needs either \"density\""),
            std::string::npos);
}

// "sleep" (docs/SLEEP.md): on with its defaults unless the file says false; an object
// sets the quiet speed and time, each defaulting on its own.
TEST(ScenarioFile, SleepKeyReachesTheSettings) {
  const dynamics::SleepSettings defaults;
  nlohmann::json j = ballOnPlate();
  EXPECT_TRUE(scenarioFromJson(j, "s.json", kScenarios).scenario.settings.sleep.enabled);
  j["sleep"] = false;
  EXPECT_FALSE(scenarioFromJson(j, "s.json", kScenarios).scenario.settings.sleep.enabled);
  j["sleep"] = nlohmann::json{{"speed", 2e-4}};
  const dynamics::SleepSettings s =
      scenarioFromJson(j, "s.json", kScenarios).scenario.settings.sleep;
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.speed, 2e-4);
  EXPECT_EQ(s.time, defaults.time);
  j["sleep"] = nlohmann::json{{"time", 0.2}};
  EXPECT_EQ(scenarioFromJson(j, "s.json", kScenarios).scenario.settings.sleep.time, 0.2);
}

// Issue 20: the mesh file's error alone did not say which body of the scenario named it.
TEST(ScenarioFile, MissingMeshNamesTheScenarioKeyAndTheFile) {
  nlohmann::json j = ballOnPlate();
  j["bodies"][1]["shape"] = "meshes/nowhere.stl";
  const std::string message = errorOf(j);
  EXPECT_EQ(message.rfind("s.json: bodies[1].shape: ", 0), 0u) << message;
  EXPECT_NE(message.find("meshes/nowhere.stl: no such file"), std::string::npos) << message;
}

// A body given by mass and inertia: the tensor must be one a rigid body can have.
TEST(ScenarioFile, InertiaMustBePositiveDefiniteAndObeyTheTriangleInequality) {
  auto withInertia = [](const nlohmann::json& inertia) {
    nlohmann::json j = ballOnPlate();
    j["bodies"][1].erase("density");
    j["bodies"][1]["mass"] = 0.05;
    j["bodies"][1]["inertia"] = inertia;
    return errorOf(j);
  };
  EXPECT_NE(withInertia({1e-6, 1e-6, 5e-6}).find("violate the triangle inequality"),
            std::string::npos);
  EXPECT_NE(withInertia({1, 0, 0, 0, 1, 2, 0, 2, 1}).find("expected a positive definite tensor"),
            std::string::npos);
  EXPECT_NE(withInertia({-1e-6, 1e-6, 1e-6}).find("positive definite"), std::string::npos);
  // A thin plate: Izz = Ixx + Iyy exactly, allowed.
  EXPECT_EQ(withInertia({1e-6, 2e-6, 3e-6}), "");
}

// "friction": "distributed" (DISTRIBUTED_FRICTION.md): the method defaults to columns and may
// be no other; "columns" sets the fixed grid (default 64 lines per side) and is refused with
// lumped friction or out of [8, 512]; the model needs coulomb and cannot have bristle. Each
// message names the file, the pair's place and key, the pair and what was expected.
nlohmann::json distributedPunch() {
  nlohmann::json j = ballOnPlate();
  j["bodies"][1]["shape"] = "meshes/punch.stl";  // columns need a mesh (or a half-space)
  j["pairs"][0]["name"] = "punch-plate";
  j["pairs"][0]["friction"] = "distributed";
  j["pairs"][0]["model"]["effects"]["coulomb"] = {{"mu", 0.2}};
  return j;
}

// Four bodies, one pair listed, "contacts" for the rest (meshes from assets/scenarios/meshes).
nlohmann::json binOfParts() {
  return nlohmann::json::parse(R"({
    "format": "vcontact.scenario/1", "duration": 0.01,
    "models": {"steel": {"format": "vcontact.model/1",
                         "effects": {"stiffness": {"kv": 1e11}, "coulomb": {"mu": 0.2}}}},
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "fixture", "shape": "meshes/fixture.stl", "motion": "fixed"},
               {"name": "tray", "shape": "meshes/battery_box.stl", "density": 1200,
                "pose": "0,0,0.03"},
               {"name": "punch", "shape": "meshes/punch.stl", "density": 7900,
                "pose": "0.2,0,0.03"}],
    "pairs": [{"name": "tray-in-fixture", "a": "tray", "b": "fixture", "model": "steel",
               "method": "fast"}],
    "contacts": {"model": {"format": "vcontact.model/1",
                           "effects": {"stiffness": {"kv": 2e11}}}}})");
}

// "contacts" adds every pair not listed with at least one free body, the later body in
// "bodies" as the payload unless it is not free, the method left to each pair's shapes.
TEST(ScenarioFile, ContactsMakeEveryPairNotListed) {
  const ScenarioFile f = scenarioFromJson(binOfParts(), "s.json", kScenarios);
  const auto& pairs = f.scenario.pairs;
  struct Expected {
    const char* name;
    std::size_t a, b;
  };
  const std::vector<Expected> expected = {{"tray-in-fixture", 2, 1},
                                          {"tray-plate", 2, 0},
                                          {"punch-plate", 3, 0},
                                          {"punch-fixture", 3, 1},
                                          {"punch-tray", 3, 2}};
  ASSERT_EQ(pairs.size(), expected.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    EXPECT_EQ(pairs[k].name, expected[k].name) << k;
    EXPECT_EQ(pairs[k].a, expected[k].a) << k;
    EXPECT_EQ(pairs[k].b, expected[k].b) << k;
    EXPECT_EQ(pairs[k].method.has_value(), k == 0) << k;
    EXPECT_EQ(pairs[k].model.parameter("stiffness.kv"), k == 0 ? 1e11 : 2e11) << k;
  }
  // A fixed body listed after a free one is the plate of their pair, and "pairs" may be left
  // out when "contacts" is given.
  nlohmann::json j = binOfParts();
  j.erase("pairs");
  std::swap(j["bodies"][1], j["bodies"][2]);  // tray, then fixture
  const auto reordered = scenarioFromJson(j, "s.json", kScenarios).scenario.pairs;
  ASSERT_EQ(reordered.size(), 5u);
  EXPECT_EQ(reordered[1].name, "tray-fixture");
  EXPECT_EQ(reordered[1].a, 1u);
  EXPECT_EQ(reordered[1].b, 2u);

  // The run queries the two half-space pairs at every evaluation and screens the others: the
  // punch is 0.2 m from the tray and the fixture.
  dynamics::Scenario sc = f.scenario;
  sc.settings.duration = 2e-3;
  dynamics::SimulationSummary summary;
  test::run(sc, &summary);
  EXPECT_GE(summary.contact_evaluations, 2 * summary.rhs_evaluations);
  EXPECT_LE(summary.contact_evaluations, 3 * summary.rhs_evaluations);
}

TEST(ScenarioFile, ContactsErrorsNameThePlaceAndTheBodies) {
  nlohmann::json spheres = ballOnPlate();  // two sphere primitives: no method handles them
  spheres["bodies"].push_back(
      {{"name", "ball2"}, {"shape", "sphere:0.01"}, {"density", 7900}, {"pose", "0.1,0,0.0105"}});
  spheres["contacts"] = spheres["pairs"][0];
  spheres["contacts"].erase("a");
  spheres["contacts"].erase("b");
  const std::string noMethod = errorOf(spheres);
  EXPECT_NE(noMethod.find("s.json: contacts: bodies 'ball2' and 'ball'"), std::string::npos)
      << noMethod;
  EXPECT_NE(noMethod.find("list the pairs that can touch"), std::string::npos) << noMethod;

  nlohmann::json twice = binOfParts();
  twice["pairs"].push_back({{"a", "fixture"}, {"b", "tray"}, {"model", "steel"}});
  EXPECT_NE(errorOf(twice).find("pairs[1].b: bodies 'fixture' and 'tray' are already a pair "
                                "('tray-in-fixture')"),
            std::string::npos)
      << errorOf(twice);

  nlohmann::json sameName = binOfParts();
  sameName["pairs"][0]["name"] = "punch-tray";
  EXPECT_NE(errorOf(sameName).find("contacts: the pair name 'punch-tray' is used twice"),
            std::string::npos)
      << errorOf(sameName);

  nlohmann::json neither = binOfParts();
  neither.erase("pairs");
  neither.erase("contacts");
  EXPECT_NE(errorOf(neither).find("pairs: expected an array of pairs"), std::string::npos);

  nlohmann::json wrongMethod = binOfParts();
  wrongMethod["contacts"]["method"] = "fast";  // tray and punch against the half-space
  EXPECT_NE(errorOf(wrongMethod)
                .find("contacts.method: bodies 'tray' and 'plate': cannot "
                      "compute"),
            std::string::npos)
      << errorOf(wrongMethod);

  nlohmann::json unknown = binOfParts();
  unknown["contacts"]["a"] = "tray";
  EXPECT_NE(errorOf(unknown).find("contacts.a: unknown key"), std::string::npos)
      << errorOf(unknown);
}

TEST(ScenarioFile, DistributedFrictionDefaultsToColumnsAndAGridOf64) {
  const ScenarioFile f = scenarioFromJson(distributedPunch(), "s.json", kScenarios);
  const dynamics::ContactPair& pair = f.scenario.pairs[0];
  EXPECT_EQ(pair.friction, dynamics::FrictionMode::kDistributed);
  ASSERT_TRUE(pair.method.has_value());
  EXPECT_EQ(*pair.method, volume::Method::kColumns);
  EXPECT_EQ(pair.column_resolution, dynamics::kDefaultColumnResolution);
  EXPECT_EQ(pair.column_resolution, 64);
  nlohmann::json j = distributedPunch();
  j["pairs"][0]["columns"] = 96;
  j["pairs"][0]["method"] = "columns";
  EXPECT_EQ(scenarioFromJson(j, "s.json", kScenarios).scenario.pairs[0].column_resolution, 96);
  // Lumped is the default and "lumped" says so.
  nlohmann::json lumped = ballOnPlate();
  lumped["pairs"][0]["friction"] = "lumped";
  EXPECT_EQ(scenarioFromJson(lumped, "s.json", kScenarios).scenario.pairs[0].friction,
            dynamics::FrictionMode::kLumped);
}

TEST(ScenarioFile, DistributedFrictionErrorsNameThePairAndKey) {
  struct Case {
    const char* name;
    const char* pointer;
    nlohmann::json value;
    const char* fragment;
  };
  const nlohmann::json bristle = {{"sigma0", 4500}, {"sigma1", 300}};
  const std::vector<Case> cases = {
      {"unknown law", "/pairs/0/friction", "pointwise",
       "s.json: pairs[0].friction: expected \"lumped\" or \"distributed\", got \"pointwise\""},
      {"another method", "/pairs/0/method", "halfspace",
       "s.json: pairs[0].friction: pair 'punch-plate': distributed friction integrates over the "
       "columns method's δ map; set \"method\": \"columns\" (or leave it out), not "
       "\"halfspace\""},
      {"too coarse", "/pairs/0/columns", 4,
       "s.json: pairs[0].columns: pair 'punch-plate': expected an integer number of grid lines "
       "per side in [8, 512], got 4"},
      {"too fine", "/pairs/0/columns", 1024, "pairs[0].columns: pair 'punch-plate': expected an"},
      {"not an integer", "/pairs/0/columns", 64.5, "in [8, 512], got 64.5"},
      {"a string", "/pairs/0/columns", "64", "in [8, 512], got \"64\""},
      {"negative", "/pairs/0/columns", -64, "in [8, 512], got -64"},
      {"bristle", "/pairs/0/model/effects/bristle", bristle,
       "s.json: pairs[0].friction: pair 'punch-plate': distributed friction is pointwise Coulomb "
       "friction and cannot replace the bristle law"},
  };
  for (const auto& c : cases) {
    nlohmann::json j = distributedPunch();
    j[nlohmann::json::json_pointer(c.pointer)] = c.value;
    if (std::string(c.name) == "bristle")
      j["pairs"][0]["model"]["effects"]["stribeck"] = nlohmann::json::object();
    const std::string message = errorOf(j);
    EXPECT_NE(message.find(c.fragment), std::string::npos)
        << c.name << ": got \"" << message << "\"";
  }
  nlohmann::json primitive = distributedPunch();
  primitive["bodies"][1]["shape"] = "box:0.02,0.02,0.02";
  EXPECT_NE(errorOf(primitive).find("pairs[0].friction: bodies 'ball' and 'plate': cannot "
                                    "compute box"),
            std::string::npos)
      << errorOf(primitive);
  nlohmann::json no_coulomb = distributedPunch();
  no_coulomb["pairs"][0]["model"]["effects"].erase("coulomb");
  EXPECT_NE(errorOf(no_coulomb)
                .find("pairs[0].friction: pair 'punch-plate': distributed friction "
                      "integrates coulomb's friction pointwise; add the coulomb "
                      "effect"),
            std::string::npos)
      << errorOf(no_coulomb);
  nlohmann::json lumped_grid = distributedPunch();
  lumped_grid["pairs"][0]["friction"] = "lumped";
  lumped_grid["pairs"][0]["columns"] = 64;
  EXPECT_NE(errorOf(lumped_grid)
                .find("pairs[0].columns: pair 'punch-plate': the column grid "
                      "applies to \"friction\": \"distributed\" only"),
            std::string::npos)
      << errorOf(lumped_grid);
}

// The Simulator checks pairs built in code the same way (no reader in between).
TEST(ScenarioFile, SimulatorRefusesADistributedPairItCannotRun) {
  const auto distributed = [] {
    return scenarioFromJson(distributedPunch(), "s.json", kScenarios).scenario;
  };
  EXPECT_NO_THROW(dynamics::Simulator{distributed()});
  const auto messageOf = [](const dynamics::Scenario& s) -> std::string {
    try {
      dynamics::Simulator sim(s);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  dynamics::Scenario method = distributed();
  method.pairs[0].method = volume::Method::kHalfspace;
  EXPECT_NE(messageOf(method).find("pair 'punch-plate': distributed friction needs the columns "
                                   "method, not halfspace"),
            std::string::npos)
      << messageOf(method);
  dynamics::Scenario grid = distributed();
  grid.pairs[0].column_resolution = 2;
  EXPECT_NE(messageOf(grid).find("pair 'punch-plate': column resolution 2 is outside [8, 512]"),
            std::string::npos)
      << messageOf(grid);
  dynamics::Scenario model = distributed();
  model.pairs[0].model = dynamics::Model::withEffects({"stiffness"});
  EXPECT_NE(messageOf(model).find("pair 'punch-plate': distributed friction integrates coulomb"),
            std::string::npos)
      << messageOf(model);
}

// A contact far too soft for the ball: it sinks past 10 % of its size and the run stops with
// the time, the pair and the quantity, after delivering every output before the stop.
TEST(ScenarioFile, FailingRunStopsWithTimePairAndQuantity) {
  for (const char* integrator : {"dopri5", "bdf"}) {
    nlohmann::json j = ballOnPlate();
    j["pairs"][0]["model"]["effects"]["stiffness"]["kv"] = 1e3;
    j["duration"] = 1.0;
    j["integrator"] = integrator;
    const ScenarioFile f = scenarioFromJson(j, "s.json", kScenarios);
    dynamics::Simulator sim(f.scenario);
    std::vector<double> times;
    dynamics::SimulationSummary summary;
    try {
      sim.run([&](const dynamics::Snapshot& s) { times.push_back(s.t); }, [](double) {}, summary);
      ADD_FAILURE() << integrator << ": the run should have stopped";
    } catch (const dynamics::SimulationError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("pair 'ball-plate': mean penetration V/A"), std::string::npos)
          << message;
      EXPECT_EQ(message.rfind("t = ", 0), 0u) << message;
      ASSERT_FALSE(times.empty()) << integrator;
      EXPECT_LE(times.back(), e.time()) << integrator;
      EXPECT_GT(times.size(), 10u) << integrator;  // it fell ~0.5 mm before touching
      EXPECT_EQ(summary.simulated_time, e.time()) << integrator;
    }
  }
}

// A minimum step far above what the impact needs (kv = 1e15 N/m³: the ball's contact lasts
// ~7 µs): both integrators stop on the step-size collapse, naming the time, the pair with its
// normal force, and the step size.
TEST(ScenarioFile, StepSizeCollapseNamesThePair) {
  for (const char* integrator : {"dopri5", "bdf"}) {
    nlohmann::json j = ballOnPlate();
    j["integrator"] = integrator;
    j["duration"] = 0.05;
    j["pairs"][0]["model"]["effects"]["stiffness"]["kv"] = 1e15;
    j["tolerances"] = {{"min_step", 1e-5}, {"initial_step", 1e-5}};
    const ScenarioFile f = scenarioFromJson(j, "s.json", kScenarios);
    dynamics::Simulator sim(f.scenario);
    dynamics::SimulationSummary summary;
    try {
      sim.run([](const dynamics::Snapshot&) {}, [](double) {}, summary);
      ADD_FAILURE() << integrator << ": the run should have stopped";
    } catch (const dynamics::SimulationError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("t = ", 0), 0u) << message;
      EXPECT_NE(message.find(", pair 'ball-plate' (normal force "), std::string::npos) << message;
      EXPECT_NE(message.find("fell below the minimum 1e-05 s"), std::string::npos) << message;
      // The ball touches after falling 0.5 mm, at sqrt(2 · 0.5 mm / g) = 10.1 ms.
      EXPECT_GT(e.time(), 0.0100) << message;
      EXPECT_GT(summary.rejected_steps, 0) << integrator;
    }
  }
}

// The bundled tippe top turns over: its symmetry axis goes from +z to below −0.9 z within
// 1.5 s (the inverted state is stable for 1 − α < I3/I1 < 1 + α at this spin).
// The z component of the top's symmetry axis after 1.5 s of the scenario.
double topAxisZAfterRun(dynamics::Scenario scenario) {
  scenario.settings.duration = 1.5;
  dynamics::Simulator sim(scenario);
  double axis_z = 1.0;
  dynamics::SimulationSummary summary;
  sim.run([&](const dynamics::Snapshot& s) { axis_z = s.bodies[1].X_WB.linear()(2, 2); },
          [](double) {}, summary);
  return axis_z;
}

TEST(ScenarioFile, TippeTopInverts) {
  const ScenarioFile f = readScenarioFile(kScenarios + "/tippe_top.json");
  // from +0.995; the scenario reaches −0.96 at 1 s, −0.99 at 2 s
  EXPECT_LT(topAxisZAfterRun(f.scenario), -0.9);
}

// With the discrete stepper at 1 ms, its impacts resolved when they rebound (the default), all
// of them or none, it turns over too (earlier than Dormand–Prince: docs/DISCRETE.md §4);
// "impacts" and "restitution_threshold" reach the settings.
TEST(ScenarioFile, TippeTopInvertsWithTheDiscreteStepper) {
  const std::vector<std::pair<const char*, dynamics::ImpactMode>> modes = {
      {"auto", dynamics::ImpactMode::kAuto},
      {"resolve", dynamics::ImpactMode::kResolve},
      {"implicit", dynamics::ImpactMode::kImplicit}};
  for (const auto& [mode, expected] : modes) {
    ScenarioFile f = readScenarioFile(kScenarios + "/tippe_top.json");
    nlohmann::json j = ballOnPlate();
    j["impacts"] = mode;
    const ScenarioFile settings = scenarioFromJson(j, "s.json", kScenarios);
    f.scenario.settings.integrator = dynamics::Integrator::kDiscrete;
    f.scenario.settings.impacts = settings.scenario.settings.impacts;
    EXPECT_EQ(f.scenario.settings.impacts, expected) << mode;
    EXPECT_LT(topAxisZAfterRun(f.scenario), -0.9) << mode;
  }
  EXPECT_EQ(scenarioFromJson(ballOnPlate(), "s.json", kScenarios).scenario.settings.impacts,
            dynamics::ImpactMode::kAuto);
  nlohmann::json j = ballOnPlate();
  j["restitution_threshold"] = 0.25;
  EXPECT_EQ(scenarioFromJson(j, "s.json", kScenarios).scenario.settings.restitution_threshold,
            0.25);
}

}  // namespace
}  // namespace vcontact::formats
