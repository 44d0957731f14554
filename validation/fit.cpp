#include "validation/fit.hpp"

#include <ceres/ceres.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "geometry/error.hpp"

namespace vcontact::validation {
namespace {

using dynamics::Model;
using dynamics::ParameterSpec;

// Huber and Cauchy scales giving 95 % efficiency under normal noise (Holland & Welsch 1977).
constexpr double kHuberScale = 1.345;
constexpr double kCauchyScale = 2.385;
// Signed parameters: u = p / s with s = this fraction of the half range.
constexpr double kSignedScaleFraction = 0.01;
// A direction of the column-normalised Jacobian whose singular value is this far below the
// largest one changes the residuals by < 1e-4 of the best-determined direction: the data
// cannot pin it down.
constexpr double kIdentifiableRatio = 1e-4;
// Weight above which a parameter counts as part of such a null direction.
constexpr double kNullComponent = 0.3;
// Central-difference step, relative to u (u is O(1) by the scaling). The replay is smooth only
// down to ~1e-6 relative changes of a parameter (sampled state updates, clamps), where the
// default 1e-6 step picks up that ripple and inflates the Jacobian; 1e-3 keeps the O(h²)
// truncation at ~1e-6 while averaging over the ripple.
constexpr double kRelativeStep = 1e-3;
// |correlation| above which two parameters are reported as nearly interchangeable.
constexpr double kHighCorrelation = 0.99;
// A parameter is "at the bound" when its distance to the bound, in its own units, is within
// this fraction of the larger of |value| and |bound| (for Δ = p − q of a relation: of |p| and
// |q|). Ceres' bounded LM leaves an active bound exactly (to round-off of the asinh map,
// ~1e-15 relative); a fit that merely ends small (kv = 1e6 N/m³ of a soft material against a
// bound at 0) is 1 relative away, however small it is in the asinh-scaled u.
constexpr double kAtBoundRelative = 1e-6;
// Design range of a positive parameter: its scale s times 10^±3 (see the header).
constexpr double kDesignDecades = 1e-3;
// Levenberg–Marquardt iterations each of several polished starts gets before only the best
// is solved to convergence (issue 37 item 6: the starts race, the winner finishes). From a
// start inside a basin LM lowers the cost by orders of magnitude within a few iterations; 10
// leaves the basins ranked as the full runs rank them on every bundled record (the verdicts
// of scripts/bundled_outputs.sh are unchanged) at a third of the LM cost of three full runs.
constexpr int kRaceIterations = 10;
// Another polished start replaces the best only when its cost is lower by this fraction:
// LM runs that end in the same minimum differ in the last digits, and the earlier start wins.
constexpr double kBetterCost = 1e-9;

// u ↔ p for one parameter (see the header).
struct Scaling {
  bool logarithmic = false;
  double s = 1.0;
  double toU(double p) const { return logarithmic ? std::asinh(p / s) : p / s; }
  double toP(double u) const { return logarithmic ? s * std::sinh(u) : s * u; }
  double dPdU(double u) const { return logarithmic ? s * std::cosh(u) : s; }
};

Scaling scalingOf(const ParameterSpec& spec) {
  if (spec.lower < 0.0) return {false, kSignedScaleFraction * 0.5 * (spec.upper - spec.lower)};
  return {true, spec.default_value > 0.0 ? spec.default_value : 1.0};
}

struct FreeParameter {
  std::size_t index;  // into Model::parameters()
  ParameterSpec spec;
  Scaling scaling;
  /// Index of q for a relation p ≥ q (u then maps Δ = p − q); −1: u maps p itself.
  long reference = -1;
  double lowerU() const { return scaling.toU(reference >= 0 ? 0.0 : spec.lower); }
  double upperU(const std::vector<ParameterSpec>& specs) const {
    if (reference < 0) return scaling.toU(spec.upper);
    return scaling.toU(spec.upper - specs[static_cast<std::size_t>(reference)].lower);
  }
};

// The relation p ≥ q declared for parameter `name`, as the index of q; −1 when none.
long referenceOf(const Model& m, const std::string& name) {
  const auto names = m.parameterNames();
  for (std::size_t e = 0; e < m.effectCount(); ++e) {
    for (const auto& r : m.effect(e).relations()) {
      if (r.parameter != name) continue;
      const auto it = std::find(names.begin(), names.end(), r.atLeast);
      if (it != names.end()) return static_cast<long>(it - names.begin());
    }
  }
  return -1;
}

std::vector<FreeParameter> freeParameters(const Model& m) {
  std::vector<FreeParameter> free;
  const auto specs = m.parameterSpecs();
  const auto& fixed = m.fixed();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (std::find(fixed.begin(), fixed.end(), specs[i].name) != fixed.end()) continue;
    FreeParameter f{i, specs[i], scalingOf(specs[i]), referenceOf(m, specs[i].name)};
    if (f.reference >= 0)
      f.scaling = {true, specs[i].default_value > 0.0 ? specs[i].default_value : 1.0};
    free.push_back(f);
  }
  return free;
}

// Model parameter values for u: plain parameters first, then those tied by a relation
// (p = q + Δ, so q must be set before).
void applyU(const std::vector<FreeParameter>& free, const std::vector<double>& u,
            std::vector<double>& values) {
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t j = 0; j < free.size(); ++j) {
      const auto& f = free[j];
      if ((f.reference >= 0) != (pass == 1)) continue;
      const double base = pass == 1 ? values[static_cast<std::size_t>(f.reference)] : 0.0;
      values[f.index] = std::clamp(base + f.scaling.toP(u[j]), f.spec.lower, f.spec.upper);
    }
  }
}

