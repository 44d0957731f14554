#pragma once
// DIR/summary.json of a simulation: how it ended, simulated and wall time, the real-time
// factor and the integrator's counts; for a stopped run also where and why it stopped.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "dynamics/simulator.hpp"

namespace vcontact::report {

/// Where and why a run stopped: "stopped_at_s" and "stop_cause" (dynamics::stopCauseName).
struct StopInfo {
  explicit StopInfo(const dynamics::SimulationError& e) : time(e.time()), cause(e.cause()) {}
  double time;  ///< s
  dynamics::StopCause cause;
};

/// @param status "completed", or what stopped the run
/// @param stop   set for a stopped run
nlohmann::json simulationSummaryJson(const dynamics::SimulationSummary& summary,
                                     const std::string& status,
                                     const std::optional<StopInfo>& stop = std::nullopt);

}  // namespace vcontact::report
