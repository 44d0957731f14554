// "surface": "recovered" on a scenario body (docs/SCENARIO.md, "Recovered surfaces"): the
// key's checks, what the run's summary records, and the bundled rolling ball from a
// 2,000-triangle mesh against the analytic sphere.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "io/shape_spec.hpp"
#include "report/simulation_summary.hpp"
#include "volume/contact.hpp"
#include "volume/recovered/recovered_surface.hpp"

namespace vcontact::formats {
namespace {

const std::string kScenarios = std::string(VCONTACT_ASSETS_DIR) + "/scenarios";
const std::string kBall2k = std::string(VCONTACT_ASSETS_DIR) + "/meshes/ball_r10mm_2k.stl";

// A 2,000-triangle ball resting on a plate, and a second one resting on the first.
nlohmann::json twoBallsOnPlate(const std::string& surface) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "format": "vcontact.scenario/1", "duration": 0.002, "output_rate": 1000,
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "density": 7900, "pose": "0,0,0.0099985"},
               {"name": "top", "density": 7900, "pose": "0,0,0.02999"}],
    "pairs": [{"a": "ball", "b": "plate", "model": "steel_on_aluminium.model.json"},
              {"a": "top", "b": "ball", "model": "steel_on_aluminium.model.json"}]})");
  for (int i : {1, 2}) j["bodies"][i]["shape"] = kBall2k;
  j["bodies"][1]["surface"] = surface;
  return j;
}

