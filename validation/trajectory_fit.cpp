#include "validation/trajectory_fit.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <nlopt.hpp>

#include "geometry/error.hpp"

namespace vcontact::validation {
namespace {

// The loss of a parameter vector the model refuses (a broken relation): worse than any toss.
constexpr double kRefusedLoss = 1e3;
// Points of the global phase closer than this (unit box) start one polish, not two.
constexpr double kDistinctStarts = 0.05;
// Subplex's first step in the unit box, and the finite-difference step of the Jacobian.
constexpr double kLocalStep = 0.05;
constexpr double kJacobianStep = 0.01;

struct Dimension {
  std::string name, unit;
  double start, lower, upper;
  bool log = false;
  bool offset = false;  // the plate offset, not a model parameter
};

std::vector<Dimension> searchSpace(const dynamics::Model& model, bool fitOffset,
                                   double startOffset) {
  std::vector<Dimension> dims;
  const auto& fixed = model.fixed();
  for (const auto& spec : model.parameterSpecs()) {
    if (std::find(fixed.begin(), fixed.end(), spec.name) != fixed.end()) continue;
    const double p0 = model.parameter(spec.name);
    Dimension d{spec.name, spec.unit, p0, spec.lower, spec.upper};
    if (p0 > 0.0 && spec.lower >= 0.0) {
      d.log = true;
      d.lower = std::max(spec.lower, p0 / kSearchFactor);
      d.upper = std::min(spec.upper, p0 * kSearchFactor);
      if (d.lower <= 0.0) d.lower = p0 / kSearchFactor;
    } else {
      d.lower = std::max(spec.lower, p0 - 1.0);
      d.upper = std::min(spec.upper, p0 + 1.0);
    }
    dims.push_back(d);
  }
  if (fitOffset)
    dims.push_back(
        {"plate.offset", "m", startOffset, -kPlateOffsetRange, kPlateOffsetRange, false, true});
  return dims;
}

double fromUnit(const Dimension& d, double u) {
  u = std::clamp(u, 0.0, 1.0);
  if (d.log) return std::exp(std::log(d.lower) + u * (std::log(d.upper) - std::log(d.lower)));
  return d.lower + u * (d.upper - d.lower);
}

double toUnit(const Dimension& d, double p) {
  if (d.upper <= d.lower) return 0.5;
  if (d.log) return (std::log(p) - std::log(d.lower)) / (std::log(d.upper) - std::log(d.lower));
  return (p - d.lower) / (d.upper - d.lower);
}

// The model and settings of a point u of the unit box.
struct Point {
  dynamics::Model model;
  TrajectorySettings settings;
};

Point place(const std::vector<Dimension>& dims, const std::vector<double>& u,
            const dynamics::Model& start, const TrajectorySettings& settings) {
  Point p{start, settings};
  for (std::size_t k = 0; k < dims.size(); ++k) {
    const double v = fromUnit(dims[k], u[k]);
    if (dims[k].offset)
      p.settings.plateOffset = v;
    else
      p.model.setParameter(dims[k].name, v);
  }
  p.model.validate();
  return p;
}

std::vector<std::size_t> allTrials(std::size_t n) {
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  return all;
}

struct Evaluator {
  const std::vector<Trial>& trials;
  std::vector<std::size_t> subset;
  const std::vector<Dimension>& dims;
  const dynamics::Model& start;
  const TrajectoryFitOptions& options;
  TrajectoryFoldFit& part;
  std::string stage;
  int total = 0;
  int done = 0;
  std::vector<std::pair<std::vector<double>, double>> seen;  // every point and its loss

