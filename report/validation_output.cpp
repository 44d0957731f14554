#include "report/validation_output.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"

namespace vcontact::report {
namespace {

using nlohmann::json;
using validation::Comparison;
using validation::FitResult;

// JSON has no infinity or NaN: those become null ("not identifiable", "fixed").
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json rmsJson(const Comparison& c) {
  json rms = json::object();
  for (const auto& o : c.outputs) rms[o.output] = o.rms;
  return rms;
}

json parametersJson(const FitResult& fit) {
  json params = json::object();
  for (const auto& p : fit.parameters) {
    if (p.fixed) continue;
    params[p.name] = p.value;
  }
  return params;
}

// Names of the free parameters at a bound, with the bound: {"bristle.sigma0": "upper"}.
json atBoundJson(const FitResult& fit) {
  json at = json::object();
  for (const auto& p : fit.parameters) {
    if (!p.fixed && !p.atBound.empty()) at[p.name] = p.atBound;
  }
  return at;
}

json rigJson(const validation::DiagnosisStage& s) {
  json rig = json::array();
  for (const auto& r : s.rig) {
    rig.push_back({{"kind", r.kind},
                   {"output", r.output},
                   {"value", r.value},
                   {"unit", r.unit},
                   {"chi2_drop", r.chi2Drop},
                   {"delta_bic", r.deltaBic},
                   {"text", r.text}});
  }
  return rig;
}

json residualJson(const validation::DiagnosisStage& s) {
  const auto& r = s.residual;
  json corr = json::object();
  for (const auto& [name, value] : r.correlation) corr[name] = value;
  return {{"explained_fraction", s.explainedFraction},
          {"noise_share", r.noiseShare},
          {"worst_output", r.output},
          {"dominant_frequency", r.frequency > 0.0 ? json(r.frequency) : json(nullptr)},
          {"frequency_share", r.frequencyShare},
          {"abs_residual_correlation", corr}};
}

json stageSummary(const validation::DiagnosisStage& s) {
  return {{"effects", s.effects},
          {"chi", s.baseline.comparison.chi},
          {"held_out_chi2", number(s.heldOutChi2)},
          {"chi2", s.baseline.comparison.chi2},
          {"bic", s.baseline.bic},
          {"rms", rmsJson(s.baseline.comparison)},
          {"params", parametersJson(s.baseline)},
          {"at_bound", atBoundJson(s.baseline)},
          {"direct_estimates", directEstimatesJson(s.direct)},
          {"warnings", s.baseline.warnings},
          {"verdict", s.verdict},
          {"kind", s.kind},
          {"rig", rigJson(s)},
          {"geometry", s.geometry ? json{{"chi", s.geometry->chi},
                                         {"chi2", s.geometry->chi2},
                                         {"text", s.geometry->text}}
                                  : json(nullptr)},
          {"residual", residualJson(s)},
          {"removed", s.removed.empty() ? json(nullptr) : json(s.removed)}};
}

json rankingJson(const validation::DiagnosisStage& s) {
  json ranking = json::array();
  for (const auto& c : s.ranking) {
    json r = {{"effect", c.effect}, {"added", c.added}};
    if (!c.error.empty()) {
      r["error"] = c.error;
    } else {
      r["chi"] = c.fit.comparison.chi;
      r["delta_bic"] = c.deltaBic;
      r["params"] = parametersJson(c.fit);
      r["at_bound"] = atBoundJson(c.fit);
      r["held_out_chi2"] = number(c.heldOutChi2);
      r["accepted"] = c.accepted;
      if (!c.rejected.empty()) r["rejected"] = c.rejected;
      if (!c.redundantWith.empty()) r["redundant_with"] = c.redundantWith;
      if (!c.fit.warnings.empty()) r["warnings"] = c.fit.warnings;
    }
    ranking.push_back(std::move(r));
  }
  return ranking;
}

json whereJson(const validation::DiagnosisStage& s) {
  json where = json::array();
  for (const auto& w : s.where) {
    where.push_back({{"output", w.output},
                     {"t0", w.t0},
                     {"t1", w.t1},
                     {"chi", w.chi},
                     {"phase", w.phase},
                     {"regime", w.regime}});
  }
  return where;
}

}  // namespace

json directEstimatesJson(const std::vector<validation::DirectEstimate>& estimates) {
  json out = json::array();
  for (const auto& e : estimates) {
    out.push_back({{"parameter", e.parameter},
                   {"unit", e.unit},
                   {"value", number(e.value)},
                   {"low", number(e.low)},
                   {"high", number(e.high)},
                   {"samples", e.samples},
                   {"t0", e.t0},
                   {"t1", e.t1},
                   {"method", e.method},
                   {"fitted", number(e.fitted)},
                   {"far", e.far},
                   {"pull", e.pull.empty() ? json(nullptr) : json(e.pull)}});
  }
  return out;
}

void putResidualsCsv(const validation::Dataset& d, const Comparison& c, std::ostream& out) {
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "t";
  for (const auto& o : c.outputs) {
    out << ',' << o.output << "_measured," << o.output << "_model," << o.output << "_residual,"
        << o.output << "_normalised";
  }
  out << '\n';
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    out << d.samples[i].t;
    for (const auto& o : c.outputs) {
      out << ',' << o.measured[k] << ',' << o.predicted[k] << ',' << o.residual[k] << ','
          << o.residual[k] / o.sigma;
    }
    out << '\n';
  }
}

