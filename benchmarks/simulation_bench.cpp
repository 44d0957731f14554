// Whole simulations of the bundled scenarios (assets/scenarios), without output:
// simulate/<scenario> with the scenario's own integrator, simulate/<scenario>/<integrator> as
// the A/B pair of Dormand–Prince and BDF on the same scenario, and
// simulate/<scenario>/discrete_<h> for the fixed-step discrete integrator against the
// Dormand–Prince run (docs/DISCRETE.md §4), its impacts resolved (the default) or, with the
// suffix _implicit, left to the plain step (§5); the suffix _general runs the same steps
// without the per-step shortcuts (Simulator::setStepShortcuts(false), the same numbers), the
// "before" of §4.4 in the same run. The discrete runs sleep by default (§7);
// discrete_1ms_implicit_nosleep is that run with "sleep": false, and
// cad_tray_drop/discrete_1ms_implicit_prebuilt that run with each Simulator built outside the
// timed region. Counters: real_time_factor
// (simulated seconds per CPU second), steps, contact evaluations (Jacobians' included) and
// Jacobians per run, output samples, and the final height of the last body (m) as a sanity
// figure beside the time; the discrete runs add skipped_queries (sleep's), asleep_at_end
// (bodies asleep when the run ends) and last_asleep_s (when the last of them fell asleep).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"

namespace {

using vcontact::dynamics::ImpactMode;
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

// The last snapshot of a run of `scenario` (all outputs skipped but the last).
Snapshot finalSnapshot(const vcontact::dynamics::Scenario& scenario) {
  Simulator sim(scenario);
  SimulationSummary summary;
  Snapshot last;
  sim.run([&](const Snapshot& s) { last = s; }, [](double) {}, summary);
  return last;
}

// The Dormand–Prince run of the scenario at its own tolerances, once per process: the
// reference of the discrete stepper's rest pose (counter rest_diff_m).
const Snapshot& reference(const std::string& name) {
  static std::map<std::string, Snapshot> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(scenarioPath(name));
  file.scenario.settings.integrator = Integrator::kDopri5;
  return cache.emplace(name, finalSnapshot(file.scenario)).first->second;
}

// Largest distance between the centres of mass of `a` and `b` (m), and largest speed in `s`.
double largestDistance(const Snapshot& a, const Snapshot& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.bodies.size() && i < b.bodies.size(); ++i)
    d = std::max(d, (a.bodies[i].p_WBcm - b.bodies[i].p_WBcm).norm());
  return d;
}
double largestSpeed(const Snapshot& s) {
  double v = 0.0;
  for (const auto& b : s.bodies) v = std::max(v, b.v_WBcm.norm());
  return v;
}

