#include "report/simulation_summary.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>

#include "io/json_file.hpp"
#include "report/async_simulation_csv.hpp"
#include "report/simulation_csv.hpp"

namespace vcontact::report {
namespace {

// "surfaces": per body with a recovered surface what recognition found, per pair with one
// which representation its queries used (docs/SCENARIO.md "Recovered surfaces").
nlohmann::json surfacesJson(const dynamics::SimulationSummary& s) {
  nlohmann::json bodies = nlohmann::json::array(), pairs = nlohmann::json::array();
  for (const dynamics::SurfaceBodyUse& b : s.surface_bodies) {
    bodies.push_back({{"body", b.body},
                      {"recognition_time_s", b.recognition_seconds},
                      {"surfaces", b.kinds},
                      {"free_form_faces", b.free_form_faces},
                      {"max_residual_m", b.max_residual}});
  }
  for (const dynamics::SurfacePairUse& p : s.surface_pairs) {
    nlohmann::json j = {{"pair", p.pair},
                        {"representation", p.polyhedral_reason.empty() ? "recovered" : "mesh"},
                        {"evaluations", p.evaluations}};
    if (!p.polyhedral_reason.empty()) j["why_mesh"] = p.polyhedral_reason;
    if (!p.mesh_reasons.empty()) j["mesh_fallbacks"] = p.mesh_reasons;
    pairs.push_back(j);
  }
  return {{"bodies", bodies}, {"pairs", pairs}};
}

// "impacts": one object per impact of a pair (dynamics/trackers/impact_tracker.hpp).
nlohmann::json impactsJson(const dynamics::SimulationSummary& s) {
  nlohmann::json out = nlohmann::json::array();
  for (const dynamics::ImpactRecord& r : s.impacts) {
    nlohmann::json j = {{"pair", r.pair},
                        {"start_s", r.start},
                        {"duration_s", r.duration},
                        {"normal_impulse_Ns", r.impulse},
                        {"approach_speed_m_s", r.approach_speed},
                        {"separation_speed_m_s", r.separation_speed},
                        {"restitution", r.restitution},
                        {"outcome", r.outcome}};
    if (!r.resolution.empty()) {  // discrete runs: how the stepper took it
      j["resolution"] = r.resolution;
      j["resolved_steps"] = r.resolved_steps;
      j["plain_steps"] = r.plain_steps;
      j["predicted_rebound_m_s"] = r.predicted_rebound;
    }
    out.push_back(std::move(j));
  }
  return out;
}

// "sleep": the bodies falling asleep and waking, in order, and the queries sleep saved.
nlohmann::json sleepJson(const dynamics::SimulationSummary& s) {
  nlohmann::json events = nlohmann::json::array();
  for (const dynamics::SleepEvent& e : s.sleep_events) {
    events.push_back({{"body", e.body}, {"t_s", e.t}, {"event", e.asleep ? "asleep" : "woke"}});
  }
  return {{"events", events}, {"skipped_queries", s.sleep_skipped_queries}};
}

}  // namespace

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
  if (!s.surface_bodies.empty()) j["surfaces"] = surfacesJson(s);
  j["impacts"] = impactsJson(s);
  if (s.resolved_steps > 0) {
    j["resolved_steps"] = s.resolved_steps;
    j["resolution_substeps"] = s.resolution_substeps;
    j["resolved_for_linearisation"] = s.resolved_for_linearisation;
    j["resolution_queries"] = s.resolution_queries;
  }
  if (s.newton_iterations > 0) j["newton_iterations"] = s.newton_iterations;
  if (!s.sleep_events.empty()) j["sleep"] = sleepJson(s);
  if (stop) {
    j["stopped_at_s"] = stop->time;
    j["stop_cause"] = dynamics::stopCauseName(stop->cause);
  }
  j["scenario"] = std::filesystem::absolute(scenario_path).string();
  return j;
}

namespace {

// Either writer: its commit() puts the CSVs and summary.json in place together.
template <class Writer>
nlohmann::json finishWith(Writer& writer, const std::string& dir,
                          const dynamics::SimulationSummary& summary,
                          const std::string& scenario_path, const std::optional<StopInfo>& stop) {
  nlohmann::json j = simulationSummaryJson(summary, scenario_path, stop);
  writer.commit(dir + "/summary.json", io::jsonText(j) + '\n');  // all the run's files, or none
  return j;
}

}  // namespace

nlohmann::json finishSimulationOutput(SimulationCsvWriter& writer, const std::string& dir,
                                      const dynamics::SimulationSummary& summary,
                                      const std::string& scenario_path,
                                      const std::optional<StopInfo>& stop) {
  return finishWith(writer, dir, summary, scenario_path, stop);
}

nlohmann::json finishSimulationOutput(AsyncSimulationCsvWriter& writer, const std::string& dir,
                                      const dynamics::SimulationSummary& summary,
                                      const std::string& scenario_path,
                                      const std::optional<StopInfo>& stop) {
  return finishWith(writer, dir, summary, scenario_path, stop);
}

}  // namespace vcontact::report