json comparisonJson(const Comparison& c, const validation::NoiseLevels& noise) {
  json sigma = json::object();
  for (const auto& [o, n] : noise) {
    sigma[o] = {{"value", n.sigma},
                {"source", n.estimated ? "estimated: 1.4826 MAD of second differences / sqrt(6)"
                                       : "sidecar noise"}};
  }
  return {{"chi", c.chi},
          {"chi2", c.chi2},
          {"residuals", c.count},
          {"rms", rmsJson(c)},
          {"sigma", sigma}};
}

json fitJson(const FitResult& fit, const validation::NoiseLevels& noise, validation::Loss loss,
             const std::vector<validation::DirectEstimate>* direct) {
  json params = json::array();
  for (const auto& p : fit.parameters) {
    params.push_back({{"name", p.name},
                      {"unit", p.unit},
                      {"initial", p.initial},
                      {"value", p.value},
                      {"std_error", number(p.stdError)},
                      {"fixed", p.fixed},
                      {"identifiable", p.identifiable},
                      {"at_bound", p.fixed ? json(false) : json(!p.atBound.empty())},
                      {"bound", p.atBound.empty() ? json(nullptr) : json(p.atBound)}});
  }
  json corr = json::array();
  for (Eigen::Index i = 0; i < fit.correlation.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < fit.correlation.cols(); ++j)
      row.push_back(number(fit.correlation(i, j)));
    corr.push_back(std::move(row));
  }
  json j = {{"comparison", comparisonJson(fit.comparison, noise)},
            {"bic", fit.bic},
            {"free_parameters", fit.freeCount},
            {"loss", validation::lossName(loss)},
            {"converged", fit.converged},
            {"iterations", fit.iterations},
            {"multistart", {{"polished", fit.startsPolished}, {"winning_start", fit.winningStart}}},
            {"solver", fit.solverReport},
            {"parameters", params},
            {"correlation", {{"names", fit.freeNames}, {"matrix", corr}}},
            {"warnings", fit.warnings},
            {"model", formats::modelToJson(fit.model)}};
  if (direct) j["direct_estimates"] = directEstimatesJson(*direct);
  return j;
}

json diagnosisJson(const validation::Diagnosis& d, const validation::NoiseLevels& noise) {
  const auto& first = d.stages.front();
  json j = {{"verdict", first.verdict},
            {"kind", first.kind},
            {"margin", validation::kBicMargin},
            {"held_out_margin", validation::kHeldOutMargin},
            {"cv_blocks", validation::kCvBlocks},
            {"baseline", stageSummary(first)},
            {"ranking", rankingJson(first)},
            {"where", whereJson(first)},
            {"sigma", comparisonJson(first.baseline.comparison, noise)["sigma"]}};
  if (d.stages.size() > 1) {
    json stages = json::array();
    for (const auto& s : d.stages) {
      json st = stageSummary(s);
      st["ranking"] = rankingJson(s);
      st["where"] = whereJson(s);
      stages.push_back(std::move(st));
    }
    j["stages"] = std::move(stages);
    j["final"] = {{"effects", d.final().model.effectIds()},
                  {"chi", d.final().comparison.chi},
                  {"held_out_chi2", number(d.stages.back().heldOutChi2)},
                  {"verdict", d.stages.back().verdict},
                  {"kind", d.stages.back().kind},
                  {"where", whereJson(d.stages.back())},
                  {"model", formats::modelToJson(d.final().model)}};
  }
  return j;
}

}  // namespace vcontact::report
