// Whole simulations of the bundled scenarios (assets/scenarios), without output:
// simulate/<scenario> with the scenario's own integrator, simulate/<scenario>/<integrator> as
// the A/B pair of Dormand–Prince and BDF on the same scenario. Counters: real_time_factor
// (simulated seconds per CPU second), steps, contact evaluations (Jacobians' included) and
// Jacobians per run, output samples, and the final height of the last body (m) as a sanity
// figure beside the time.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>
#include <string>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"

namespace {

using vcontact::dynamics::Integrator;
using vcontact::dynamics::SimulationSummary;
using vcontact::dynamics::Simulator;
using vcontact::dynamics::Snapshot;

// The scenarios live next to this source tree's benchmarks/ folder.
std::string scenarioPath(const std::string& name) {
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "assets" / "scenarios" /
          (name + ".json"))
      .string();
}

void simulate(benchmark::State& state, const std::string& name,
              std::optional<Integrator> integrator) {
  vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(scenarioPath(name));
  if (integrator) file.scenario.settings.integrator = *integrator;
  double simulated = 0.0, final_height = 0.0;
  long steps = 0, contacts = 0, jacobians = 0, samples = 0;
  for (auto _ : state) {
    Simulator sim(file.scenario);
    SimulationSummary summary;
    Snapshot last;
    samples = 0;
    sim.run(
        [&](const Snapshot& s) {
          last = s;
          ++samples;
        },
        [](double) {}, summary);
    simulated += summary.simulated_time;
    steps = summary.steps;
    contacts = summary.contact_evaluations;
    jacobians = summary.jacobian_evaluations;
    final_height = last.bodies.back().p_WBcm.z();
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["contact_evals"] = static_cast<double>(contacts);
  state.counters["jacobians"] = static_cast<double>(jacobians);
  state.counters["outputs"] = static_cast<double>(samples);
  state.counters["final_z_m"] = final_height;
}

void registerScenario(const std::string& name) {
  const std::pair<const char*, std::optional<Integrator>> variants[] = {
      {"", std::nullopt}, {"/dopri5", Integrator::kDopri5}, {"/bdf", Integrator::kBdf}};
  for (const auto& [suffix, integrator] : variants) {
    benchmark::RegisterBenchmark(("simulate/" + name + suffix).c_str(), simulate, name, integrator)
        ->Unit(benchmark::kMillisecond);
  }
}

[[maybe_unused]] const bool kRegistered = [] {
  for (const char* name : {"ball_drop", "ball_roll", "tippe_top", "punch_slide_spin"}) {
    registerScenario(name);
  }
  // Two meshes, fast method, 2 kHz output: the CAD-part target (>= 1x at 1 kHz).
  benchmark::RegisterBenchmark("simulate/battery_box_fixture", simulate,
                               std::string("battery_box_fixture"), std::nullopt)
      ->Unit(benchmark::kMillisecond);
  // The same target on meshes of the size the issue names: two 12.8k-triangle trays and a
  // fixture, three fast pairs, 1 kHz output. Seconds per run: one iteration is enough.
  benchmark::RegisterBenchmark("simulate/cad_tray_drop", simulate, std::string("cad_tray_drop"),
                               std::nullopt)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  return true;
}();

}  // namespace
