#pragma once
// DIR/summary.json of a simulation: how it ended, simulated and wall time, the real-time
// factor and the integrator's counts; for a stopped run also where and why it stopped; and the
// scenario file it ran. One function ends a run's output for every front end (the CLI's
// `simulate`, Python's Scenario.run), so they write the same files in the same order.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "dynamics/simulation_output.hpp"

namespace vcontact::report {

class SimulationCsvWriter;
class AsyncSimulationCsvWriter;

/// Where and why a run stopped: "stopped_at_s" and "stop_cause" (dynamics::stopCauseName),
/// and the message, which becomes the summary's "status".
struct StopInfo {
  explicit StopInfo(const dynamics::SimulationError& e)
      : time(e.time()), cause(e.cause()), message(e.what()) {}
  double time;  ///< s
  dynamics::StopCause cause;
  std::string message;
};

/// The summary of a run: "status" is "completed", or the stop's message when `stop` is set;
/// "scenario" is the absolute path of the scenario file.
nlohmann::json simulationSummaryJson(const dynamics::SimulationSummary& summary,
                                     const std::string& scenario_path,
                                     const std::optional<StopInfo>& stop = std::nullopt);

/// Ends a run's output: the CSVs and `dir`/summary.json under their final names together (a
/// stopped run keeps its rows up to the stop). Returns the summary written.
/// @throws InputError naming the file when a write failed; no file of the run is left then
nlohmann::json finishSimulationOutput(SimulationCsvWriter& writer, const std::string& dir,
                                      const dynamics::SimulationSummary& summary,
                                      const std::string& scenario_path,
                                      const std::optional<StopInfo>& stop);
/// The same through the threaded writer: what was handed over is written first.
nlohmann::json finishSimulationOutput(AsyncSimulationCsvWriter& writer, const std::string& dir,
                                      const dynamics::SimulationSummary& summary,
                                      const std::string& scenario_path,
                                      const std::optional<StopInfo>& stop);

}  // namespace vcontact::report