std::string errorOf(const nlohmann::json& j) {
  try {
    scenarioFromJson(j, "s.json", kScenarios);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioSurface, AnUnknownRepresentationNamesTheKeyAndTheChoices) {
  const std::string e = errorOf(twoBallsOnPlate("analytic"));
  EXPECT_NE(e.find("s.json"), std::string::npos) << e;
  EXPECT_NE(e.find("surface"), std::string::npos) << e;
  EXPECT_NE(e.find("expected \"mesh\""), std::string::npos) << e;
  EXPECT_NE(e.find("\"recovered\""), std::string::npos) << e;
}

TEST(ScenarioSurface, RecoveredIsRefusedOnAPrimitive) {
  nlohmann::json j = twoBallsOnPlate("mesh");
  j["bodies"][1]["shape"] = "sphere:0.01";
  j["bodies"][1]["surface"] = "recovered";
  const std::string e = errorOf(j);
  EXPECT_NE(e.find("applies to a mesh body; a sphere"), std::string::npos) << e;
}

// "mesh" is the default and leaves the body as it was: no recognition, no summary section.
TEST(ScenarioSurface, MeshIsTheDefault) {
  nlohmann::json j = twoBallsOnPlate("mesh");
  const ScenarioFile explicitMesh = scenarioFromJson(j, "s.json", kScenarios);
  j["bodies"][1].erase("surface");
  const ScenarioFile unset = scenarioFromJson(j, "s.json", kScenarios);
  EXPECT_EQ(explicitMesh.scenario.bodies[1].surface, nullptr);
  EXPECT_EQ(unset.scenario.bodies[1].surface, nullptr);
  dynamics::Simulator sim(unset.scenario);
  dynamics::SimulationSummary summary;
  sim.run([](const dynamics::Snapshot&) {}, [](double) {}, summary);
  EXPECT_TRUE(summary.surface_bodies.empty());
  EXPECT_FALSE(report::simulationSummaryJson(summary, "s.json").contains("surfaces"));
}

// The summary records per body what recognition found, and per pair which representation its
// queries used: the ball on the plate answers on its sphere at every query; the ball under the
// second ball (a mesh) is queried by the same `recovered` row, which has no closed form for two
// spheres and falls back to the polyhedra (`fast`) at every query, saying why; a pair that asks
// for another method (cgal) is on the polyhedra throughout, and says why.
TEST(ScenarioSurface, TheSummaryRecordsRecognitionAndRepresentations) {
  const ScenarioFile f = scenarioFromJson(twoBallsOnPlate("recovered"), "s.json", kScenarios);
  ASSERT_NE(f.scenario.bodies[1].surface, nullptr);
  dynamics::Simulator sim(f.scenario);
  dynamics::SimulationSummary summary;
  sim.run([](const dynamics::Snapshot&) {}, [](double) {}, summary);
  const nlohmann::json j = report::simulationSummaryJson(summary, "s.json")["surfaces"];
  ASSERT_EQ(j["bodies"].size(), 1u);
  EXPECT_EQ(j["bodies"][0]["body"], "ball");
  EXPECT_EQ(j["bodies"][0]["surfaces"], nlohmann::json({{"sphere", 1}}));
  EXPECT_EQ(j["bodies"][0]["free_form_faces"], 0);
  EXPECT_GT(j["bodies"][0]["recognition_time_s"].get<double>(), 0.0);
  ASSERT_EQ(j["pairs"].size(), 2u);
  EXPECT_EQ(j["pairs"][0]["representation"], "recovered");
  EXPECT_EQ(j["pairs"][0]["evaluations"], nlohmann::json({{"sphere", summary.rhs_evaluations}}));
  EXPECT_EQ(j["pairs"][1]["representation"], "recovered");
  EXPECT_EQ(j["pairs"][1]["evaluations"].size(), 1u);
  EXPECT_GT(j["pairs"][1]["evaluations"]["mesh"].get<long>(), 0);
  ASSERT_EQ(j["pairs"][1]["mesh_fallbacks"].size(), 1u) << j["pairs"][1];
  EXPECT_NE(j["pairs"][1]["mesh_fallbacks"][0].get<std::string>().find(
                "the pin is not one solid of revolution"),
            std::string::npos)
      << j["pairs"][1];

  nlohmann::json cgal = twoBallsOnPlate("recovered");
  cgal["pairs"][1]["method"] = "cgal";
  cgal["duration"] = 0.0002;  // a few corefinements
  cgal["output_rate"] = 10000;
  const ScenarioFile g = scenarioFromJson(cgal, "s.json", kScenarios);
  dynamics::Simulator other(g.scenario);
  dynamics::SimulationSummary otherSummary;
  other.run([](const dynamics::Snapshot&) {}, [](double) {}, otherSummary);
  const nlohmann::json k = report::simulationSummaryJson(otherSummary, "s.json")["surfaces"];
  ASSERT_EQ(k["pairs"].size(), 2u);
  EXPECT_EQ(k["pairs"][1]["representation"], "mesh");
  EXPECT_NE(k["pairs"][1]["why_mesh"].get<std::string>().find("asks for method 'cgal'"),
            std::string::npos)
      << k["pairs"][1];
  EXPECT_GT(k["pairs"][1]["evaluations"]["mesh"].get<long>(), 0);
}

struct RunOutput {
  std::vector<dynamics::Snapshot> outputs;
  dynamics::SimulationSummary summary;
};

RunOutput run(const dynamics::Scenario& s) {
  RunOutput r;
  dynamics::Simulator sim(s);
  sim.run([&](const dynamics::Snapshot& o) { r.outputs.push_back(o); }, [](double) {}, r.summary);
  return r;
}

// Largest difference of f(output) between two runs, over their common output times.
template <class F>
double largestDifference(const RunOutput& a, const RunOutput& b, F f) {
  double d = 0.0;
  for (std::size_t i = 0; i < std::min(a.outputs.size(), b.outputs.size()); ++i)
    d = std::max(d, std::abs(f(a.outputs[i]) - f(b.outputs[i])));
  return d;
}

// The bundled ball_roll_recovered.json (a 2,000-triangle STL ball rolling at 0.2 m/s) against
// the same scenario with the analytic sphere in its place, and with the polyhedron.
// The bundled peg on its recovered surface, tilted 5° in the bundled block: the simulation's
// query is the volume command's (the method table's `recovered` row), so its first output has
// the same two patches, to the bit, as computeContact at that pose, and the summary counts the
// slices of a pin in a bore.
TEST(ScenarioRecovered, TiltedPegHasTheVolumeCommandsTwoPatches) {
  const std::string meshes = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/meshes/";
  const std::string pose = "0,-0.00116,0.0118,5,0,0";
  nlohmann::json j = nlohmann::json::parse(R"({
    "format": "vcontact.scenario/1", "duration": 0.0001, "output_rate": 10000,
    "gravity": [0, 0, 0],
    "bodies": [{"name": "block", "motion": "fixed"},
               {"name": "peg", "density": 7800, "surface": "recovered"}],
    "pairs": [{"a": "peg", "b": "block", "model": "steel_on_aluminium.model.json"}]})");
  j["bodies"][0]["shape"] = meshes + "block_hole_d10.stl";
  j["bodies"][1]["shape"] = meshes + "peg_d10.stl";
  j["bodies"][1]["pose"] = pose;
  const ScenarioFile f = scenarioFromJson(j, "s.json", kScenarios);
  dynamics::Simulator sim(f.scenario);
  dynamics::SimulationSummary summary;
  std::vector<dynamics::PairOutput> first;
  sim.run(
      [&](const dynamics::Snapshot& s) {
        if (first.empty()) first = s.pairs;
      },
      [](double) {}, summary);
  ASSERT_EQ(first.size(), 1u);
  volume::QueryOptions query;
  query.method = volume::Method::kRecovered;
  const volume::ContactPatches expected =
      volume::computeContact(f.scenario.bodies[1].shape, io::parsePose(pose, "pose"),
                             f.scenario.bodies[0].shape, Eigen::Isometry3d::Identity(), query);
  ASSERT_EQ(expected.patches.size(), 2u);
  ASSERT_EQ(first[0].patches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(first[0].patches[i].cv.volume, expected.patches[i].volume) << i;
    EXPECT_EQ(first[0].patches[i].cv.p_WC, expected.patches[i].p_WC) << i;
    EXPECT_EQ(first[0].patches[i].cv.n_W, expected.patches[i].n_W) << i;
  }
  ASSERT_EQ(summary.surface_pairs.size(), 1u);
  EXPECT_TRUE(summary.surface_pairs[0].polyhedral_reason.empty());
  EXPECT_GT(summary.surface_pairs[0].evaluations.at("revolution_in_bore"), 0);
}

