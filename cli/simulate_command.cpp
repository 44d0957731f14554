// vcontact simulate SCENARIO --out DIR: integrates a scenario and writes CSV output.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "report/simulation_csv.hpp"
#include "report/simulation_summary.hpp"

namespace vcontact::cli {
namespace {

constexpr int kSimulationFailedExitCode = 3;  // 2 is bad input (main.cpp)
constexpr double kProgressIntervalS = 0.5;    // wall-clock seconds between progress lines

struct SimulateOptions {
  std::string scenario;
  std::string out = "out";
  bool quiet = false;
};

// Prints "t = … s (…%)" at most every kProgressIntervalS of wall time.
class Progress {
 public:
  Progress(double duration, bool quiet) : duration_(duration), quiet_(quiet) {}
  void operator()(double t) {
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < kProgressIntervalS) return;
    last_ = now;
    std::cerr << "\rvcontact: t = " << t << " s (" << static_cast<int>(100.0 * t / duration_)
              << "%)   " << std::flush;
  }
  void done() const {
    if (!quiet_) std::cerr << '\n';
  }

 private:
  double duration_;
  bool quiet_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void writeSummary(const std::string& dir, const dynamics::SimulationSummary& s,
                  const std::string& status, const std::string& scenario) {
  nlohmann::json j = report::simulationSummaryJson(s, status);
  j["scenario"] = std::filesystem::absolute(scenario).string();  // for `vcontact view`
  io::writeJson(j, dir + "/summary.json");
  std::cerr << "vcontact: simulated " << s.simulated_time << " s in " << s.wall_time
            << " s wall (real-time factor " << s.realTimeFactor() << "), " << s.steps << " steps ("
            << s.rejected_steps << " rejected), " << s.contact_evaluations
            << " contact evaluations";
  if (s.jacobian_evaluations > 0) std::cerr << ", " << s.jacobian_evaluations << " Jacobians";
  std::cerr << '\n';
}

void runSimulate(const SimulateOptions& o) {
  const formats::ScenarioFile file = formats::readScenarioFile(o.scenario);
  printWarnings(file.warnings);
  dynamics::Simulator sim(file.scenario);
  report::SimulationCsvWriter writer(o.out, sim.scenario(), file.outputs);
  Progress progress(file.scenario.settings.duration, o.quiet);
  dynamics::SimulationSummary summary;
  try {
    sim.run([&](const dynamics::Snapshot& s) { writer.write(s); }, [&](double t) { progress(t); },
            summary);
  } catch (const dynamics::SimulationError& e) {
    writer.flush();
    progress.done();
    writeSummary(o.out, summary, e.what(), o.scenario);
    std::cerr << "vcontact: error: " << o.scenario << ": simulation stopped: " << e.what()
              << "; output up to then is in " << o.out << '\n';
    throw CLI::RuntimeError(kSimulationFailedExitCode);
  }
  progress.done();
  writeSummary(o.out, summary, "completed", o.scenario);
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Integrate a scenario (dynamics/SCENARIO.md) and write bodies.csv, pair_<name>.csv "
      "and summary.json.");
  cmd->add_option("SCENARIO", opts->scenario, "scenario JSON file")->required();
  cmd->add_option("--out", opts->out, "output directory")->capture_default_str();
  cmd->add_flag("--quiet", opts->quiet, "no progress on standard error");
  cmd->callback([opts] { runSimulate(*opts); });
}

}  // namespace vcontact::cli