  double operator()(const std::vector<double>& u) {
    double loss = kRefusedLoss;
    try {
      const Point p = place(dims, u, start, options.settings);
      loss = meanTrialLoss(trials, subset, p.model, p.settings);
    } catch (const InputError&) {
    }
    ++part.evaluations;
    part.trialSimulations += static_cast<long>(subset.size());
    seen.emplace_back(u, loss);
    if (options.progress) options.progress(stage, ++done, total);
    return loss;
  }
};

double callback(unsigned n, const double* x, double* grad, void* data) {
  (void)grad;  // derivative-free algorithms only
  return (*static_cast<Evaluator*>(data))(std::vector<double>(x, x + n));
}

// Global DIRECT-L over the unit box, then Subplex from the best distinct points; the best u.
std::vector<double> optimise(Evaluator& eval, const std::vector<double>& u0) {
  const unsigned n = static_cast<unsigned>(eval.dims.size());
  const auto& o = eval.options;
  eval.total = o.globalEvaluations + o.starts * o.localEvaluations + 1;
  eval(u0);  // the start itself is a candidate
  if (n == 0) return u0;
  nlopt::opt global(nlopt::GN_DIRECT_L, n);
  global.set_lower_bounds(std::vector<double>(n, 0.0));
  global.set_upper_bounds(std::vector<double>(n, 1.0));
  global.set_min_objective(callback, &eval);
  global.set_maxeval(o.globalEvaluations);
  std::vector<double> x(n, 0.5);
  double f = 0.0;
  try {
    global.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {
  }
  auto ranked = eval.seen;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.second < b.second; });
  std::vector<std::vector<double>> starts;
  for (const auto& point : ranked) {
    if (static_cast<int>(starts.size()) >= o.starts) break;
    const std::vector<double>& u = point.first;  // a plain name: clang 14 cannot capture a binding
    const bool distinct = std::all_of(starts.begin(), starts.end(), [&](const auto& s) {
      double d2 = 0.0;
      for (unsigned k = 0; k < n; ++k) d2 += (s[k] - u[k]) * (s[k] - u[k]);
      return std::sqrt(d2) > kDistinctStarts;
    });
    if (distinct) starts.push_back(u);
  }
  for (auto s : starts) {
    nlopt::opt local(nlopt::LN_SBPLX, n);
    local.set_lower_bounds(std::vector<double>(n, 0.0));
    local.set_upper_bounds(std::vector<double>(n, 1.0));
    local.set_min_objective(callback, &eval);
    local.set_maxeval(o.localEvaluations);
    local.set_initial_step(kLocalStep);
    local.set_xtol_abs(1e-4);
    try {
      local.optimize(s, f);
    } catch (const nlopt::roundoff_limited&) {
    }
  }
  const auto best =
      std::min_element(eval.seen.begin(), eval.seen.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  return best->first;
}

// All trials' residuals at u, concatenated in trial order.
Eigen::VectorXd residualsAt(const std::vector<Trial>& trials, const Point& p) {
  std::vector<Eigen::VectorXd> r(trials.size());
  tbb::parallel_for(std::size_t{0}, trials.size(), [&](std::size_t i) {
    r[i] = evaluateTrial(p.model, trials[i], p.settings).residuals;
  });
  Eigen::Index n = 0;
  for (const auto& v : r) n += v.size();
  Eigen::VectorXd all(n);
  Eigen::Index at = 0;
  for (const auto& v : r) {
    all.segment(at, v.size()) = v;
    at += v.size();
  }
  return all;
}

// Gauss–Newton standard errors in the parameters' own units (chain rule through the box map).
void standardErrors(const std::vector<Trial>& trials, const std::vector<Dimension>& dims,
                    const std::vector<double>& u, const dynamics::Model& start,
                    const TrajectorySettings& settings, std::vector<TrajectoryParameter>& out) {
  const auto n = static_cast<Eigen::Index>(dims.size());
  const Eigen::VectorXd r0 = residualsAt(trials, place(dims, u, start, settings));
  Eigen::MatrixXd J(r0.size(), n);
  Eigen::VectorXd dpdu(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    std::vector<double> up = u, um = u;
    up[static_cast<std::size_t>(k)] = std::min(1.0, u[static_cast<std::size_t>(k)] + kJacobianStep);
    um[static_cast<std::size_t>(k)] = std::max(0.0, u[static_cast<std::size_t>(k)] - kJacobianStep);
    const double du = up[static_cast<std::size_t>(k)] - um[static_cast<std::size_t>(k)];
    try {
      J.col(k) = (residualsAt(trials, place(dims, up, start, settings)) -
                  residualsAt(trials, place(dims, um, start, settings))) /
                 du;
    } catch (const InputError&) {
      J.col(k).setZero();
    }
    const auto& d = dims[static_cast<std::size_t>(k)];
    dpdu[k] = (fromUnit(d, up[static_cast<std::size_t>(k)]) -
               fromUnit(d, um[static_cast<std::size_t>(k)])) /
              du;
  }
  const double dof = std::max<double>(1.0, static_cast<double>(r0.size() - n));
  const double sigma2 = r0.squaredNorm() / dof;
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  for (Eigen::Index k = 0; k < n; ++k) {
    out[static_cast<std::size_t>(k)].stdError =
        lu.isInvertible() ? std::sqrt(sigma2 * lu.inverse()(k, k)) * std::abs(dpdu[k])
                          : std::numeric_limits<double>::quiet_NaN();
  }
}

std::string worstPhase(const TrajectoryErrors& e) {
  std::string name;
  double worst = -1.0;
  for (const auto& p : e.phases) {
    const double share = p.e_q * static_cast<double>(p.samples);
    if (share > worst) {
      worst = share;
      name = trajectoryPhaseName(p.phase);
    }
  }
  return name;
}

double cpuNow() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

double meanTrialLoss(const std::vector<Trial>& trials, const std::vector<std::size_t>& subset,
                     const dynamics::Model& model, TrajectorySettings settings) {
  const std::vector<std::size_t> which = subset.empty() ? allTrials(trials.size()) : subset;
  std::vector<double> loss(which.size());
  tbb::parallel_for(std::size_t{0}, which.size(), [&](std::size_t k) {
    loss[k] = evaluateTrial(model, trials[which[k]], settings).loss;
  });
  double sum = 0.0;
  for (double l : loss) sum += l;  // in trial order: the same sum on any thread count
  return which.empty() ? 0.0 : sum / static_cast<double>(which.size());
}

bool crossValidates(const TrajectoryFitOptions& options, std::size_t trials) {
  return options.folds >= 2 && static_cast<std::size_t>(options.folds) <= trials;
}

TrajectoryFoldFit fitTrajectoryFold(const std::vector<Trial>& trials, const dynamics::Model& start,
                                    const TrajectoryFitOptions& options, int fold) {
  const int k = options.folds;
  if (fold < -1 || (fold >= 0 && (!crossValidates(options, trials.size()) || fold >= k)))
    throw InputError("--fold", "expected \"all\" or a fold in [0, " + std::to_string(k) +
                                   ") of a " + std::to_string(k) + "-fold cross-validation of " +
                                   std::to_string(trials.size()) + " trials, got " +
                                   std::to_string(fold));
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpuNow();
  TrajectoryFoldFit part;
  part.fold = fold;
  part.folds = k;
  const std::vector<Dimension> dims =
      searchSpace(start, options.fitPlateOffset, options.settings.plateOffset);
  std::vector<double> u0(dims.size());
  for (std::size_t d = 0; d < dims.size(); ++d) u0[d] = toUnit(dims[d], dims[d].start);
  std::vector<std::size_t> train;
  for (std::size_t i = 0; i < trials.size(); ++i)
    (fold >= 0 && static_cast<int>(i % static_cast<std::size_t>(k)) == fold ? part.heldOut : train)
        .push_back(i);
  const std::string stage =
      fold < 0 ? "fit"
               : "cross-validation fold " + std::to_string(fold + 1) + "/" + std::to_string(k);
  Evaluator eval{trials, train, dims, start, options, part, stage, 0, 0, {}};
  part.u = optimise(eval, u0);
  for (std::size_t d = 0; d < dims.size(); ++d)
    part.parameters.push_back({dims[d].name, dims[d].unit, dims[d].start,
                               fromUnit(dims[d], part.u[d]), dims[d].lower, dims[d].upper, 0.0,
                               dims[d].log});
  if (fold < 0) standardErrors(trials, dims, part.u, start, options.settings, part.parameters);
  if (fold >= 0) {
    const Point p = place(dims, part.u, start, options.settings);
    part.heldOutLoss.resize(part.heldOut.size());
    tbb::parallel_for(std::size_t{0}, part.heldOut.size(), [&](std::size_t j) {
      part.heldOutLoss[j] = evaluateTrial(p.model, trials[part.heldOut[j]], p.settings).loss;
    });
  }
  part.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  part.cpuSeconds = cpuNow() - cpu0;
  return part;
}

namespace {

void checkParts(const std::vector<Trial>& trials, const TrajectoryFitOptions& options,
                const std::vector<Dimension>& dims, const TrajectoryFoldFit& all,
                const std::vector<TrajectoryFoldFit>& folds) {
  auto refuse = [](const std::string& what) { throw InputError("--merge", what); };
  if (all.fold != -1) refuse("the first part must be the fit on all trials (fold \"all\")");
  const bool cv = crossValidates(options, trials.size());
  if (folds.size() != (cv ? static_cast<std::size_t>(options.folds) : 0u))
    refuse("expected " + std::to_string(cv ? options.folds : 0) +
           " fold parts besides the fit "
           "on all trials, got " +
           std::to_string(folds.size()));
  auto checkOne = [&](const TrajectoryFoldFit& p, int fold) {
    bool named = p.parameters.size() == dims.size();
    for (std::size_t d = 0; named && d < dims.size(); ++d)
      named = p.parameters[d].name == dims[d].name;
    if (p.fold != fold || p.folds != options.folds || p.u.size() != dims.size() || !named)
      refuse("part " + std::to_string(p.fold) + " of " + std::to_string(p.folds) +
             " folds does not fit here (expected fold " + std::to_string(fold) + " of " +
             std::to_string(options.folds) + " over " + std::to_string(dims.size()) +
             " parameters)");
  };
  checkOne(all, -1);
  for (std::size_t f = 0; f < folds.size(); ++f) {
    checkOne(folds[f], static_cast<int>(f));
    std::vector<std::size_t> members;  // trial i is in fold i mod k
    for (std::size_t i = f; i < trials.size(); i += folds.size()) members.push_back(i);
    if (folds[f].heldOut != members || folds[f].heldOutLoss.size() != members.size())
      refuse("part " + std::to_string(f) + " does not score fold " + std::to_string(f) +
             "'s trials (" + std::to_string(members.size()) + " of the " +
             std::to_string(trials.size()) + ")");
  }
}

// The delete-a-group jackknife's standard error of parameter k from the fold fits (each
// without one fold's trials): sqrt((n − 1)/n Σ_f (θ_f − θ̄)²) over the n folds.
double jackknifeError(const std::vector<TrajectoryFoldFit>& folds, std::size_t k) {
  const auto n = static_cast<double>(folds.size());
  double mean = 0.0;
  for (const auto& f : folds) mean += f.parameters[k].value / n;
  double ss = 0.0;
  for (const auto& f : folds) ss += (f.parameters[k].value - mean) * (f.parameters[k].value - mean);
  return std::sqrt((n - 1.0) / n * ss);
}

}  // namespace

TrajectoryFitResult assembleTrajectoryFit(const std::vector<Trial>& trials,
                                          const dynamics::Model& start,
                                          const TrajectoryFitOptions& options,
                                          const TrajectoryFoldFit& all,
                                          const std::vector<TrajectoryFoldFit>& folds) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpuNow();
  const std::vector<Dimension> dims =
      searchSpace(start, options.fitPlateOffset, options.settings.plateOffset);
  checkParts(trials, options, dims, all, folds);
  TrajectoryFitResult result;
  const std::vector<double>& best = all.u;
  const Point fitted = place(dims, best, start, options.settings);
  result.model = fitted.model;
  result.plateOffset = fitted.settings.plateOffset;
  for (std::size_t k = 0; k < dims.size(); ++k) {
    const auto& d = dims[k];
    const double u = best[k];
    TrajectoryParameter p{
        d.name, d.unit, d.start, fromUnit(d, u), d.lower, d.upper, all.parameters[k].stdError,
        d.log};
    p.gaussNewtonError = all.parameters[k].stdError;
    if (!folds.empty()) {
      p.jackknifeError = jackknifeError(folds, k);
      // the larger: fold fits that all stop on one point of the loss's jumps scatter by
      // nothing, and Gauss-Newton's error is then the only one left
      p.stdError = std::isnan(p.gaussNewtonError) ? p.jackknifeError
                                                  : std::max(p.jackknifeError, p.gaussNewtonError);
    }
    result.parameters.push_back(p);
    if (u < 1e-3 || u > 1 - 1e-3)
      result.warnings.push_back(d.name + " ended at the edge of its search box [" +
                                std::to_string(d.lower) + ", " + std::to_string(d.upper) + "]");
  }

