#include "validation/diagnose.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>
#include <variant>

#include "geometry/error.hpp"
#include "validation/phases.hpp"
#include "volume/contact.hpp"

namespace vcontact::validation {
namespace {

using dynamics::Model;

// A sample fails when the chi of the window around it exceeds 3: for a model that explains
// the data the window's mean (r/σ)² is 1 ± sqrt(2/m), so 9 is far out for any m ≥ 5.
constexpr double kWindowChi = 3.0;
// Window of the moving chi (phaseHalfWindow): long enough to average the noise, short enough
// to resolve an impact or a restart; 1 % of the record, at least 5 samples. A failing run
// shorter than that is a lone outlier.
constexpr std::size_t kMinWindowSamples = 5;
// Windows reported, worst (largest excess χ²) first.
constexpr std::size_t kMaxWindows = 8;

// Every effect `id` needs that `model` lacks, `id` first (MODEL.md §3 requirements).
// @throws InputError when a required effect is neither a candidate nor a library effect
void closure(const Model& model, const CandidateSet& set, const std::string& id,
             std::vector<std::string>& out) {
  if (model.has(id) || std::find(out.begin(), out.end(), id) != out.end()) return;
  const auto effect = set.create(id);
  if (!effect)
    throw InputError("candidates", "no effect '" + id + "' (required by " + out.front() + ")");
  out.push_back(id);
  for (auto req : effect->requiredEffects()) closure(model, set, std::string(req), out);
}

// The parameters of the added effects: what the candidate's multistart explores.
std::vector<std::string> addedParameters(const Model& m, const Candidate& c) {
  std::vector<std::string> out;
  for (const auto& name : m.parameterNames()) {
    for (const auto& id : c.added) {
      if (name.rfind(id + ".", 0) == 0) out.push_back(name);
    }
  }
  return out;
}

void tell(const DiagnoseOptions& options, const std::string& what, int done, int total) {
  if (options.progress) options.progress(what, done, total);
}

// @param replayer  the baseline's, copied by each candidate (its geometry shared)
void fitCandidates(const Replayer& replayer, const NoiseLevels& noise, const Model& baseline,
                   const DiagnoseOptions& options, const std::string& label,
                   std::vector<Candidate>& candidates) {
  std::atomic<int> done{0};
  const int total = static_cast<int>(candidates.size());
  tell(options, label + "candidates fitted", 0, total);
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t i) {
    Candidate& c = candidates[i];
    try {
      Replayer own_replayer = replayer;
      const Model start = candidateModel(baseline, options.candidates, c);
      FitOptions own = options.fit;
      own.explore = addedParameters(start, c);
      c.fit = fit(own_replayer, noise, start, own);
    } catch (const std::exception& e) {
      c.error = e.what();
    }
    tell(options, label + "candidates fitted", ++done, total);
  });
}

bool properSubset(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  if (a.size() >= b.size()) return false;
  return std::all_of(a.begin(), a.end(),
                     [&](const auto& x) { return std::find(b.begin(), b.end(), x) != b.end(); });
}

void rank(std::vector<Candidate>& candidates, double baselineBic, double margin) {
  for (auto& c : candidates) c.deltaBic = c.error.empty() ? c.fit.bic - baselineBic : 0.0;
  for (auto& c : candidates) {
    for (const auto& other : candidates) {
      if (!c.error.empty() || !other.error.empty() || !properSubset(other.added, c.added)) continue;
      if (c.fit.comparison.chi2 > other.fit.comparison.chi2 - margin)
        c.redundantWith = other.effect;
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) {
                     if (a.error.empty() != b.error.empty()) return a.error.empty();
                     if (a.redundantWith.empty() != b.redundantWith.empty())
                       return a.redundantWith.empty();
                     return a.deltaBic < b.deltaBic;
                   });
}

// ---- where ------------------------------------------------------------------------------

struct RegimeVariable {
  const char* name;
  const char* unit;
  const char* high;  // what a window far above the record's median means physically
  const char* low;
  bool tangential;  // describes tangential motion: not used for a window of normal motion
  std::function<double(const RegimeSample&)> get;
};

