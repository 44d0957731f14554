#include "report/trajectory_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>

#include "geometry/primitives.hpp"
#include "report/svg_chart.hpp"

namespace vcontact::report {
namespace {

using nlohmann::json;
using validation::TrajectoryPhase;

constexpr int kPageWidth = 1060;
const char* kPageStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:1em auto;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;"
    "font-size:13px;vertical-align:top}svg.chart{margin:4px}.warnings{color:#a40}";

std::string num(double v, int digits = 4) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

json finiteOrNull(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The pose's seven numbers x, y, z, qw, qx, qy, qz, the quaternion's sign chosen nearest `ref`.
std::array<double, 7> poseNumbers(const Eigen::Isometry3d& X, const Eigen::Quaterniond* ref) {
  Eigen::Quaterniond q(X.linear());
  if (ref && q.dot(*ref) < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d p = X.translation();
  return {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()};
}

// Windows of the record where the simulation has parted from it (trajectory_compare.hpp).
std::vector<Window> partedWindows(const validation::Trial& trial,
                                  const validation::TrialEvaluation& e) {
  std::vector<Window> w;
  if (std::isnan(e.errors.partTime)) return w;
  const double t0 = trial.data.samples.front().t;
  w.push_back({t0 + e.errors.partTime, trial.data.samples.back().t, "parted"});
  return w;
}

}  // namespace

void putTrajectoryCsv(const validation::Trial& trial, const validation::TrialEvaluation& e,
                      std::ostream& out) {
  static const char* names[] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "t";
  for (const char* n : names) out << ',' << n << ',' << n << "_sim";
  out << ",dp,dtheta,phase\n";
  const auto& d = trial.data;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto rec = poseNumbers(d.samples[i].X_BA, nullptr);
    const Eigen::Quaterniond q(d.samples[i].X_BA.linear());
    const auto sim = poseNumbers(e.path.X_BA[i], &q);
    out << d.samples[i].t;
    for (int k = 0; k < 7; ++k) out << ',' << rec[k] << ',' << sim[k];
    out << ',' << e.errors.dp[i] << ',' << e.errors.dtheta[i] << ",\""
        << validation::trajectoryPhaseName(trial.phases[i]) << "\"\n";
  }
}

json trajectoryErrorsJson(const validation::TrajectoryErrors& e) {
  json phases = json::object();
  for (const auto& p : e.phases) {
    phases[validation::trajectoryPhaseName(p.phase)] = {
        {"samples", p.samples},
        {"e_q", p.e_q},
        {"position_error_fraction", p.positionFraction},
        {"rotation_error_deg", p.rotationDeg},
        {"max_penetration_m", p.maxPenetration}};
  }
  return {{"e_q", e.e_q},
          {"e_q_position", e.e_position},
          {"e_q_attitude", e.e_attitude},
          {"h_m", e.h},
          {"payload_size_m", e.size},
          {"position_error_fraction", e.positionFraction},
          {"rotation_error_deg", e.rotationDeg},
          {"max_penetration_m", e.maxPenetration},
          {"part_time_s", finiteOrNull(e.partTime)},
          {"phases", phases}};
}

json trajectoryCompareJson(const validation::Trial& trial, const validation::TrialEvaluation& e) {
  const auto& s = trial.start;
  const Eigen::Vector3d p = s.X_BA.translation();
  const Eigen::Quaterniond q(s.X_BA.linear());
  json j = trajectoryErrorsJson(e.errors);
  j["samples"] = trial.data.size();
  j["initial_state"] = {
      {"source", s.estimated ? "free flight before the first contact" : "velocity columns"},
      {"free_samples", s.samplesUsed},
      {"position_rms_m", s.positionRms},
      {"attitude_rms_rad", s.attitudeRms},
      {"pose", {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()}},
      {"v_cm", {s.v_BAcm.x(), s.v_BAcm.y(), s.v_BAcm.z()}},
      {"w", {s.w_BA.x(), s.w_BA.y(), s.w_BA.z()}}};
  j["stopped"] = e.path.stopped.empty() ? json(nullptr) : json(e.path.stopped);
  // What `vcontact view` needs to draw the run again: the shapes are the dataset's.
  j["dataset"] = std::filesystem::absolute(trial.data.sidecarPath).string();
  return j;
}

std::string trajectoryReportHtml(const validation::Trial& trial,
                                 const validation::TrialEvaluation& e, const std::string& model) {
  const auto& d = trial.data;
  std::vector<double> t, zRec, zSim, vRec, vSim, angle, dp;
  for (std::size_t i = 0; i < d.size(); ++i) {
    t.push_back(d.samples[i].t);
    zRec.push_back(d.samples[i].X_BA.translation().z());
    zSim.push_back(e.path.X_BA[i].translation().z());
    vRec.push_back(d.samples[i].v_BA.norm());
    vSim.push_back(e.path.v_BA[i].norm());
    angle.push_back(e.errors.dtheta[i] * 180.0 / std::numbers::pi);
    dp.push_back(e.errors.dp[i] / e.errors.size);
  }
  const auto windows = partedWindows(trial, e);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>vcontact compare: "
    << escapeXml(d.name) << "</title><style>" << kPageStyle << "</style></head><body>\n"
    << "<h1>vcontact compare: " << escapeXml(d.name)
    << " (dynamic)</h1>\n<p>model: " << escapeXml(model)
    << "</p>\n<p>payload: " << escapeXml(geometry::describe(d.payload))
    << "; plate: " << escapeXml(geometry::describe(d.plate)) << "; " << d.size()
    << " samples; initial state from "
    << (trial.start.estimated ? "the free flight before the first contact" : "the velocity columns")
    << "</p>\n<p>e_q = " << num(e.errors.e_q) << " (position " << num(e.errors.e_position)
    << ", attitude " << num(e.errors.e_attitude) << ", h = " << num(e.errors.h) << " m); mean |Δp| "
    << num(100 * e.errors.positionFraction, 3) << " % of the payload's size, mean rotation error "
    << num(e.errors.rotationDeg, 3) << "°, deepest penetration "
    << num(1e3 * e.errors.maxPenetration, 3) << " mm";
  if (!std::isnan(e.errors.partTime))
    h << "; the paths part at t = " << num(d.samples.front().t + e.errors.partTime)
      << " s (shaded)";
  h << "</p>\n";
  if (!e.path.stopped.empty())
    h << "<p class=\"warnings\">the simulation stopped: " << escapeXml(e.path.stopped) << "</p>\n";
  h << "<table><tr><th>phase</th><th>samples</th><th>e_q</th><th>|Δp| / size</th>"
       "<th>rotation error (°)</th><th>deepest penetration (mm)</th></tr>";
  for (const auto& p : e.errors.phases)
    h << "<tr><td>" << validation::trajectoryPhaseName(p.phase) << "</td><td>" << p.samples
      << "</td><td>" << num(p.e_q) << "</td><td>" << num(p.positionFraction, 3) << "</td><td>"
      << num(p.rotationDeg, 3) << "</td><td>" << num(1e3 * p.maxPenetration, 3) << "</td></tr>";
  h << "</table>\n";
  h << lineChart({"Height of the payload origin", "t (s)", "z (m)", kPageWidth},
                 {{"recorded", t, zRec, "", false}, {"simulated", t, zSim, "", false}}, windows);
  h << lineChart({"Speed of the payload origin", "t (s)", "|v| (m/s)", kPageWidth},
                 {{"recorded", t, vRec, "", false}, {"simulated", t, vSim, "", false}}, windows);
  h << lineChart(
      {"Errors", "t (s)", "angle (°) · |Δp| / size", kPageWidth},
      {{"angle between the attitudes (°)", t, angle, "", false}, {"|Δp| / size", t, dp, "", false}},
      windows);
  h << "\n</body></html>\n";
  return h.str();
}

// Which error TrajectoryParameter::stdError is (trajectory_fit.hpp).
const char* standardErrorMethod(const validation::TrajectoryParameter& p) {
  if (std::isnan(p.jackknifeError)) return "gauss-newton";
  return p.stdError == p.jackknifeError ? "jackknife over the folds"
                                        : "gauss-newton (above the jackknife)";
}

json trajectoryFitJson(const validation::TrajectoryFitResult& r,
                       const validation::TrajectoryFitOptions& o) {
  json params = json::array();
  for (const auto& p : r.parameters)
    params.push_back({{"name", p.name},
                      {"unit", p.unit},
                      {"start", p.start},
                      {"value", p.value},
                      {"std_error", finiteOrNull(p.stdError)},
                      {"std_error_method", standardErrorMethod(p)},
                      {"std_error_gauss_newton", finiteOrNull(p.gaussNewtonError)},
                      {"std_error_jackknife", finiteOrNull(p.jackknifeError)},
                      {"search", {p.lower, p.upper}},
                      {"scale", p.logScale ? "log" : "linear"}});
  json trials = json::array();
  for (const auto& t : r.trials)
    trials.push_back({{"name", t.name},
                      {"fold", t.fold},
                      {"e_q_start", t.e_q_start},
                      {"e_q_fitted", t.e_q_fitted},
                      {"e_q_held_out", finiteOrNull(t.e_q_heldOut)},
                      {"worst_phase", t.worstPhase},
                      {"errors", trajectoryErrorsJson(t.errors)}});
  return {{"trials_count", r.trials.size()},
          {"mean_e_q",
           {{"start", r.meanStart},
            {"fitted", r.meanFitted},
            {"held_out", finiteOrNull(r.meanHeldOut)},
            {"folds", o.folds}}},
          {"plate_offset_m", r.plateOffset},
          {"parameters", params},
          {"optimiser",
           {{"global", "NLopt GN_DIRECT_L"},
            {"global_evaluations", o.globalEvaluations},
            {"local", "NLopt LN_SBPLX"},
            {"local_evaluations", o.localEvaluations},
            {"starts", o.starts}}},
          {"evaluations", r.evaluations},
          {"trial_simulations", r.trialSimulations},
          {"wall_s", r.seconds},
          {"cpu_s", r.cpuSeconds},
          {"warnings", r.warnings},
          {"trials", trials}};
}

void putTrialsCsv(const validation::TrajectoryFitResult& r, std::ostream& out) {
  out.precision(8);
  out << "name,fold,e_q_start,e_q_fitted,e_q_held_out,worst_phase,part_time_s\n";
  for (const auto& t : r.trials)
    out << '"' << t.name << "\"," << t.fold << ',' << t.e_q_start << ',' << t.e_q_fitted << ','
        << t.e_q_heldOut << ",\"" << t.worstPhase << "\"," << t.errors.partTime << '\n';
}

std::string trajectoryFitReportHtml(const validation::TrajectoryFitResult& r,
                                    const validation::TrajectoryFitOptions& o) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>vcontact fit: "
    << r.trials.size() << " trials</title><style>" << kPageStyle
    << "</style></head><body>\n<h1>vcontact fit: " << r.trials.size()
    << " dynamic trials</h1>\n<p>mean e_q: start " << num(r.meanStart) << ", fitted "
    << num(r.meanFitted) << ", " << o.folds << "-fold cross-validated (held out) "
    << num(r.meanHeldOut) << "; " << r.evaluations << " evaluations, " << r.trialSimulations
    << " trial simulations, " << num(r.seconds, 3) << " s wall, " << num(r.cpuSeconds, 3)
    << " s CPU</p>\n<table><tr><th>parameter</th><th>start</th><th>fitted</th><th>± std. error</th>"
       "<th>(Gauss–Newton)</th><th>unit</th><th>search box</th></tr>";
  for (const auto& p : r.parameters)
    h << "<tr><td>" << escapeXml(p.name) << "</td><td>" << num(p.start) << "</td><td>"
      << num(p.value) << "</td><td>" << num(p.stdError, 2) << "</td><td>"
      << num(p.gaussNewtonError, 2) << "</td><td>" << escapeXml(p.unit) << "</td><td>["
      << num(p.lower, 3) << ", " << num(p.upper, 3) << "] " << (p.logScale ? "log" : "linear")
      << "</td></tr>";
  h << "</table>\n<p>The standard error is the larger of the jackknife's over the folds (the "
       "fits without one fold's trials) and Gauss–Newton's when the fit is cross-validated, "
       "else Gauss–Newton's, which takes every sample as independent and so understates the "
       "error of a trajectory fit.</p>\n";
  for (const auto& w : r.warnings) h << "<p class=\"warnings\">" << escapeXml(w) << "</p>\n";
  std::vector<double> index, fitted, heldOut;
  for (std::size_t i = 0; i < r.trials.size(); ++i) {
    index.push_back(static_cast<double>(i));
    fitted.push_back(r.trials[i].e_q_fitted);
    heldOut.push_back(std::isnan(r.trials[i].e_q_heldOut) ? r.trials[i].e_q_fitted
                                                          : r.trials[i].e_q_heldOut);
  }
  h << lineChart({"e_q per trial", "trial", "e_q", kPageWidth, 300, true},
                 {{"fitted", index, fitted, "", true}, {"held out", index, heldOut, "", true}});
  std::vector<std::size_t> order(r.trials.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return heldOut[a] > heldOut[b]; });
  h << "<h2>Worst trials (held out)</h2><table><tr><th>trial</th><th>fold</th><th>e_q held out"
       "</th><th>e_q fitted</th><th>fails in</th><th>parts at (s)</th></tr>";
  for (std::size_t k = 0; k < std::min<std::size_t>(20, order.size()); ++k) {
    const auto& t = r.trials[order[k]];
    h << "<tr><td>" << escapeXml(t.name) << "</td><td>" << t.fold << "</td><td>"
      << num(t.e_q_heldOut) << "</td><td>" << num(t.e_q_fitted) << "</td><td>"
      << escapeXml(t.worstPhase) << "</td><td>" << num(t.errors.partTime, 3) << "</td></tr>";
  }
  h << "</table>\n</body></html>\n";
  return h.str();
}

