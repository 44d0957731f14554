// Whole simulations of the bundled scenarios (assets/scenarios), without output:
// simulation/<scenario>. Counters: real_time_factor (simulated seconds per CPU second),
// steps and contact evaluations per run, and the final height of the first free body (m) as
// a sanity figure beside the time.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "dynamics/simulator.hpp"
#include "io/scenario_file.hpp"

namespace {

using vcontact::dynamics::Simulator;
using vcontact::dynamics::SimulationSummary;
using vcontact::dynamics::Snapshot;

// The scenarios live next to this source tree's benchmarks/ folder.
std::string scenarioPath(const std::string& name) {
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "assets" / "scenarios" /
          (name + ".json"))
      .string();
}

void simulate(benchmark::State& state, const std::string& name) {
  const vcontact::io::ScenarioFile file = vcontact::io::readScenarioFile(scenarioPath(name));
  double simulated = 0.0, final_height = 0.0;
  long steps = 0, contacts = 0;
  for (auto _ : state) {
    Simulator sim(file.scenario);
    SimulationSummary summary;
    Snapshot last;
    sim.run([&](const Snapshot& s) { last = s; }, [](double) {}, summary);
    simulated += summary.simulated_time;
    steps = summary.steps;
    contacts = summary.contact_evaluations;
    final_height = last.bodies.back().p_WBcm.z();
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["contact_evals"] = static_cast<double>(contacts);
  state.counters["final_z_m"] = final_height;
}

}  // namespace

BENCHMARK_CAPTURE(simulate, ball_drop, std::string("ball_drop"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulate, ball_roll, std::string("ball_roll"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulate, tippe_top, std::string("tippe_top"))->Unit(benchmark::kMillisecond);