// u of the model values (a relation the values break starts at Δ = 0).
std::vector<double> uOf(const std::vector<FreeParameter>& free, const std::vector<double>& values) {
  std::vector<double> u;
  for (const auto& f : free) {
    const double p = values[f.index];
    u.push_back(f.reference < 0 ? f.scaling.toU(p)
                                : f.scaling.toU(std::max(
                                      0.0, p - values[static_cast<std::size_t>(f.reference)])));
  }
  return u;
}

// Normalised (and robustified) residuals of the whole record as a function of u.
class RecordResiduals {
 public:
  RecordResiduals(Replayer& replayer, const NoiseLevels& noise, Model model,
                  std::vector<FreeParameter> free, Loss loss, std::vector<bool> heldOut)
      : replayer_(replayer),
        noise_(noise),
        model_(std::move(model)),
        free_(std::move(free)),
        heldOut_(std::move(heldOut)) {
    values_ = model_.parameters();
    u_.resize(free_.size());
    if (loss == Loss::kHuber) loss_ = std::make_unique<ceres::HuberLoss>(kHuberScale);
    if (loss == Loss::kCauchy) loss_ = std::make_unique<ceres::CauchyLoss>(kCauchyScale);
  }

  int residualCount() const {
    return static_cast<int>(replayer_.dataset().size() * replayer_.dataset().outputs.size());
  }

  bool operator()(double const* const* u, double* residuals) const {
    for (std::size_t j = 0; j < free_.size(); ++j) u_[j] = u[j][0];
    applyU(free_, u_, values_);
    model_.setParameters(values_);
    const Prediction p = replayer_.run(model_, false);  // the residuals need no regime
    if (p.nonFinite) return false;  // Ceres rejects the step (the start is checked in fit)
    const auto& d = replayer_.dataset();
    int k = 0;
    for (const auto& o : d.outputs) {
      const Eigen::VectorXd e = (d.measured(o) - p.column(o)) / noise_.at(o).sigma;
      for (Eigen::Index i = 0; i < e.size(); ++i) {
        const bool out = !heldOut_.empty() && heldOut_[static_cast<std::size_t>(i)];
        residuals[k++] = out ? 0.0 : robust(e[i]);
      }
    }
    return true;
  }

  /// Σ residual² at u (the multistart's screening).
  double cost(const std::vector<double>& u) const {
    std::vector<const double*> ptr;
    for (const auto& x : u) ptr.push_back(&x);
    std::vector<double> r(static_cast<std::size_t>(residualCount()));
    if (!(*this)(ptr.data(), r.data())) return std::numeric_limits<double>::infinity();
    double c = 0.0;
    for (double x : r) c += x * x;
    return std::isfinite(c) ? c : std::numeric_limits<double>::infinity();
  }