json trajectoryDiagnosisJson(const validation::TrajectoryDiagnosis& d,
                             const validation::TrajectoryFitOptions& o) {
  json ranking = json::array();
  for (const auto& c : d.ranking) {
    json params = json::array();
    for (const auto& p : c.fit.parameters)
      params.push_back(
          {{"name", p.name}, {"value", p.value}, {"std_error", finiteOrNull(p.stdError)}});
    ranking.push_back(
        {{"effect", c.effect},
         {"added", c.added},
         {"mean_e_q_fitted", c.error.empty() ? json(c.fit.meanFitted) : json()},
         {"mean_e_q_held_out", c.error.empty() ? finiteOrNull(c.fit.meanHeldOut) : json()},
         {"mean_change", finiteOrNull(c.meanDelta)},
         {"change_std_error", finiteOrNull(c.deltaStdError)},
         {"accepted", c.accepted},
         {"rejected", c.rejected},
         {"error", c.error},
         {"parameters", params}});
  }
  json unexplained = json::array();
  for (const auto& u : d.unexplained)
    unexplained.push_back({{"trial", u.name},
                           {"index", u.index},
                           {"e_q_held_out", u.e_q},
                           {"best_model", u.model},
                           {"fails_in", u.phase},
                           {"hint", u.hint}});
  return {{"verdict", d.verdict},
          {"folds", o.folds},
          {"trials_count", d.baseline.trials.size()},
          {"acceptance",
           {{"paired_sigmas", validation::kPairedSigmas},
            {"unexplained_factor", validation::kUnexplainedFactor},
            {"unexplained_floor", validation::kUnexplainedFloor}}},
          {"baseline",
           {{"effects", d.baseline.model.effectIds()},
            {"mean_e_q_fitted", d.baseline.meanFitted},
            {"mean_e_q_held_out", finiteOrNull(d.baseline.meanHeldOut)}}},
          {"ranking", ranking},
          {"median_best_e_q_held_out", d.medianBest},
          {"unexplained", unexplained},
          {"wall_s", d.seconds}};
}

