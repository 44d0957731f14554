// vcontact simulate SCENARIO --out DIR: integrates a scenario and writes CSV output.

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "io/interrupt.hpp"
#include "io/json_file.hpp"
#include "io/output_folder.hpp"
#include "io/progress.hpp"
#include "report/async_simulation_csv.hpp"
#include "report/simulation_summary.hpp"

namespace vcontact::cli {
namespace {

constexpr int kSimulationFailedExitCode = 3;  // 2 is bad input (main.cpp)

struct SimulateOptions {
  std::string scenario;
  std::string out = "out";
  std::optional<double> outputRate;  ///< Hz; the scenario's output_rate when not given
  bool quiet = false;
  int threads = 0;
  std::string outputThread = "off";  ///< "on": the CSVs are written on a thread of their own
};

// A discrete run's impacts that "auto" left to the plain step (only that mode leaves any):
// what a user who needs their rebounds should change.
void printPlainImpacts(const dynamics::SimulationSummary& s,
                       const dynamics::SimulationSettings& settings) {
  long resolved = 0, plain = 0;
  for (const dynamics::ImpactRecord& r : s.impacts) {
    if (r.resolution == "plain" || r.resolution == "partly") ++plain;
    if (r.resolution == "resolved") ++resolved;
  }
  if (plain == 0) return;
  std::cerr << "vcontact: " << plain << " of " << (plain + resolved)
            << " fast impacts were left to the plain step, which dissipates them (predicted "
               "rebound below restitution_threshold = "
            << settings.restitution_threshold
            << " m/s); lower it, or set \"impacts\": \"resolve\", to resolve them "
               "(docs/DISCRETE.md §5; summary.json impacts[].resolution)\n";
}

// The run's figures on standard error, for a person at a terminal.
void printSummary(const dynamics::SimulationSummary& s,
                  const dynamics::SimulationSettings& settings) {
  std::cerr << "vcontact: simulated " << s.simulated_time << " s in " << s.wall_time
            << " s wall (real-time factor " << s.realTimeFactor() << "), " << s.steps << " steps ("
            << s.rejected_steps << " rejected), " << s.contact_evaluations
            << " contact evaluations";
  if (s.jacobian_evaluations > 0) std::cerr << ", " << s.jacobian_evaluations << " Jacobians";
  std::cerr << '\n';
  if (s.patches_without_slot > 0) {
    std::cerr << "vcontact: warning: " << s.patches_without_slot
              << " contact patches (summed over the output times; up to " << s.patches_max
              << " of one pair at once) had no state slot of their own (they read the friction "
                 "states of the nearest patch's slot, or were lumped into a one-slot pair's "
                 "single region); raise the pairs' max_patches (up to 16), "
                 "or set it to 1 to lump each pair's patches into one region "
                 "(docs/SCENARIO.md, Contact patches; summary.json patches.without_slot)\n";
  }
  printPlainImpacts(s, settings);
  for (const dynamics::SurfacePairUse& p : s.surface_pairs) {
    std::cerr << "vcontact: pair '" << p.pair << "': ";
    if (!p.polyhedral_reason.empty()) {
      std::cerr << "polyhedra throughout: " << p.polyhedral_reason << '\n';
      continue;
    }
    const char* sep = "recovered surface, evaluations ";
    for (const auto& [representation, n] : p.evaluations) {
      std::cerr << sep << representation << ' ' << n;
      sep = ", ";
    }
    std::cerr << '\n';
  }
}

// What recognition found on the bodies with a recovered surface, and how long it took (once,
// when the scenario was read).
void printRecognition(const dynamics::Scenario& scenario, bool quiet) {
  if (quiet) return;
  const dynamics::RecoveredPairs recovered(scenario);
  for (const dynamics::SurfaceBodyUse& b : recovered.bodies()) {
    std::cerr << "vcontact: body '" << b.body << "': recovered surface " << b.description
              << " (recognised in " << b.recognition_seconds << " s)\n";
  }
}

// The effects the discrete stepper takes at each step's start only (Model::explicitEffects),
// per pair: a stiff one among them needs a smaller step, or an error-controlled integrator.
void printExplicitEffects(const dynamics::Scenario& scenario, bool quiet) {
  if (quiet || scenario.settings.integrator != dynamics::Integrator::kDiscrete) return;
  for (const dynamics::ContactPair& pair : scenario.pairs) {
    const std::vector<std::string> ids = pair.model.explicitEffects();
    if (ids.empty()) continue;
    std::cerr << "vcontact: pair '" << pair.name << "': ";
    for (std::size_t i = 0; i < ids.size(); ++i) std::cerr << (i ? ", " : "") << ids[i];
    std::cerr << (ids.size() == 1 ? " is" : " are")
              << " not linearised by the discrete stepper (each step takes "
              << (ids.size() == 1 ? "its share" : "their shares")
              << " at the step's start): if stiff, lower \"step\" or use \"dopri5\" "
                 "(docs/DISCRETE.md §2)\n";
  }
}

// The output rate of the command line replaces the scenario's; then the rows the run would
// write are counted and refused beyond report::kMaxOutputRows, before anything is written.
void applyOutputOptions(const SimulateOptions& o, formats::ScenarioFile& file) {
  dynamics::SimulationSettings& set = file.scenario.settings;
  if (o.outputRate) {
    if (!(*o.outputRate > 0.0 && *o.outputRate <= 1e9)) {
      throw InputError("--output-rate", "expected a rate in Hz, > 0 and <= 1e9");
    }
    set.output_rate_hz = *o.outputRate;
  }
  const std::uint64_t rows = report::outputRowCount(file.scenario, file.outputs);
  if (rows <= report::kMaxOutputRows) return;
  std::ostringstream s;
  s << "the run would write " << rows << " CSV rows (" << set.duration << " s at "
    << set.output_rate_hz << " Hz), more than the limit of " << report::kMaxOutputRows
    << "; lower the output rate";
  throw InputError(o.outputRate ? "--output-rate" : o.scenario, s.str());
}

// What the end of the run needs, tried before it: the output folder can be made, the
// summary can be built and written as JSON (a file name that is not UTF-8, issue 36), its
// place is no folder, and no output would replace the scenario file. (The CSV files are
// opened before the run.)
void checkBeforeRun(const SimulateOptions& o) {
  try {  // the message names the option too
    io::checkOutputFolder(o.out);
  } catch (const InputError& e) {
    throw InputError("--out", e.what());
  }
  (void)io::jsonText(report::simulationSummaryJson(dynamics::SimulationSummary{}, o.scenario));
  const std::string summary = (std::filesystem::path(o.out) / "summary.json").string();
  std::error_code ec;
  if (std::filesystem::is_directory(summary, ec)) {
    throw InputError(summary, "is a folder; expected the place of the run's summary file");
  }
  io::refuseOverwritingInputs({summary}, {{o.scenario, "the scenario file"}}, "--out");
}

void runSimulate(const SimulateOptions& o) {
  formats::ScenarioFile file = formats::readScenarioFile(o.scenario);
  printWarnings(file.warnings);
  applyOutputOptions(o, file);
  checkBeforeRun(o);
  printRecognition(file.scenario, o.quiet);
  printExplicitEffects(file.scenario, o.quiet);
  dynamics::Simulator sim(file.scenario);
  sim.setOutputDepths(file.outputs.pairs);  // the depth column is in the pair files only
  sim.setParallelPairs(o.threads != 1);
  // the process's TBB threads for the run: --threads, else every core
  const tbb::global_control threads(
      tbb::global_control::max_allowed_parallelism,
      o.threads > 0 ? static_cast<std::size_t>(o.threads) : tbb::info::default_concurrency());
  const report::OutputThread thread =
      o.outputThread == "on" ? report::OutputThread::kOn : report::OutputThread::kOff;
  // Ctrl-C or SIGTERM from here on ends the run as a stopped one: exit 3, the rows so far and
  // summary.json in place (io/interrupt.hpp); a second signal ends the process at once.
  const io::InterruptHandlers interrupts;
  report::AsyncSimulationCsvWriter writer(o.out, sim.scenario(), file.outputs, thread);
  io::Progress progress("simulate", file.scenario.settings.duration, "s", o.quiet);
  dynamics::SimulationSummary summary;
  try {
    sim.run([&](const dynamics::Snapshot& s) { writer.write(s); },
            [&](double t) { progress.update(t); }, summary);
  } catch (const dynamics::SimulationError& e) {
    progress.finish();
    report::finishSimulationOutput(writer, o.out, summary, o.scenario, report::StopInfo{e});
    printSummary(summary, file.scenario.settings);
    std::cerr << "vcontact: error: " << o.scenario << ": simulation stopped: " << e.what()
              << "; output up to then is in " << o.out << '\n';
    throw CLI::RuntimeError(kSimulationFailedExitCode);
  }
  progress.finish();
  report::finishSimulationOutput(writer, o.out, summary, o.scenario, std::nullopt);
  printSummary(summary, file.scenario.settings);
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Integrate a scenario (docs/SCENARIO.md) and write bodies.csv, pair_<name>.csv, "
      "loads.csv (with loads or springs) and summary.json.");
  cmd->add_option("SCENARIO", opts->scenario, "scenario JSON file")->required();
  cmd->add_option("--out", opts->out, "output directory")->capture_default_str();
  cmd->add_option("--output-rate", opts->outputRate,
                  "states written per simulated second, Hz (default: the scenario's "
                  "output_rate_hz)");
  cmd->add_option("--output-thread", opts->outputThread,
                  "on: the CSVs are formatted and written on a second thread while the run steps "
                  "on; off: on the stepping thread (the same files)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--threads", opts->threads,
                  "threads that evaluate the contact pairs of a step side by side (1: one "
                  "after another; default 0: every core); the results are the same to the bit")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--quiet", opts->quiet, "no progress on standard error (none in pipes or CI)");
  cmd->callback([opts] { runSimulate(*opts); });
}

}  // namespace vcontact::cli