 private:
  // sign(e) sqrt(ρ(e²)): the same objective as Ceres' residual-wise loss.
  double robust(double e) const {
    if (!loss_) return e;
    double rho[3];
    loss_->Evaluate(e * e, rho);
    return std::copysign(std::sqrt(rho[0]), e);
  }

  Replayer& replayer_;
  const NoiseLevels& noise_;
  mutable Model model_;
  std::vector<FreeParameter> free_;
  std::vector<bool> heldOut_;
  mutable std::vector<double> values_;
  mutable std::vector<double> u_;
  std::unique_ptr<ceres::LossFunction> loss_;
};

// The Jacobian at the solution; nothing when the residuals could not be evaluated (a
// non-finite prediction within the difference step of the solution).
std::optional<Eigen::MatrixXd> denseJacobian(ceres::Problem& problem,
                                             const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions opts;
  opts.parameter_blocks = blocks;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  if (!problem.Evaluate(opts, &cost, nullptr, nullptr, &crs)) return std::nullopt;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) J(r, crs.cols[k]) = crs.values[k];
  }
  return J;
}

// Parameters in a near-null direction of the column-normalised Jacobian.
std::vector<bool> unidentifiable(const Eigen::MatrixXd& J) {
  const Eigen::Index k = J.cols();
  std::vector<bool> out(static_cast<std::size_t>(k), false);
  Eigen::VectorXd norms = J.colwise().norm();
  Eigen::MatrixXd Jn = J;
  for (Eigen::Index j = 0; j < k; ++j) {
    if (norms[j] == 0.0)
      out[static_cast<std::size_t>(j)] = true;
    else
      Jn.col(j) /= norms[j];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Jn.transpose() * Jn);
  const double top = std::max(eig.eigenvalues().maxCoeff(), std::numeric_limits<double>::min());
  for (Eigen::Index i = 0; i < k; ++i) {
    // singular value ratio = sqrt(eigenvalue ratio)
    if (std::sqrt(std::max(eig.eigenvalues()[i], 0.0) / top) >= kIdentifiableRatio) continue;
    for (Eigen::Index j = 0; j < k; ++j) {
      if (std::abs(eig.eigenvectors()(j, i)) > kNullComponent)
        out[static_cast<std::size_t>(j)] = true;
    }
  }
  return out;
}

std::string str(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

void addWarnings(FitResult& r) {
  for (const auto& p : r.parameters) {
    if (p.fixed) continue;
    std::ostringstream s;
    if (!p.atBound.empty()) {
      s << p.name << " = " << str(p.value) << " is at its " << p.atBound
        << " bound: the data push it out of the physical range (the effect stands in for "
        << "something else)";
      r.warnings.push_back(s.str());
      s.str("");
    }
    if (!p.identifiable) {
      s << p.name << ": the data cannot identify it (no independent effect on the outputs); "
        << "fix it or add data that exercises it";
    } else if (p.stdError > std::abs(p.value)) {
      s << p.name << ": poorly determined, std error " << str(p.stdError) << " exceeds |value| "
        << str(std::abs(p.value));
    } else {
      continue;
    }
    r.warnings.push_back(s.str());
  }
  const auto k = static_cast<std::size_t>(r.correlation.rows());
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i + 1; j < k; ++j) {
      const double c = r.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      if (!(std::abs(c) > kHighCorrelation)) continue;
      std::ostringstream s;
      s << r.freeNames[i] << " and " << r.freeNames[j] << " are correlated at " << str(c)
        << ": the data determine mainly a combination of them";
      r.warnings.push_back(s.str());
    }
  }
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Standard errors and correlations in p from the covariance C of the kept u (keptIndex),
// scaled: Cov p = D Cov u Dᵀ, D = dp/du: diagonal, plus dp/du_q for p = q + Δ.
void takeCovariance(const std::vector<FreeParameter>& free, const std::vector<double>& u,
                    const std::vector<std::size_t>& keptIndex, const RowMajor& C, double scale,
                    FitResult& r) {
  const std::size_t k = free.size();
  const auto m = static_cast<Eigen::Index>(keptIndex.size());
  const auto kk = static_cast<Eigen::Index>(k);
  Eigen::MatrixXd Cu = Eigen::MatrixXd::Zero(kk, kk), D = Eigen::MatrixXd::Zero(kk, kk);
  for (Eigen::Index a = 0; a < m; ++a) {
    for (Eigen::Index b = 0; b < m; ++b) {
      Cu(static_cast<Eigen::Index>(keptIndex[static_cast<std::size_t>(a)]),
         static_cast<Eigen::Index>(keptIndex[static_cast<std::size_t>(b)])) = C(a, b);
    }
  }
  for (std::size_t j = 0; j < k; ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    D(jj, jj) = free[j].scaling.dPdU(u[j]);
    for (std::size_t q = 0; q < k && free[j].reference >= 0; ++q) {
      if (free[q].index == static_cast<std::size_t>(free[j].reference))
        D(jj, static_cast<Eigen::Index>(q)) = free[q].scaling.dPdU(u[q]);
    }
  }
  const Eigen::MatrixXd Cp = D * Cu * D.transpose() * scale;
  for (const std::size_t ja : keptIndex) {
    const auto a = static_cast<Eigen::Index>(ja);
    r.parameters[free[ja].index].stdError = std::sqrt(std::max(Cp(a, a), 0.0));
    for (const std::size_t jb : keptIndex) {
      const auto b = static_cast<Eigen::Index>(jb);
      r.correlation(a, b) = Cp(a, b) / std::sqrt(Cp(a, a) * Cp(b, b));
    }
  }
}