// The discrete stepper at step h against the Dormand–Prince reference of the same scenario,
// in the same process: counters rest_diff_m (largest distance between the bodies' final
// centres of mass), final_speed_m_s and ref_speed_m_s (largest final speed of a body),
// resolved_steps, impacts and first_restitution (of the run's first impact, 0 without one).
// Without `with_reference` (bin_of_ten, whose Dormand–Prince run takes many minutes) neither
// rest_diff_m nor ref_speed_m_s.
// With `prebuilt`, each iteration's Simulator is built and destroyed outside the timed region
// (state.PauseTiming): the run alone, without the per-scenario setup.
void discrete(benchmark::State& state, const std::string& name, double h, bool with_reference,
              ImpactMode mode, bool sleep, bool shortcuts, bool prebuilt) {
  vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(scenarioPath(name));
  file.scenario.settings.integrator = Integrator::kDiscrete;
  file.scenario.settings.step = h;
  file.scenario.settings.impacts = mode;
  file.scenario.settings.sleep.enabled = sleep;
  double simulated = 0.0, restitution = 0.0, last_asleep = 0.0;
  long steps = 0, contacts = 0, resolved = 0, impacts = 0, skipped = 0, asleep = 0;
  Snapshot last;
  for (auto _ : state) {
    if (prebuilt) state.PauseTiming();
    auto sim = std::make_unique<Simulator>(file.scenario);
    sim->setStepShortcuts(shortcuts);
    if (prebuilt) state.ResumeTiming();
    SimulationSummary summary;
    sim->run([&](const Snapshot& s) { last = s; }, [](double) {}, summary);
    if (prebuilt) {
      state.PauseTiming();
      sim.reset();
      state.ResumeTiming();
    }
    simulated += summary.simulated_time;
    steps = summary.steps;
    contacts = summary.contact_evaluations;
    resolved = summary.resolved_steps;
    impacts = static_cast<long>(summary.impacts.size());
    restitution = summary.impacts.empty() ? 0.0 : summary.impacts.front().restitution;
    skipped = summary.sleep_skipped_queries;
    asleep = 0;
    for (const vcontact::dynamics::SleepEvent& e : summary.sleep_events) {
      asleep += e.asleep ? 1 : -1;
      if (e.asleep) last_asleep = e.t;
    }
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["contact_evals"] = static_cast<double>(contacts);
  state.counters["resolved_steps"] = static_cast<double>(resolved);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["first_restitution"] = restitution;
  state.counters["skipped_queries"] = static_cast<double>(skipped);
  state.counters["asleep_at_end"] = static_cast<double>(asleep);
  state.counters["last_asleep_s"] = last_asleep;
  state.counters["final_speed_m_s"] = largestSpeed(last);
  state.counters["final_z_m"] = last.bodies.back().p_WBcm.z();
  if (!with_reference) return;
  const Snapshot& ref = reference(name);
  state.counters["rest_diff_m"] = largestDistance(last, ref);
  state.counters["ref_speed_m_s"] = largestSpeed(ref);
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
  // The discrete stepper (docs/DISCRETE.md §4) at 1 ms and 0.5 ms beside the Dormand–Prince
  // runs above and below; the reference run is outside the timed loop.
  // bin_of_ten: ten 2k-triangle parts in a bin, 55 pairs (issue 18: >= 1x real time).
  for (const char* name : {"ball_drop", "tippe_top", "cad_tray_drop", "bin_of_ten"}) {
    const bool with_reference = std::string(name) != "bin_of_ten";
    for (const auto& [suffix, h] : {std::pair{"1ms", 1e-3}, std::pair{"0.5ms", 5e-4}}) {
      for (const auto& [mode_suffix, mode] :
           {std::pair{"", ImpactMode::kAuto}, std::pair{"_resolve", ImpactMode::kResolve},
            std::pair{"_implicit", ImpactMode::kImplicit}}) {
        const std::string full = "simulate/" + std::string(name) + "/discrete_" + suffix;
        benchmark::RegisterBenchmark((full + mode_suffix).c_str(), discrete, std::string(name), h,
                                     with_reference, mode, true, true, false)
            ->Unit(benchmark::kMillisecond);
        if (std::string(name) != "ball_drop" && std::string(name) != "tippe_top") continue;
        benchmark::RegisterBenchmark((full + mode_suffix + "_general").c_str(), discrete,
                                     std::string(name), h, with_reference, mode, true, false, false)
            ->Unit(benchmark::kMillisecond);
      }
    }
    // the setup (trees, topology, the Simulator's own) outside the timed region: the cost per
    // simulated second alone (issue 18; docs/DISCRETE.md §4.2)
    if (std::string(name) == "cad_tray_drop") {
      benchmark::RegisterBenchmark("simulate/cad_tray_drop/discrete_1ms_implicit_prebuilt",
                                   discrete, std::string(name), 1e-3, with_reference,
                                   ImpactMode::kImplicit, true, true, true)
          ->Unit(benchmark::kMillisecond);
    }
    // the same run awake throughout: the reference of sleep's gain (docs/SLEEP.md)
    benchmark::RegisterBenchmark(
        ("simulate/" + std::string(name) + "/discrete_1ms_implicit_nosleep").c_str(), discrete,
        std::string(name), 1e-3, with_reference, ImpactMode::kImplicit, false, true, false)
        ->Unit(benchmark::kMillisecond);
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
