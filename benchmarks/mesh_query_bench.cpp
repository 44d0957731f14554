// The fast mesh–mesh query as a simulation runs it (issue 18, item 4; docs/DISCRETE.md §4.2):
// the poses of cad_tray_drop's bodies along its discrete run (h = 1 ms, 0.2 s; the trays land
// by 0.05 s and rest from about 0.08 s on), recorded once per process outside the timed loops.
//
// query/cad_tray/<pair>/<phase>/<variant>, pair tray-fixture or upper-tray:
//   phase rest: the pose at 0.2 s, every query at that pose;
//   phase path: the poses of the resting phase (0.1–0.2 s, 101 poses) visited forth and back,
//     one query per pose, as the stepper makes them (one per step);
//   variants: cold (no cache: both trees descended every query), cached (the pair's
//     MeshMeshCache of leaf pairs, as the simulator passes it), cached_depth (the same with the
//     exact depth pass, as at an output time).
// query/cad_tray/<pair>/<rest|landing>/depth_reference and depth: the depth pass alone at the
//   rest pose or at the first pose in contact from 23 ms on (the landing), on the boundary segments
//   of the query (its last patch's) (the pass of 89ea7e6, kept in the tests as
//   ReferenceColumnDepth, against volume/depth/deepest_column.cpp).
// Counters: V (m³), the leaf pairs the cache holds, its refreshes and its plain descents (after
// a recording no query reused), so that a fast wrong answer shows beside its time.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "tests/volume/depth/deepest_column_reference.hpp"  // the old pass
#include "volume/depth/deepest_column.hpp"
#include "volume/fast/intersector.hpp"
#include "volume/fast/surface_integration.hpp"

