#pragma once
// DIR/summary.json of a simulation: how it ended, simulated and wall time, the real-time
// factor and the integrator's counts.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "dynamics/simulator.hpp"

namespace vcontact::report {

/// @param status "completed", or what stopped the run
nlohmann::json simulationSummaryJson(const dynamics::SimulationSummary& summary,
                                     const std::string& status);

}  // namespace vcontact::report