const std::vector<RegimeVariable>& regimeVariables() {
  static const std::vector<RegimeVariable> v = {
      {"sliding speed |v_t|", "m/s", "fast sliding", "sticking or slow sliding", true,
       [](const RegimeSample& r) { return r.speed; }},
      {"spin ratio r_gyr|ω_n|/|v_t|", "", "spin-dominated sliding", "translation-dominated sliding",
       true, [](const RegimeSample& r) { return r.spin_ratio; }},
      {"time without tangential motion", "s", "long without slip", "slipping", true,
       [](const RegimeSample& r) { return r.time_at_rest; }},
      {"rest before this motion", "s", "restart after a long stop", "restart after a short stop",
       true, [](const RegimeSample& r) { return r.preceding_rest; }},
      {"penetration rate δ̇_c", "m/s", "fast approach (impact)", "separating", false,
       [](const RegimeSample& r) { return r.penetration_rate; }},
      {"normal load f_n", "N", "high load", "light load or no contact", false,
       [](const RegimeSample& r) { return r.load; }},
  };
  return v;
}

// A phase of normal motion only: tangential regime variables say nothing of it.
bool normalPhase(Phase p) {
  return p == Phase::kApproach || p == Phase::kSeparation || p == Phase::kLoading ||
         p == Phase::kHolding || p == Phase::kUnloading;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

std::string format3(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// Mean mid-rank percentile of the window's samples within the whole record: 0.5 when the
// window is typical of the record in this variable, near 1 (0) when it sits at the top
// (bottom) of its range. A rank statistic (Mann–Whitney), blind to units and outliers.
double windowRank(const std::vector<double>& all, const std::vector<double>& sorted, std::size_t a,
                  std::size_t b) {
  double sum = 0.0;
  for (std::size_t i = a; i <= b; ++i) {
    const auto lo = std::lower_bound(sorted.begin(), sorted.end(), all[i]);
    const auto hi = std::upper_bound(sorted.begin(), sorted.end(), all[i]);
    sum += (static_cast<double>(lo - sorted.begin()) + 0.5 * static_cast<double>(hi - lo));
  }
  return sum / (static_cast<double>(b - a + 1) * static_cast<double>(sorted.size()));
}

// The regime variable in which the window [a, b] of phase `phase` is most unlike the whole
// record (the tangential ones only for a window with tangential motion).
std::string describeRegime(const std::vector<RegimeSample>& regime, std::size_t a, std::size_t b,
                           Phase phase) {
  double best = 0.0;
  std::string text = "typical of the record in every regime variable";
  for (const auto& var : regimeVariables()) {
    if (var.tangential && normalPhase(phase)) continue;
    std::vector<double> all;
    for (const auto& r : regime) all.push_back(var.get(r));
    std::vector<double> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    const double q = windowRank(all, sorted, a, b);
    if (std::abs(q - 0.5) <= best) continue;
    best = std::abs(q - 0.5);
    const std::vector<double> in(all.begin() + static_cast<std::ptrdiff_t>(a),
                                 all.begin() + static_cast<std::ptrdiff_t>(b) + 1);
    std::ostringstream s;
    const bool high = q > 0.5;
    s << var.name << " in [" << format3(quantile(in, 0.1)) << ", " << format3(quantile(in, 0.9))
      << "]";
    if (*var.unit) s << ' ' << var.unit;
    s << " (" << (high ? var.high : var.low) << ")";
    text = s.str();
  }
  return text;
}

void windowsOf(const Dataset& d, const OutputResiduals& r, const Prediction& p,
               const std::vector<Phase>& phases,
               std::vector<std::pair<double, FailureWindow>>& out) {
  const auto n = static_cast<std::size_t>(r.residual.size());
  const std::size_t half = phaseHalfWindow(n);
  const Eigen::VectorXd e2 = (r.residual / r.sigma).array().square();
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + e2[static_cast<Eigen::Index>(i)];
  auto meanOver = [&](std::size_t a, std::size_t b) {  // inclusive
    return (cum[b + 1] - cum[a]) / static_cast<double>(b - a + 1);
  };
  std::vector<bool> failing(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i >= half ? i - half : 0, b = std::min(n - 1, i + half);
    failing[i] = meanOver(a, b) > kWindowChi * kWindowChi;
  }
  for (std::size_t i = 0; i < n;) {
    if (!failing[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;  // a window ends where the failing run or the phase does
    while (j + 1 < n && failing[j + 1] && phases[j + 1] == phases[i]) ++j;
    if (j + 1 - i < kMinWindowSamples) {  // a lone outlier, not a regime
      i = j + 1;
      continue;
    }
    FailureWindow w{r.output,
                    d.samples[i].t,
                    d.samples[j].t,
                    std::sqrt(meanOver(i, j)),
                    describeRegime(p.regime, i, j, phases[i]),
                    std::string(phaseName(phases[i]))};
    const double excess = cum[j + 1] - cum[i] - static_cast<double>(j - i + 1);
    out.emplace_back(excess, std::move(w));
    i = j + 1;
  }
}

// Why the candidate's added parameters are not physical; empty when they are.
std::string unphysical(const Candidate& c) {
  for (const auto& p : c.fit.parameters) {
    if (p.fixed || p.atBound.empty()) continue;
    for (const auto& id : c.added) {
      if (p.name.rfind(id + ".", 0) == 0)
        return p.name + " = " + format3(p.value) + " is at its " + p.atBound + " bound";
    }
  }
  return {};
}

// Steps 1–3 of the acceptance (see the header); marks the first accepted candidate.
void accept(const Dataset& dataset, const NoiseLevels& noise, const DiagnoseOptions& options,
            const std::string& label, DiagnosisStage& stage) {
  std::size_t validated = 0;
  for (auto& c : stage.ranking) {
    if (!c.error.empty() || !c.redundantWith.empty()) continue;
    if (!(c.deltaBic < -options.margin)) break;  // ranked: the rest are worse
    c.rejected = unphysical(c);
    if (!c.rejected.empty()) continue;
    if (validated++ == kCvCandidates) {
      c.rejected = "not cross-validated (only the best " + std::to_string(kCvCandidates) + " are)";
      continue;
    }
    tell(options, label + "cross-validating " + c.effect, static_cast<int>(validated),
         static_cast<int>(kCvCandidates));
    c.heldOutChi2 = heldOutChi2(dataset, noise, c.fit.model, options.fit);
    const double drop = stage.heldOutChi2 - c.heldOutChi2;
    const double excess = stage.heldOutChi2 - static_cast<double>(stage.baseline.comparison.count);
    const double needed = std::max(options.heldOutMargin, kHeldOutShare * excess);
    if (!(drop > needed)) {
      c.rejected = "held-out chi2 falls by " + format3(drop) + ", not more than " +
                   format3(needed) + " (the margin, or a quarter of the excess over the noise)";
      continue;
    }
    c.accepted = true;
    return;
  }
}

// χ² left after the rig finding (refined with the contact model refitted where it was).
double rigChi2(const DiagnosisStage& stage, const RigFinding& rig) {
  return rig.remainingChi2 >= 0.0 ? rig.remainingChi2
                                  : stage.baseline.comparison.chi2 - rig.chi2Drop;
}

// The physical candidate that explains the residual as well as the rig finding (χ² within
// the margin of what the finding leaves), its parameters physical; null when none does.
const Candidate* physicalRival(const DiagnosisStage& stage, const RigFinding& rig, double margin) {
  const Candidate* best = nullptr;
  for (const auto& c : stage.ranking) {
    if (!c.error.empty() || !c.redundantWith.empty() || !(c.deltaBic < -margin)) continue;
    if (!unphysical(c).empty()) continue;
    if (!best || c.fit.comparison.chi2 < best->fit.comparison.chi2) best = &c;
  }
  return best && best->fit.comparison.chi2 <= rigChi2(stage, rig) + margin ? best : nullptr;
}

void decide(const Dataset& dataset, const DiagnoseOptions& options, DiagnosisStage& stage) {
  const auto accepted = std::find_if(stage.ranking.begin(), stage.ranking.end(),
                                     [](const Candidate& c) { return c.accepted; });
  // a rig verdict needs the (refined) finding to pass the margin and to remove at least
  // kRigShare of the baseline's excess χ² (χ² − n): a rig artifact is one global correction,
  // not a partial stand-in for structure it does not explain
  const double excess =
      stage.baseline.comparison.chi2 - static_cast<double>(stage.baseline.comparison.count);
  const RigFinding* rig = !stage.rig.empty() && stage.rig.front().deltaBic < -options.margin &&
                                  stage.rig.front().chi2Drop >= kRigShare * excess
                              ? &stage.rig.front()
                              : nullptr;
  double bestChi2 = stage.baseline.comparison.chi2;
  for (const auto& c : stage.ranking) {
    if (c.error.empty()) bestChi2 = std::min(bestChi2, c.fit.comparison.chi2);
  }
  const double base = stage.baseline.comparison.chi2;
  stage.explainedFraction = base > 0.0 ? std::max(0.0, 1.0 - bestChi2 / base) : 0.0;
  stage.residual = describeResidual(dataset, stage.baseline);
  const Candidate* explains = rig ? physicalRival(stage, *rig, options.margin) : nullptr;
  const bool acceptedFirst =
      accepted != stage.ranking.end() &&
      (!rig || accepted->deltaBic <= rig->deltaBic ||
       accepted->fit.comparison.chi2 <= rigChi2(stage, *rig) + options.margin);
  const bool singleChannelLag = rig && rig->kind == "lag" && dataset.outputs.size() == 1;
  const bool faceting = stage.geometry && stage.geometry->chi2 < base - options.margin &&
                        (!rig || stage.geometry->chi2 <= rigChi2(stage, *rig) + options.margin) &&
                        (accepted == stage.ranking.end() ||
                         stage.geometry->chi2 <= accepted->fit.comparison.chi2 + options.margin);
  if (faceting) {
    stage.kind = "geometry";
    stage.verdict = "geometry: " + stage.geometry->text;
  } else if (acceptedFirst) {
    stage.kind = "effect";
    stage.verdict = accepted->effect;
  } else if (singleChannelLag || (rig && explains)) {
    // the record cannot separate the rig finding from physics (see the header)
    stage.kind = "ambiguous";
    stage.verdict = (singleChannelLag ? std::string("lag") : rig->text) + " or " +
                    (explains ? explains->effect : std::string("viscoelastic")) + ": cannot tell";
  } else if (rig) {
    stage.kind = "rig";
    stage.verdict = "rig: " + rig->text;
  } else if (stage.baseline.comparison.chi <= options.explainedChi) {
    stage.kind = stage.verdict = "none";
  } else {
    stage.kind = stage.verdict = "unexplained";
  }
}

// The faceting check (see the header): nothing unless the payload is a mesh on a half-space
// read without its recovered surface and the surfaces can be recognised.
std::optional<GeometryCheck> facetingCheck(const Dataset& dataset, const NoiseLevels& noise,
                                           const FitResult& baseline, const FitOptions& options) {
  const auto* mesh = std::get_if<geometry::Mesh>(&dataset.payload);
  if (!mesh || dataset.payload_surface ||
      !std::holds_alternative<geometry::HalfSpace>(dataset.plate))
    return std::nullopt;
  Dataset recovered = dataset;
  try {
    recovered.payload_surface = volume::recoverSurface(mesh->mesh);
  } catch (const InputError&) {
    return std::nullopt;  // not closed or not oriented: nothing to recover
  }
  FitOptions own = options;
  own.designPoints = 0;  // from the mesh's optimum
  Replayer replayer(recovered);
  const FitResult refit = fit(replayer, noise, baseline.model, own);
  GeometryCheck g{refit.comparison.chi2, refit.comparison.chi,
                  "faceting: the recovered surface gives chi " + format3(refit.comparison.chi) +
                      " (the mesh " + format3(baseline.comparison.chi) + ")"};
  return g;
}

// Seconds since `t`, and t reset to now.
double lap(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

DiagnosisStage diagnoseStage(const Dataset& dataset, const NoiseLevels& noise, const Model& start,
                             const DiagnoseOptions& options, bool explore, std::size_t index) {
  DiagnosisStage stage;
  auto t = std::chrono::steady_clock::now();
  const std::string label = "diagnose: stage " + std::to_string(index + 1) + ": ";
  tell(options, label + "baseline fit", 0, 0);
  stage.effects = start.effectIds();
  Replayer replayer(dataset);
  FitOptions baselineOptions = options.fit;
  if (!explore) baselineOptions.designPoints = 0;  // the start is the previous optimum
  stage.baseline = fit(replayer, noise, start, baselineOptions);
  stage.where = failureWindows(dataset, stage.baseline.comparison, stage.baseline.prediction);
  stage.direct = directEstimates(dataset, noise, stage.baseline.prediction);
  compareWithFit(dataset, stage.baseline, stage.direct);
  stage.seconds.baseline = lap(t);
  stage.ranking = candidateList(stage.baseline.model, options);
  fitCandidates(replayer, noise, stage.baseline.model, options, label, stage.ranking);
  rank(stage.ranking, stage.baseline.bic, options.margin);
  stage.seconds.candidates = lap(t);
  tell(options, label + "cross-validating the baseline", 0, 0);
  stage.heldOutChi2 = heldOutChi2(dataset, noise, stage.baseline.model, options.fit);
  accept(dataset, noise, options, label, stage);
  stage.seconds.crossValidation = lap(t);
  tell(options, label + "rig candidates", 0, 0);
  stage.rig = rigCandidates(dataset, stage.baseline.comparison);
  if (!stage.rig.empty() && stage.rig.front().deltaBic < -options.margin)
    stage.rig.front() = refineRig(dataset, noise, stage.baseline, stage.rig.front(), options.fit);
  if (stage.baseline.comparison.chi > options.explainedChi)
    stage.geometry = facetingCheck(dataset, noise, stage.baseline, options.fit);
  decide(dataset, options, stage);
  stage.seconds.rest = lap(t);
  return stage;
}

// `model` without effect `id`, or nothing when another effect of it requires `id`.
std::optional<Model> without(const Model& model, const std::string& id) {
  Model m;
  m.settings = model.settings;
  for (std::size_t i = 0; i < model.effectCount(); ++i) {
    const auto& e = model.effect(i);
    if (e.id() == id) continue;
    const auto req = e.requiredEffects();
    if (std::find(req.begin(), req.end(), id) != req.end()) return std::nullopt;
    m.add(e.clone());
  }
  std::vector<std::string> fixed;
  const auto names = m.parameterNames();
  for (const auto& f : model.fixed()) {
    if (std::find(names.begin(), names.end(), f) != names.end()) fixed.push_back(f);
  }
  m.setFixed(fixed);
  return m;
}

// Backward elimination over the effects the iteration added (see the header).
void prune(const Dataset& dataset, const NoiseLevels& noise, const DiagnoseOptions& options,
           Diagnosis& d) {
  std::vector<std::string> added;
  for (std::size_t i = 0; i + 1 < d.stages.size(); ++i) added.push_back(d.stages[i].verdict);
  if (added.size() < 2) return;
  for (const auto& id : added) {
    const FitResult& current = d.final();
    const auto reduced = without(current.model, id);
    if (!reduced) continue;
    Replayer replayer(dataset);
    const FitResult refit = fit(replayer, noise, *reduced, options.fit);
    if (refit.bic >= current.bic + options.margin) continue;
    DiagnosisStage stage = diagnoseStage(dataset, noise, *reduced, options, false, d.stages.size());
    stage.removed = id;
    d.stages.push_back(std::move(stage));
  }
}

}  // namespace

std::vector<FailureWindow> failureWindows(const Dataset& dataset, const Comparison& comparison,
                                          const Prediction& prediction) {
  std::vector<std::pair<double, FailureWindow>> all;
  const std::vector<Phase> phases = phasesOf(prediction.regime, phaseHalfWindow(dataset.size()));
  for (const auto& r : comparison.outputs) windowsOf(dataset, r, prediction, phases, all);
  std::stable_sort(all.begin(), all.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<FailureWindow> out;
  for (std::size_t i = 0; i < std::min(all.size(), kMaxWindows); ++i) out.push_back(all[i].second);
  return out;
}

Model candidateModel(const Model& baseline, const CandidateSet& set, const Candidate& c) {
  Model m = baseline;
  for (const auto& id : c.added) m.add(set.create(id));
  m.setFixed(baseline.fixed());
  return m;
}

std::vector<Candidate> candidateList(const Model& model, const DiagnoseOptions& options) {
  std::vector<Candidate> candidates;
  for (const auto& id : options.candidates.ids()) {
    if (model.has(id)) continue;
    Candidate c;
    c.effect = id;
    closure(model, options.candidates, id, c.added);
    candidates.push_back(std::move(c));
  }
  return candidates;
}

Diagnosis diagnose(const Dataset& dataset, const NoiseLevels& noise, const Model& start,
                   const DiagnoseOptions& given) {
  DiagnoseOptions options = given;
  options.fit.progress = nullptr;  // fits run in parallel: the stages report, not each fit
  Diagnosis d;
  d.stages.push_back(diagnoseStage(dataset, noise, start, options, true, 0));
  while (options.iterate && d.stages.back().kind == "effect") {
    const DiagnosisStage& last = d.stages.back();
    const auto best = std::find_if(last.ranking.begin(), last.ranking.end(),
                                   [](const Candidate& c) { return c.accepted; });
    d.stages.push_back(
        diagnoseStage(dataset, noise, best->fit.model, options, false, d.stages.size()));
  }
  if (options.iterate) prune(dataset, noise, options, d);
  return d;
}

}  // namespace vcontact::validation