namespace {

using Eigen::Isometry3d;
using vcontact::dynamics::Integrator;
using vcontact::dynamics::Scenario;
using vcontact::dynamics::SimulationSummary;
using vcontact::dynamics::Simulator;
using vcontact::dynamics::Snapshot;
using vcontact::volume::MeshMeshCache;

/// The scenario and its bodies' poses at every millisecond of the discrete run.
struct Trajectory {
  Scenario scenario;
  std::vector<std::vector<Isometry3d>> poses;  ///< [output][body]
};

const Trajectory& trayTrajectory() {
  static const Trajectory trajectory = [] {
    const auto path = std::filesystem::path(__FILE__).parent_path().parent_path() / "assets" /
                      "scenarios" / "cad_tray_drop.json";
    Trajectory t{vcontact::formats::readScenarioFile(path.string()).scenario, {}};
    t.scenario.settings.integrator = Integrator::kDiscrete;
    t.scenario.settings.step = 1e-3;
    t.scenario.settings.duration = 0.2;
    t.scenario.settings.output_rate_hz = 1000.0;
    Simulator sim(t.scenario);
    sim.setOutputDepths(false);  // the poses only
    SimulationSummary summary;
    sim.run(
        [&](const Snapshot& s) {
          std::vector<Isometry3d>& row = t.poses.emplace_back();
          for (const auto& b : s.bodies) row.push_back(b.X_WB);
        },
        [](double) {}, summary);
    return t;
  }();
  return trajectory;
}

enum class Variant { kCold, kCached, kCachedDepth };

/// Queries of pair k at the poses `first .. last` of the trajectory, forth and back.
void query(benchmark::State& state, std::size_t k, std::size_t first, std::size_t last,
           Variant variant) {
  const Trajectory& t = trayTrajectory();
  const auto& pair = t.scenario.pairs[k];
  const auto& shapeA = t.scenario.bodies[pair.a].shape;
  const auto& shapeB = t.scenario.bodies[pair.b].shape;
  MeshMeshCache cache;
  MeshMeshCache* c = variant == Variant::kCold ? nullptr : &cache;
  const bool deepest = variant == Variant::kCachedDepth;
  std::size_t i = first;
  long direction = 1;
  vcontact::volume::ContactVolume cv;
  for (auto _ : state) {
    const auto& X = t.poses[i];
    cv = vcontact::volume::fastContact(shapeA, X[pair.a], shapeB, X[pair.b], c, deepest).aggregate;
    benchmark::DoNotOptimize(cv);
    if (first != last) {
      if ((direction > 0 && i == last) || (direction < 0 && i == first)) direction = -direction;
      i = static_cast<std::size_t>(static_cast<long>(i) + direction);
    }
  }
  state.counters["V"] = cv.volume;
  state.counters["leaf_pairs"] = static_cast<double>(cache.leafPairs.size());
  state.counters["refreshes"] = static_cast<double>(cache.refreshes);
  state.counters["plain"] = static_cast<double>(cache.plain);
}

/// The depth pass alone on the segments of pair k's query at pose `at` of the trajectory: the
/// current pass (ColumnDepth) or the reference (the pass of 89ea7e6).
template <typename Pass>
void depthPass(benchmark::State& state, std::size_t k, std::size_t at) {
  const Trajectory& t = trayTrajectory();
  const auto& pair = t.scenario.pairs[k];
  const auto contact = [&](std::size_t i) {
    const auto& X = t.poses[i];
    return vcontact::volume::fastContact(t.scenario.bodies[pair.a].shape, X[pair.a],
                                         t.scenario.bodies[pair.b].shape, X[pair.b], nullptr, true)
        .aggregate.inContact();
  };
  // The first pose in contact from `at` on (the pair bounces during the landing).
  while (!contact(at) && at + 1 < t.poses.size()) ++at;
  state.counters["pose_ms"] = static_cast<double>(at);
  const vcontact::volume::ColumnDepth& last = vcontact::volume::internal::lastDepthPass();
  const auto inputs = last.inputs();
  const auto args = last.lastArguments();
  Pass pass;
  double d = 0.0;
  for (auto _ : state) {
    pass.clear();
    for (const auto& in : inputs) pass.add(in.key, in.n_f, in.p, in.q);
    d = pass.deepest(args.n, args.o, args.scale);
    benchmark::DoNotOptimize(d);
  }
  state.counters["depth"] = d;
  state.counters["segments"] = static_cast<double>(inputs.size());
}

[[maybe_unused]] const bool kRegistered = [] {
  const std::pair<const char*, Variant> variants[] = {{"cold", Variant::kCold},
                                                      {"cached", Variant::kCached},
                                                      {"cached_depth", Variant::kCachedDepth}};
  const std::pair<const char*, std::size_t> pairs[] = {{"tray-fixture", 0}, {"upper-tray", 1}};
  for (const auto& [pairName, k] : pairs) {
    for (const auto& [variantName, variant] : variants) {
      const std::string base = std::string("query/cad_tray/") + pairName;
      // 201 outputs (0 .. 0.2 s): the rest pose is the last, the resting phase the last 101.
      benchmark::RegisterBenchmark((base + "/rest/" + variantName).c_str(), query, k, 200, 200,
                                   variant)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark((base + "/path/" + variantName).c_str(), query, k, 100, 200,
                                   variant)
          ->Unit(benchmark::kMicrosecond);
    }
    // The rest pose (0.2 s) and the first pose in contact from 23 ms on (the landing: the
    // tray's pins in the chamfers, the upper tray tilted on the rim).
    for (const auto& [phase, at] : {std::pair<const char*, std::size_t>{"rest", 200},
                                    std::pair<const char*, std::size_t>{"landing", 23}}) {
      const std::string depth = std::string("query/cad_tray/") + pairName + "/" + phase + "/depth";
      benchmark::RegisterBenchmark((depth + "_reference").c_str(),
                                   depthPass<vcontact::volume::test::ReferenceColumnDepth>, k, at)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(depth.c_str(), depthPass<vcontact::volume::ColumnDepth>, k, at)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  return true;
}();

}  // namespace