// Covariance of the identifiable free parameters in p, scaled (see the header).
void estimateUncertainty(ceres::Problem& problem, const std::vector<FreeParameter>& free,
                         std::vector<double>& u, FitResult& r) {
  const std::size_t k = free.size();
  std::vector<double*> blocks;
  for (auto& x : u) blocks.push_back(&x);
  const std::optional<Eigen::MatrixXd> J = denseJacobian(problem, blocks);
  if (!J) {
    r.warnings.push_back(
        "no uncertainty: the model's prediction is not finite next to the solution (within the "
        "difference step of the Jacobian)");
  }
  const std::vector<bool> lost = J ? unidentifiable(*J) : std::vector<bool>(k, true);
  std::vector<const double*> kept;
  std::vector<std::size_t> keptIndex;
  for (std::size_t j = 0; j < k; ++j) {
    if (lost[j]) {
      problem.SetParameterBlockConstant(blocks[j]);
    } else {
      kept.push_back(blocks[j]);
      keptIndex.push_back(j);
    }
  }
  r.correlation = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(k),
                                            static_cast<Eigen::Index>(k), std::nan(""));
  for (std::size_t j = 0; j < k; ++j) {
    r.parameters[free[j].index].identifiable = !lost[j];
    r.parameters[free[j].index].stdError = std::numeric_limits<double>::infinity();
  }
  if (kept.empty()) return;
  ceres::Covariance::Options opts;
  opts.algorithm_type = ceres::DENSE_SVD;
  opts.null_space_rank = -1;  // the near-null directions were removed above
  ceres::Covariance covariance(opts);
  if (!covariance.Compute(kept, &problem)) return;
  const auto m = static_cast<Eigen::Index>(kept.size());
  RowMajor C(m, m);
  covariance.GetCovarianceMatrix(kept, C.data());
  const double dof = static_cast<double>(r.comparison.count) - static_cast<double>(k);
  const double scale = std::max(1.0, r.comparison.chi2 / std::max(dof, 1.0));
  takeCovariance(free, u, keptIndex, C, scale, r);
}

// The result before solving: `start`'s parameters, the free ones marked.
FitResult startingResult(const Model& start, const std::vector<FreeParameter>& free) {
  FitResult r;
  r.model = start;
  const auto specs = start.parameterSpecs();
  const auto initial = start.parameters();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    r.parameters.push_back(
        {specs[i].name, specs[i].unit, initial[i], initial[i], std::nan(""), true, true, ""});
  }
  for (const auto& f : free) {
    r.parameters[f.index].fixed = false;
    r.freeNames.push_back(f.spec.name);
  }
  r.freeCount = free.size();
  return r;
}

