#include "validation/trajectory_diagnose.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "geometry/error.hpp"
#include "validation/diagnose.hpp"

namespace vcontact::validation {
namespace {

// Mean and standard error of the mean of Δ_i = candidate's held-out e_q − the baseline's.
void pairedDelta(const TrajectoryFitResult& baseline, TrajectoryCandidate& c) {
  const std::size_t n = baseline.trials.size();
  std::vector<double> delta;
  for (std::size_t i = 0; i < n; ++i)
    delta.push_back(c.fit.trials[i].e_q_heldOut - baseline.trials[i].e_q_heldOut);
  double mean = 0.0;
  for (double d : delta) mean += d / static_cast<double>(n);
  double ss = 0.0;
  for (double d : delta) ss += (d - mean) * (d - mean);
  c.meanDelta = mean;
  c.deltaStdError = n > 1 ? std::sqrt(ss / static_cast<double>(n - 1) / static_cast<double>(n))
                          : std::numeric_limits<double>::quiet_NaN();
}

std::string acceptance(const TrajectoryCandidate& c) {
  std::ostringstream why;
  why.precision(3);
  if (!(c.meanDelta < 0.0)) {
    why << "raises the held-out e_q (mean change " << c.meanDelta << " per trial)";
  } else if (!(-c.meanDelta > kPairedSigmas * c.deltaStdError)) {
    why << "lowers the held-out e_q by " << -c.meanDelta << " per trial, within " << kPairedSigmas
        << " standard errors (" << c.deltaStdError << ")";
  }
  return why.str();
}

TrajectoryCandidate fitCandidate(const std::vector<Trial>& trials, const TrajectoryFitResult& base,
                                 const Candidate& listed, const TrajectoryDiagnoseOptions& o) {
  TrajectoryCandidate c;
  c.effect = listed.effect;
  c.added = listed.added;
  TrajectoryFitOptions fit = o.fit;
  fit.progress = nullptr;
  fit.settings.plateOffset = base.plateOffset;
  try {
    c.fit = fitTrajectories(trials, candidateModel(base.model, o.candidates, listed), fit);
  } catch (const std::exception& e) {
    c.error = e.what();
    return c;
  }
  pairedDelta(base, c);
  c.rejected = acceptance(c);
  c.accepted = c.rejected.empty();
  return c;
}

// What the record says about a trial no model explains (see the header).
std::string hintFor(const Trial& t, const std::string& phase) {
  std::ostringstream hint;
  hint.precision(3);
  const auto sigma = t.data.noise.find("position");
  if (t.start.estimated && sigma != t.data.noise.end() &&
      t.start.positionRms > kFlightResidualSigmas * sigma->second) {
    hint << "the flight before the first contact is not a free body's (the parabola leaves "
         << t.start.positionRms << " m against sigma " << sigma->second
         << " m): a bad marker track, or a toss that starts in hand";
    return hint.str();
  }
  const double sink = recordedSink(t.data);
  const double margin = contactMargin(t.data);
  if (sink > margin) {
    hint << "the record goes " << sink << " m below the plate (margin " << margin
         << " m): it rests where the plate is not (a table edge) or a marker was lost";
    return hint.str();
  }
  if (phase == "flight") return "the flight differs from a free body's: a bad marker track";
  if (phase == "impacts")
    return "the landing: an edge or corner strike the model does not reproduce";
  if (phase == "rest") return "the rest pose: an uneven board, or the plate offset";
  return "the " + phase + ": friction or rolling that the model does not reproduce";
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

void findUnexplained(const std::vector<Trial>& trials, TrajectoryDiagnosis& d) {
  std::vector<double> best;
  std::vector<const TrialScore*> by;
  std::vector<std::string> model;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    best.push_back(d.baseline.trials[i].e_q_heldOut);
    by.push_back(&d.baseline.trials[i]);
    model.emplace_back("baseline");
    for (const auto& c : d.ranking) {
      if (!c.error.empty() || !(c.fit.trials[i].e_q_heldOut < best[i])) continue;
      best[i] = c.fit.trials[i].e_q_heldOut;
      by[i] = &c.fit.trials[i];
      model[i] = c.effect;
    }
  }
  d.medianBest = median(best);
  const double limit = std::max(kUnexplainedFactor * d.medianBest, kUnexplainedFloor);
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (!(best[i] > limit)) continue;
    d.unexplained.push_back({i, trials[i].data.name, best[i], model[i], by[i]->worstPhase,
                             hintFor(trials[i], by[i]->worstPhase)});
  }
  std::sort(d.unexplained.begin(), d.unexplained.end(),
            [](const auto& a, const auto& b) { return a.e_q > b.e_q; });
}

}  // namespace

TrajectoryDiagnosis diagnoseTrajectories(const std::vector<Trial>& trials,
                                         const dynamics::Model& start,
                                         const TrajectoryDiagnoseOptions& options) {
  if (!crossValidates(options.fit, trials.size()))
    throw InputError("--folds",
                     "a diagnosis ranks effects by held-out e_q: it needs k >= 2 "
                     "folds and at least k trials (" +
                         std::to_string(trials.size()) + " given)");
  const auto begin = std::chrono::steady_clock::now();
  DiagnoseOptions listing;
  listing.candidates = options.candidates;
  const std::vector<Candidate> listed = candidateList(start, listing);
  const int total = 1 + static_cast<int>(listed.size());
  TrajectoryDiagnosis d;
  if (options.progress) options.progress("baseline", 0, total);
  TrajectoryFitOptions fit = options.fit;
  fit.progress = nullptr;
  d.baseline = fitTrajectories(trials, start, fit);
  for (std::size_t k = 0; k < listed.size(); ++k) {
    if (options.progress)
      options.progress("candidate " + listed[k].effect, static_cast<int>(k) + 1, total);
    d.ranking.push_back(fitCandidate(trials, d.baseline, listed[k], options));
  }
  if (options.progress) options.progress("done", total, total);
  std::stable_sort(d.ranking.begin(), d.ranking.end(), [](const auto& a, const auto& b) {
    if (a.error.empty() != b.error.empty()) return a.error.empty();
    return a.fit.meanHeldOut < b.fit.meanHeldOut;
  });
  d.verdict = d.accepted() ? d.accepted()->effect : "none";
  findUnexplained(trials, d);
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return d;
}

}  // namespace vcontact::validation