std::string trajectoryDiagnosisReportHtml(const validation::TrajectoryDiagnosis& d,
                                          const validation::TrajectoryFitOptions& o) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>vcontact diagnose: "
    << d.baseline.trials.size() << " trials</title><style>" << kPageStyle
    << "</style></head><body>\n<h1>vcontact diagnose: " << d.baseline.trials.size()
    << " dynamic trials</h1>\n<p><b>verdict: " << escapeXml(d.verdict)
    << "</b>. Baseline mean e_q: fitted " << num(d.baseline.meanFitted) << ", " << o.folds
    << "-fold cross-validated (held out) " << num(d.baseline.meanHeldOut) << "; "
    << num(d.seconds, 3) << " s wall. A candidate is accepted when its held-out e_q, paired by "
    << "trial, is lower than the baseline's by more than " << validation::kPairedSigmas
    << " standard errors.</p>\n<table><tr><th>candidate</th><th>adds</th><th>e_q held out</th>"
       "<th>change per trial</th><th>± std. error</th><th>accepted</th><th>why not</th></tr>";
  for (const auto& c : d.ranking) {
    std::string adds;
    for (const auto& a : c.added) adds += (adds.empty() ? "" : ", ") + a;
    h << "<tr><td>" << escapeXml(c.effect) << "</td><td>" << escapeXml(adds) << "</td><td>"
      << (c.error.empty() ? num(c.fit.meanHeldOut) : std::string("failed")) << "</td><td>"
      << num(c.meanDelta) << "</td><td>" << num(c.deltaStdError, 2) << "</td><td>"
      << (c.accepted ? "yes" : "no") << "</td><td>"
      << escapeXml(c.error.empty() ? c.rejected : c.error) << "</td></tr>";
  }
  h << "</table>\n<h2>Trials no model explains</h2>\n<p>best held-out e_q of any model above "
    << validation::kUnexplainedFactor << " times the median (" << num(d.medianBest) << ") and "
    << validation::kUnexplainedFloor << ": " << d.unexplained.size() << " of "
    << d.baseline.trials.size()
    << "</p><table><tr><th>trial</th><th>best e_q held out</th>"
       "<th>by</th><th>fails in</th><th>what the record says</th></tr>";
  for (const auto& u : d.unexplained)
    h << "<tr><td>" << escapeXml(u.name) << "</td><td>" << num(u.e_q) << "</td><td>"
      << escapeXml(u.model) << "</td><td>" << escapeXml(u.phase) << "</td><td>" << escapeXml(u.hint)
      << "</td></tr>";
  h << "</table>\n</body></html>\n";
  return h.str();
}

}  // namespace vcontact::report