// The least-squares problem in u: one residual block over the whole record (central
// differences), each u bounded by its parameter's bounds.
void buildProblem(Replayer& replayer, const NoiseLevels& noise, const Model& start,
                  const std::vector<FreeParameter>& free, const FitOptions& options,
                  std::vector<double>& u, ceres::Problem& problem) {
  auto* functor = new RecordResiduals(replayer, noise, start, free, options.loss, options.heldOut);
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = kRelativeStep;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<RecordResiduals, ceres::CENTRAL>(
      functor, ceres::TAKE_OWNERSHIP, diff);
  for (std::size_t j = 0; j < free.size(); ++j) cost->AddParameterBlock(1);
  cost->SetNumResiduals(functor->residualCount());
  std::vector<double*> blocks;
  for (auto& x : u) blocks.push_back(&x);
  problem.AddResidualBlock(cost, nullptr, blocks);
  const auto specs = start.parameterSpecs();
  for (std::size_t j = 0; j < free.size(); ++j) {
    problem.SetParameterLowerBound(blocks[j], 0, free[j].lowerU());
    problem.SetParameterUpperBound(blocks[j], 0, free[j].upperU(specs));
  }
}

ceres::Solver::Options solverOptions(const FitOptions& options) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = options.maxIterations;
  // No projected line search: with bounds set Ceres follows every step that leaves the box with
  // a line search whose every trial evaluates the Jacobian (2 replays a free parameter). On a
  // parameter held at a bound (stribeck.mu_s at coulomb.mu) that cost 9 Jacobians an iteration
  // and 3 s of the 4.6 s of dwell's candidate fit on a 6,400-sample record (issue 37 item 6);
  // the trust region alone shrinks the projected step instead (Solver::Options: 0 turns the
  // search off for the trust-region minimizer).
  so.max_num_line_search_step_size_iterations = 0;
  so.num_threads = 1;  // starts and candidates run in parallel one level up (TBB)
  so.logging_type = ceres::SILENT;
  return so;
}

// |x − bound| within kAtBoundRelative of max(|x|, |bound|) (see the constant).
bool near(double x, double bound) {
  return std::abs(x - bound) <= kAtBoundRelative * std::max(std::abs(x), std::abs(bound));
}

// The bound the parameter's value sits at, in its own units: "lower", "upper", ">= q" for a
// relation p ≥ q at Δ = 0, or empty.
std::string boundReached(const FreeParameter& f, const std::vector<double>& values,
                         const std::vector<ParameterSpec>& specs) {
  const double p = values[f.index];
  if (f.reference >= 0) {
    const auto q = static_cast<std::size_t>(f.reference);
    if (near(p, values[q])) return ">= " + specs[q].name;
  } else if (near(p, f.spec.lower)) {
    return "lower";
  }
  if (near(p, f.spec.upper)) return "upper";
  return {};
}

// r's model and free parameter values at the solution u, clamped to their bounds, and the
// parameters that sit at a bound (see the header).
void takeSolution(const std::vector<FreeParameter>& free, const std::vector<double>& u,
                  FitResult& r) {
  std::vector<double> values = r.model.parameters();
  applyU(free, u, values);
  const auto specs = r.model.parameterSpecs();
  for (std::size_t j = 0; j < free.size(); ++j) {
    auto& est = r.parameters[free[j].index];
    est.value = values[free[j].index];
    est.atBound = boundReached(free[j], values, specs);
  }
  r.model.setParameters(values);
}

// @throws InputError naming the effect, its parameters and the first sample where `model`'s
// prediction is not finite: such a model cannot be compared with the record.
void requireFinite(const Model& model, const Prediction& p, const Dataset& d) {
  if (!p.nonFinite) return;
  const NonFinitePrediction& bad = *p.nonFinite;
  const auto row = static_cast<Eigen::Index>(bad.sample);
  std::ostringstream s;
  s.precision(6);
  s << "effect '" << bad.effect << "' predicts a non-finite wrench (";
  for (Eigen::Index c = 0; c < p.wrench.cols(); ++c) {
    if (std::isfinite(p.wrench(row, c))) continue;
    s << kWrenchColumns[static_cast<std::size_t>(c)] << " = " << p.wrench(row, c);
    break;
  }
  s << ") at sample " << bad.sample << " (t = " << d.samples[bad.sample].t << " s)";
  const auto names = model.parameterNames();
  const auto values = model.parameters();
  std::string sep = " with ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].rfind(bad.effect + ".", 0) != 0) continue;
    s << sep << names[i] << " = " << values[i];
    sep = ", ";
  }
  s << "; every sample needs a finite force and torque (check the effect's formula and "
       "parameters)";
  throw InputError("model", s.str());
}