TEST(ScenarioRecovered, BallRollTracksTheAnalyticSphere) {
  const ScenarioFile f = readScenarioFile(kScenarios + "/ball_roll_recovered.json");
  dynamics::Scenario analytic = f.scenario, polyhedral = f.scenario;
  const double R = 0.01;  // m, the radius the mesh was tessellated at
  analytic.bodies[1].shape = geometry::Sphere{R};
  analytic.bodies[1].surface = nullptr;
  polyhedral.bodies[1].surface = nullptr;
  const RunOutput recovered = run(f.scenario), sphere = run(analytic), mesh = run(polyhedral);
  ASSERT_EQ(recovered.outputs.size(), 1001u);
  ASSERT_EQ(sphere.outputs.size(), 1001u);

  // The recovered sphere lies within δ of the true one: the fit's largest vertex residual plus
  // the STL's rounding of a coordinate of 10 mm (single precision, 2^-24 of it).
  const double delta = f.scenario.bodies[1].surface->recognition.surfaces.at(0).max_residual +
                       R * std::ldexp(1.0, -24);
  // Started from the same pose, the centre's height differs by at most δ (the offset of the
  // surface) twice: once in the rest height, once in the amplitude of the ringing it starts.
  const auto z = [](const dynamics::Snapshot& s) { return s.bodies[1].p_WBcm.z(); };
  EXPECT_LE(largestDifference(recovered, sphere, z), 2.0 * delta);
  // The normal force then differs by the contact stiffness k = dF/dd = kv π (2Rd − d²) at the
  // static penetration d = 1.414 µm (MODEL.md §5) times that height difference.
  const double kv = 5.17e12, d = 1.41378e-6;
  const double k = kv * M_PI * (2.0 * R * d - d * d);  // N/m, ≈ 4.6e5
  const auto fn = [](const dynamics::Snapshot& s) { return s.pairs[0].result.f_n; };
  EXPECT_LE(largestDifference(recovered, sphere, fn), k * 2.0 * delta);
  // Along the path the ball loses Δv = 7e-5 m/s to rolling resistance and friction, forces of
  // the contact's size, which the offset changes by the relative δ/d at most: the speed
  // differs by no more than Δv δ/d, the position by that times the duration (1 s).
  const auto vx = [](const dynamics::Snapshot& s) { return s.bodies[1].v_WBcm.x(); };
  const auto x = [](const dynamics::Snapshot& s) { return s.bodies[1].p_WBcm.x(); };
  const double dv =
      sphere.outputs.front().bodies[1].v_WBcm.x() - sphere.outputs.back().bodies[1].v_WBcm.x();
  EXPECT_GT(dv, 0.0);
  EXPECT_LE(largestDifference(recovered, sphere, vx), dv * delta / d);
  EXPECT_LE(largestDifference(recovered, sphere, x), dv * delta / d * 1.0);
  // Every query was the sphere's closed form.
  ASSERT_EQ(recovered.summary.surface_pairs.size(), 1u);
  EXPECT_EQ(recovered.summary.surface_pairs[0].evaluations,
            (std::map<std::string, long>{{"sphere", recovered.summary.contact_evaluations}}));

  // The polyhedron's chords lie up to 44 µm inside the sphere, thirty times the penetration:
  // its run clatters over the facets, off by orders of magnitude more than the bound.
  EXPECT_GT(largestDifference(mesh, sphere, z), 1e3 * delta);
  EXPECT_GT(largestDifference(mesh, sphere, fn), 0.5 * fn(sphere.outputs.back()));
}

}  // namespace
}  // namespace vcontact::formats
