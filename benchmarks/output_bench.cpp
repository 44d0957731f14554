// The cost of a simulation's output (issue 18, item 4: writing output at most 10 % of a run):
// output/<scenario>/<integrator>/<sink> runs the same simulation with
//
// - `none`: an output callback that does nothing, and no exact depths for the output
//   (Simulator::setOutputDepths(false)): what the run costs without its output; ball_drop's
//   discrete runs also as `none_general`, without the stepper's per-step shortcuts
//   (Simulator::setStepShortcuts(false): the same numbers, the "before" of DISCRETE.md §4.4);
// - `csv`: report::SimulationCsvWriter, with the depths its pair files hold (for `fast` pairs
//   a query with the depth pass at every output time), into a new scratch folder committed at
//   the end as `vcontact simulate` does (summary.json aside). The folder is removed between
//   runs outside the timing: replacing the files of an earlier run costs the file system more
//   than writing them (ext4 writes a replaced file's data out at the rename), which is not
//   the writer's cost.
//
// The share of the run spent on its output (depths, formatting, writing) is
// 1 − time(none) / time(csv), read from one run of the binary. Counters: real_time_factor
// (simulated seconds per CPU second), outputs (output times) and, for csv, bytes (the CSV bytes of
// one run).

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "report/simulation_csv.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::dynamics::Integrator;
using vcontact::dynamics::SimulationSummary;
using vcontact::dynamics::Simulator;
using vcontact::dynamics::Snapshot;

// The scenarios live next to this source tree's benchmarks/ folder.
std::string scenarioPath(const std::string& name) {
  return (fs::path(__FILE__).parent_path().parent_path() / "assets" / "scenarios" /
          (name + ".json"))
      .string();
}

// A run variant: the integrator (none: the scenario's own), the discrete step h (s), and the
// duration (none: the scenario's own).
struct Variant {
  std::optional<Integrator> integrator;
  double step = 0.0;
  std::optional<double> duration;
};

vcontact::formats::ScenarioFile load(const std::string& name, const Variant& v) {
  vcontact::formats::ScenarioFile file = vcontact::formats::readScenarioFile(scenarioPath(name));
  if (v.integrator) file.scenario.settings.integrator = *v.integrator;
  if (v.step > 0.0) file.scenario.settings.step = v.step;
  if (v.duration) file.scenario.settings.duration = *v.duration;
  return file;
}

// The bytes of the regular files in `dir`.
double folderBytes(const fs::path& dir) {
  double bytes = 0.0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file()) bytes += static_cast<double>(e.file_size());
  }
  return bytes;
}

void output(benchmark::State& state, const std::string& name, const Variant& variant, bool csv,
            bool shortcuts) {
  const vcontact::formats::ScenarioFile file = load(name, variant);
  const fs::path dir =
      fs::temp_directory_path() / ("vcontact_output_bench_" + std::to_string(::getpid()));
  double simulated = 0.0, bytes = 0.0;
  long outputs = 0;
  for (auto _ : state) {
    Simulator sim(file.scenario);
    sim.setStepShortcuts(shortcuts);
    SimulationSummary summary;
    outputs = 0;
    if (csv) {
      vcontact::report::SimulationCsvWriter writer(dir.string(), sim.scenario(), file.outputs);
      sim.run(
          [&](const Snapshot& s) {
            writer.write(s);
            ++outputs;
          },
          [](double) {}, summary);
      writer.commit();
      state.PauseTiming();
      bytes = folderBytes(dir);
      std::error_code ec;
      fs::remove_all(dir, ec);
      state.ResumeTiming();
    } else {
      sim.setOutputDepths(false);  // nothing is written, so no output needs the exact depth
      sim.run([&](const Snapshot&) { ++outputs; }, [](double) {}, summary);
    }
    simulated += summary.simulated_time;
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["outputs"] = static_cast<double>(outputs);
  if (csv) state.counters["bytes"] = bytes;
}

void registerPair(const std::string& name, const std::string& label, const Variant& v) {
  for (const bool csv : {false, true}) {
    const std::string full = "output/" + name + "/" + label + (csv ? "/csv" : "/none");
    benchmark::RegisterBenchmark(full.c_str(), output, name, v, csv, true)
        ->Unit(benchmark::kMillisecond);
  }
}

[[maybe_unused]] const bool kRegistered = [] {
  const std::pair<const char*, Variant> integrators[] = {
      {"dopri5", {Integrator::kDopri5, 0.0, std::nullopt}},
      {"discrete_1ms", {Integrator::kDiscrete, 1e-3, std::nullopt}},
      {"discrete_0.5ms", {Integrator::kDiscrete, 5e-4, std::nullopt}}};
  for (const auto& [label, v] : integrators) {
    registerPair("ball_drop", label, v);
    if (v.integrator != Integrator::kDiscrete) continue;
    benchmark::RegisterBenchmark(
        ("output/ball_drop/" + std::string(label) + "/none_general").c_str(), output, "ball_drop",
        v, false, false)
        ->Unit(benchmark::kMillisecond);
  }
  // The mesh scenarios: their output rows are few beside their queries, but each output
  // time asks the pairs once more for the exact depth (Simulator::fillDepths).
  for (const auto& [label, v] : integrators) registerPair("cad_tray_drop", label, v);
  for (const auto& [label, v] : integrators) {
    Variant first = v;
    first.duration = 0.02;  // the approach and the jam's first contact, not the long creep
    registerPair("peg_jam", label, first);
  }
  // Ten 2k-triangle parts in a bin, 55 pairs, 100 Hz output: discrete only (its Dormand–Prince
  // run takes many minutes, docs/DISCRETE.md §4).
  for (const auto& [label, v] : integrators) {
    if (v.integrator == Integrator::kDiscrete) registerPair("bin_of_ten", label, v);
  }
  return true;
}();

}  // namespace