// r's prediction by its model and that prediction compared with the record.
// @throws InputError when the prediction is not finite
void predict(Replayer& replayer, const NoiseLevels& noise, FitResult& r) {
  r.prediction = replayer.run(r.model);
  requireFinite(r.model, r.prediction, replayer.dataset());
  r.comparison = compare(replayer.dataset(), r.prediction, noise);
}

// Point i ≥ 1 of the Halton sequence in the prime base `base`: in [0, 1).
double halton(int i, int base) {
  double f = 1.0, x = 0.0;
  for (; i > 0; i /= base) {
    f /= base;
    x += f * (i % base);
  }
  return x;
}

// Design range in u of one free parameter (see the header).
std::pair<double, double> designRange(const FreeParameter& f,
                                      const std::vector<ParameterSpec>& specs) {
  double lo = f.lowerU(), hi = f.upperU(specs);
  if (f.scaling.logarithmic) {
    lo = std::max(lo, f.scaling.toU(f.scaling.s * kDesignDecades));
    hi = std::min(hi, f.scaling.toU(f.scaling.s / kDesignDecades));
    if (f.reference >= 0 || f.spec.lower <= 0.0) lo = f.lowerU();  // from 0 (Δ = 0, p = 0)
  }
  return {lo, std::max(lo, hi)};
}

// The start and the Halton points (see the header), in u.
std::vector<std::vector<double>> designStarts(const Model& start,
                                              const std::vector<FreeParameter>& free,
                                              const FitOptions& options) {
  static constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
  const std::vector<double> u0 = uOf(free, start.parameters());
  std::vector<std::vector<double>> starts{u0};
  const auto specs = start.parameterSpecs();
  std::vector<std::size_t> explored;
  for (std::size_t j = 0; j < free.size(); ++j) {
    const auto& e = options.explore;
    if (e.empty() || std::find(e.begin(), e.end(), free[j].spec.name) != e.end())
      explored.push_back(j);
  }
  if (explored.empty() || explored.size() > std::size(kPrimes)) return starts;
  for (int i = 1; i <= options.designPoints; ++i) {
    std::vector<double> u = u0;
    for (std::size_t d = 0; d < explored.size(); ++d) {
      const auto [lo, hi] = designRange(free[explored[d]], specs);
      u[explored[d]] = lo + (hi - lo) * halton(i, kPrimes[d]);
    }
    starts.push_back(std::move(u));
  }
  return starts;
}

struct Polished {
  std::vector<double> u;
  double cost = std::numeric_limits<double>::infinity();
  ceres::Solver::Summary summary;
};

// LM from u (its own copy of the replayer, sharing its geometry: runs in parallel).
Polished polish(const Replayer& parent, const NoiseLevels& noise, const Model& start,
                const std::vector<FreeParameter>& free, const FitOptions& options,
                std::vector<double> u) {
  Replayer replayer = parent;
  Polished p;
  ceres::Problem problem;
  buildProblem(replayer, noise, start, free, options, u, problem);
  ceres::Solve(solverOptions(options), &problem, &p.summary);
  p.cost = std::isfinite(p.summary.final_cost) ? p.summary.final_cost : p.cost;
  p.u = std::move(u);
  return p;
}

