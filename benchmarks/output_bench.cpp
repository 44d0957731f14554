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
//   the writer's cost. The writer works on the stepping thread (`--output-thread off`);
// - `csv_async`: the same files written by the writer thread of report::AsyncSimulationCsvWriter
//   (`vcontact simulate`'s default): the stepping thread copies each snapshot into a slot and
//   steps on.
//
// The time of a run is measured twice: wall time (Google Benchmark's "Time"; the commit, and
// so the wait for the writer thread, included) and the stepping thread's CPU time ("CPU", the
// benchmark thread's CLOCK_THREAD_CPUTIME_ID; also the counter step_cpu_ms). The share of
// the run spent on its output (depths, formatting, writing) is 1 − none / x for either, read
// from one run of the binary. The writer thread does not make the work smaller: the counter
// process_cpu_ms (CLOCK_PROCESS_CPUTIME_ID per run: every thread, TBB's workers too) shows
// the whole. Other counters: real_time_factor (simulated seconds per CPU second of the
// stepping thread), outputs (output times) and, with CSVs, bytes (the CSV bytes of one run).

#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "report/async_simulation_csv.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::dynamics::Integrator;
using vcontact::dynamics::SimulationSummary;
using vcontact::dynamics::Simulator;
using vcontact::dynamics::Snapshot;
using vcontact::report::OutputThread;

// Where a run's output goes.
enum class Sink { kNone, kCsv, kCsvAsync };

const char* sinkName(Sink sink) {
  switch (sink) {
    case Sink::kNone:
      return "none";
    case Sink::kCsv:
      return "csv";
    case Sink::kCsvAsync:
      return "csv_async";
  }
  return "";
}

// Seconds of CPU on `clock` (CLOCK_THREAD_CPUTIME_ID, CLOCK_PROCESS_CPUTIME_ID).
double cpuSeconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

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

// One run into the CSVs of `dir` (kCsv on this thread, kCsvAsync on the writer thread), committed
// as `vcontact simulate` commits them; returns the output times.
long runWithCsv(Simulator& sim, const vcontact::formats::ScenarioFile& file, const fs::path& dir,
                OutputThread thread, SimulationSummary& summary) {
  long outputs = 0;
  vcontact::report::AsyncSimulationCsvWriter writer(dir.string(), sim.scenario(), file.outputs,
                                                    thread);
  sim.run(
      [&](const Snapshot& s) {
        writer.write(s);
        ++outputs;
      },
      [](double) {}, summary);
  writer.commit();
  return outputs;
}

void output(benchmark::State& state, const std::string& name, const Variant& variant, Sink sink,
            bool shortcuts) {
  const vcontact::formats::ScenarioFile file = load(name, variant);
  const fs::path dir =
      fs::temp_directory_path() / ("vcontact_output_bench_" + std::to_string(::getpid()));
  double simulated = 0.0, bytes = 0.0, step_cpu = 0.0, process_cpu = 0.0;
  long outputs = 0;
  for (auto _ : state) {
    const double step_start = cpuSeconds(CLOCK_THREAD_CPUTIME_ID);
    const double process_start = cpuSeconds(CLOCK_PROCESS_CPUTIME_ID);
    Simulator sim(file.scenario);
    sim.setStepShortcuts(shortcuts);
    SimulationSummary summary;
    if (sink == Sink::kNone) {
      outputs = 0;
      sim.setOutputDepths(false);  // nothing is written, so no output needs the exact depth
      sim.run([&](const Snapshot&) { ++outputs; }, [](double) {}, summary);
    } else {
      const OutputThread thread = sink == Sink::kCsvAsync ? OutputThread::kOn : OutputThread::kOff;
      outputs = runWithCsv(sim, file, dir, thread, summary);
    }
    step_cpu += cpuSeconds(CLOCK_THREAD_CPUTIME_ID) - step_start;
    process_cpu += cpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - process_start;
    simulated += summary.simulated_time;
    if (sink == Sink::kNone) continue;
    state.PauseTiming();
    bytes = folderBytes(dir);
    std::error_code ec;
    fs::remove_all(dir, ec);
    state.ResumeTiming();
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["outputs"] = static_cast<double>(outputs);
  state.counters["step_cpu_ms"] =
      benchmark::Counter(1e3 * step_cpu, benchmark::Counter::kAvgIterations);
  state.counters["process_cpu_ms"] =
      benchmark::Counter(1e3 * process_cpu, benchmark::Counter::kAvgIterations);
  if (sink != Sink::kNone) state.counters["bytes"] = bytes;
}

void registerPair(const std::string& name, const std::string& label, const Variant& v) {
  for (const Sink sink : {Sink::kNone, Sink::kCsv, Sink::kCsvAsync}) {
    const std::string full = "output/" + name + "/" + label + "/" + sinkName(sink);
    benchmark::RegisterBenchmark(full.c_str(), output, name, v, sink, true)
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
        v, Sink::kNone, false)
        ->Unit(benchmark::kMillisecond);
  }
  // The ball drop run on for 5 s (10,001 output times, 4 MB of CSV): the writer thread's start,
  // its first-touched slots and the final wait weigh less than in the 0.3 s run.
  registerPair("ball_drop", "discrete_1ms_5s", {Integrator::kDiscrete, 1e-3, 5.0});
  // The mesh scenarios: their output rows are few beside their queries, but each output
  // time asks the pairs once more for the exact depth (MotionEquations::snapshot).
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