  if (folds.empty() && !dims.empty())
    result.warnings.push_back(
        "the standard errors are Gauss-Newton's, which take every sample as independent and "
        "understate a trajectory fit's error; cross-validate (--folds k) for the jackknife's");
  result.trials.resize(trials.size());
  TrajectorySettings startSettings = options.settings;
  tbb::parallel_for(std::size_t{0}, trials.size(), [&](std::size_t i) {
    TrialScore& s = result.trials[i];
    s.name = trials[i].data.name;
    s.e_q_start = evaluateTrial(start, trials[i], startSettings).loss;
    const TrialEvaluation e = evaluateTrial(fitted.model, trials[i], fitted.settings);
    s.e_q_fitted = e.loss;
    s.errors = e.errors;
    s.worstPhase = worstPhase(e.errors);
    s.e_q_heldOut = std::numeric_limits<double>::quiet_NaN();
  });
  for (const auto& s : result.trials) {
    result.meanStart += s.e_q_start / static_cast<double>(trials.size());
    result.meanFitted += s.e_q_fitted / static_cast<double>(trials.size());
  }
  result.evaluations = all.evaluations;
  result.trialSimulations = all.trialSimulations;
  result.seconds = all.seconds;
  result.cpuSeconds = all.cpuSeconds;
  if (!folds.empty()) {
    double heldOut = 0.0;
    for (const auto& f : folds) {  // in fold order, then trial order: the single-process sum
      for (std::size_t j = 0; j < f.heldOut.size(); ++j) {
        result.trials[f.heldOut[j]].e_q_heldOut = f.heldOutLoss[j];
        result.trials[f.heldOut[j]].fold = f.fold;
        heldOut += f.heldOutLoss[j];
      }
      result.evaluations += f.evaluations;
      result.trialSimulations += f.trialSimulations;
      result.seconds += f.seconds;
      result.cpuSeconds += f.cpuSeconds;
    }
    result.meanHeldOut = heldOut / static_cast<double>(trials.size());
  }
  result.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  result.cpuSeconds += cpuNow() - cpu0;
  return result;
}

TrajectoryFitResult fitTrajectories(const std::vector<Trial>& trials, const dynamics::Model& start,
                                    const TrajectoryFitOptions& options) {
  const TrajectoryFoldFit all = fitTrajectoryFold(trials, start, options, -1);
  std::vector<TrajectoryFoldFit> folds;
  if (crossValidates(options, trials.size()))
    for (int fold = 0; fold < options.folds; ++fold)
      folds.push_back(fitTrajectoryFold(trials, start, options, fold));
  return assembleTrajectoryFit(trials, start, options, all, folds);
}

}  // namespace vcontact::validation
