#include "report/simulation_summary.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "report/simulation_csv.hpp"

namespace vcontact::report {

nlohmann::json simulationSummaryJson(const dynamics::SimulationSummary& s,
                                     const std::string& scenario_path,
                                     const std::optional<StopInfo>& stop) {
  nlohmann::json j = {{"status", stop ? stop->message : std::string("completed")},
                      {"simulated_time_s", s.simulated_time},
                      {"wall_time_s", s.wall_time},
                      {"real_time_factor", s.realTimeFactor()},
                      {"steps", s.steps},
                      {"rejected_steps", s.rejected_steps},
                      {"rhs_evaluations", s.rhs_evaluations},
                      {"contact_evaluations", s.contact_evaluations},
                      {"jacobian_evaluations", s.jacobian_evaluations},
                      {"patches",
                       {{"max", s.patches_max},
                        {"mean", s.patches_mean},
                        {"without_slot", s.patches_without_slot}}}};
  if (stop) {
    j["stopped_at_s"] = stop->time;
    j["stop_cause"] = dynamics::stopCauseName(stop->cause);
  }
  j["scenario"] = std::filesystem::absolute(scenario_path).string();
  return j;
}

nlohmann::json finishSimulationOutput(SimulationCsvWriter& writer, const std::string& dir,
                                      const dynamics::SimulationSummary& summary,
                                      const std::string& scenario_path,
                                      const std::optional<StopInfo>& stop) {
  nlohmann::json j = simulationSummaryJson(summary, scenario_path, stop);
  writer.commit(dir + "/summary.json", j.dump(2) + '\n');  // all the run's files, or none
  return j;
}

}  // namespace vcontact::report