// Screens every start by its cost, polishes the cheapest, returns the best (see the header).
std::pair<Polished, int> multistart(Replayer& replayer, const NoiseLevels& noise,
                                    const Model& start, const std::vector<FreeParameter>& free,
                                    const FitOptions& options) {
  const auto starts = designStarts(start, free, options);
  const RecordResiduals screen(replayer, noise, start, free, options.loss, options.heldOut);
  const auto tell = [&](const char* what, int done, int total) {
    if (options.progress) options.progress(what, done, total);
  };
  std::vector<std::pair<double, int>> ranked;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    tell("fit: screening starts", static_cast<int>(i), static_cast<int>(starts.size()));
    ranked.emplace_back(i == 0 ? -1.0 : screen.cost(starts[i]), static_cast<int>(i));
  }
  // the given start is always polished (cost −1 ranks it first)
  std::stable_sort(ranked.begin(), ranked.end());
  ranked.resize(std::min(ranked.size(), static_cast<std::size_t>(std::max(1, options.polished))));
  std::vector<Polished> runs(ranked.size());
  std::atomic<int> done{0};
  const int total = static_cast<int>(runs.size());
  tell("fit: Levenberg-Marquardt starts", 0, total);
  // several starts: each gets kRaceIterations, then only the best is solved to the end
  FitOptions race = options;
  if (runs.size() > 1) race.maxIterations = std::min(options.maxIterations, kRaceIterations);
  tbb::parallel_for(std::size_t{0}, runs.size(), [&](std::size_t i) {
    runs[i] = polish(replayer, noise, start, free, race,
                     starts[static_cast<std::size_t>(ranked[i].second)]);
    tell("fit: Levenberg-Marquardt starts", ++done, total);
  });
  std::size_t best = 0;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    if (runs[i].cost < runs[best].cost * (1.0 - kBetterCost)) best = i;
  }
  if (race.maxIterations < options.maxIterations &&
      runs[best].summary.termination_type == ceres::NO_CONVERGENCE) {
    Polished rest = polish(replayer, noise, start, free, options, runs[best].u);
    if (rest.cost <= runs[best].cost) runs[best] = std::move(rest);
  }
  return {std::move(runs[best]), ranked[best].second};
}

// Solves for the free parameters (multistart) and fills r: solver outcome, fitted model,
// its prediction and the uncertainty of the free parameters.
void solveFree(Replayer& replayer, const NoiseLevels& noise, const Model& start,
               const std::vector<FreeParameter>& free, const FitOptions& options, FitResult& r) {
  auto [best, index] = multistart(replayer, noise, start, free, options);
  r.startsPolished = std::min(options.designPoints + 1, std::max(1, options.polished));
  r.winningStart = index;
  r.iterations = static_cast<int>(best.summary.iterations.size());
  r.converged = best.summary.termination_type == ceres::CONVERGENCE;
  r.solverReport = best.summary.BriefReport();
  std::vector<double> u = best.u;
  takeSolution(free, u, r);
  predict(replayer, noise, r);
  ceres::Problem problem;
  buildProblem(replayer, noise, start, free, options, u, problem);
  estimateUncertainty(problem, free, u, r);
  if (!r.converged)
    r.warnings.push_back("the solver stopped before convergence: " + r.solverReport);
}

}  // namespace

Loss parseLoss(const std::string& name) {
  if (name == "none" || name == "squared") return Loss::kSquared;
  if (name == "huber") return Loss::kHuber;
  if (name == "cauchy") return Loss::kCauchy;
  throw InputError("robust loss", "unknown loss '" + name + "'; expected none, huber or cauchy");
}

std::string lossName(Loss loss) {
  switch (loss) {
    case Loss::kHuber:
      return "huber";
    case Loss::kCauchy:
      return "cauchy";
    case Loss::kSquared:
      break;
  }
  return "none";
}

FitResult fit(Replayer& replayer, const NoiseLevels& noise, const Model& start,
              const FitOptions& options) {
  const std::vector<FreeParameter> free = freeParameters(start);
  FitResult r = startingResult(start, free);
  if (!free.empty()) {
    requireFinite(start, replayer.run(start, false), replayer.dataset());
    solveFree(replayer, noise, start, free, options, r);
  } else {
    predict(replayer, noise, r);
    r.converged = true;
  }
  r.bic = bic(r.comparison, r.freeCount);
  addWarnings(r);
  try {
    r.model.validate();
  } catch (const InputError& e) {
    r.warnings.push_back("the fitted values break a relation of the model: " + e.message());
  }
  return r;
}

}  // namespace vcontact::validation
