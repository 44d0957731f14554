#include "validation/fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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
};

std::vector<FreeParameter> freeParameters(const Model& m) {
  std::vector<FreeParameter> free;
  const auto specs = m.parameterSpecs();
  const auto& fixed = m.fixed();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (std::find(fixed.begin(), fixed.end(), specs[i].name) != fixed.end()) continue;
    free.push_back({i, specs[i], scalingOf(specs[i])});
  }
  return free;
}

// Normalised (and robustified) residuals of the whole record as a function of u.
class RecordResiduals {
 public:
  RecordResiduals(Replayer& replayer, const NoiseLevels& noise, Model model,
                  std::vector<FreeParameter> free, Loss loss)
      : replayer_(replayer), noise_(noise), model_(std::move(model)), free_(std::move(free)) {
    values_ = model_.parameters();
    if (loss == Loss::kHuber) loss_ = std::make_unique<ceres::HuberLoss>(kHuberScale);
    if (loss == Loss::kCauchy) loss_ = std::make_unique<ceres::CauchyLoss>(kCauchyScale);
  }

  int residualCount() const {
    return static_cast<int>(replayer_.dataset().size() * replayer_.dataset().outputs.size());
  }

  bool operator()(double const* const* u, double* residuals) const {
    for (std::size_t j = 0; j < free_.size(); ++j) {
      const auto& f = free_[j];
      values_[f.index] = std::clamp(f.scaling.toP(u[j][0]), f.spec.lower, f.spec.upper);
    }
    model_.setParameters(values_);
    const Prediction p = replayer_.run(model_);
    const auto& d = replayer_.dataset();
    int k = 0;
    for (const auto& o : d.outputs) {
      const Eigen::VectorXd e = (d.measured(o) - p.column(o)) / noise_.at(o).sigma;
      for (Eigen::Index i = 0; i < e.size(); ++i) residuals[k++] = robust(e[i]);
    }
    return true;
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
  mutable std::vector<double> values_;
  std::unique_ptr<ceres::LossFunction> loss_;
};

Eigen::MatrixXd denseJacobian(ceres::Problem& problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions opts;
  opts.parameter_blocks = blocks;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  problem.Evaluate(opts, &cost, nullptr, nullptr, &crs);
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

// Covariance of the identifiable free parameters in p, scaled (see the header).
void estimateUncertainty(ceres::Problem& problem, const std::vector<FreeParameter>& free,
                         std::vector<double>& u, FitResult& r) {
  const std::size_t k = free.size();
  std::vector<double*> blocks;
  for (auto& x : u) blocks.push_back(&x);
  const std::vector<bool> lost = unidentifiable(denseJacobian(problem, blocks));
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
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C(m, m);
  covariance.GetCovarianceMatrix(kept, C.data());
  const double dof = static_cast<double>(r.comparison.count) - static_cast<double>(k);
  const double scale = std::max(1.0, r.comparison.chi2 / std::max(dof, 1.0));
  for (Eigen::Index a = 0; a < m; ++a) {
    const std::size_t ja = keptIndex[static_cast<std::size_t>(a)];
    const double da = free[ja].scaling.dPdU(u[ja]);
    r.parameters[free[ja].index].stdError = da * std::sqrt(std::max(C(a, a), 0.0) * scale);
    for (Eigen::Index b = 0; b < m; ++b) {
      const std::size_t jb = keptIndex[static_cast<std::size_t>(b)];
      r.correlation(static_cast<Eigen::Index>(ja), static_cast<Eigen::Index>(jb)) =
          C(a, b) / std::sqrt(C(a, a) * C(b, b));
    }
  }
}

// The result before solving: `start`'s parameters, the free ones marked.
FitResult startingResult(const Model& start, const std::vector<FreeParameter>& free) {
  FitResult r;
  r.model = start;
  const auto specs = start.parameterSpecs();
  const auto initial = start.parameters();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    r.parameters.push_back(
        {specs[i].name, specs[i].unit, initial[i], initial[i], std::nan(""), true, true});
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
                  const std::vector<FreeParameter>& free, Loss loss, std::vector<double>& u,
                  ceres::Problem& problem) {
  auto* functor = new RecordResiduals(replayer, noise, start, free, loss);
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = kRelativeStep;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<RecordResiduals, ceres::CENTRAL>(
      functor, ceres::TAKE_OWNERSHIP, diff);
  for (std::size_t j = 0; j < free.size(); ++j) cost->AddParameterBlock(1);
  cost->SetNumResiduals(functor->residualCount());
  std::vector<double*> blocks;
  for (auto& x : u) blocks.push_back(&x);
  problem.AddResidualBlock(cost, nullptr, blocks);
  for (std::size_t j = 0; j < free.size(); ++j) {
    problem.SetParameterLowerBound(blocks[j], 0, free[j].scaling.toU(free[j].spec.lower));
    problem.SetParameterUpperBound(blocks[j], 0, free[j].scaling.toU(free[j].spec.upper));
  }
}

ceres::Solver::Options solverOptions(const FitOptions& options) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = options.maxIterations;
  so.num_threads = 1;  // candidates run in parallel one level up (TBB)
  so.logging_type = ceres::SILENT;
  return so;
}

// r's model and free parameter values at the solution u, clamped to their bounds.
void takeSolution(const std::vector<FreeParameter>& free, const std::vector<double>& u,
                  FitResult& r) {
  std::vector<double> values = r.model.parameters();
  for (std::size_t j = 0; j < free.size(); ++j) {
    values[free[j].index] =
        std::clamp(free[j].scaling.toP(u[j]), free[j].spec.lower, free[j].spec.upper);
    r.parameters[free[j].index].value = values[free[j].index];
  }
  r.model.setParameters(values);
}

// r's prediction by its model and that prediction compared with the record.
void predict(Replayer& replayer, const NoiseLevels& noise, FitResult& r) {
  r.prediction = replayer.run(r.model);
  r.comparison = compare(replayer.dataset(), r.prediction, noise);
}

// Solves for the free parameters from `start` and fills r: solver outcome, fitted model,
// its prediction and the uncertainty of the free parameters.
void solveFree(Replayer& replayer, const NoiseLevels& noise, const Model& start,
               const std::vector<FreeParameter>& free, const FitOptions& options, FitResult& r) {
  const auto initial = start.parameters();
  std::vector<double> u;
  for (const auto& f : free) u.push_back(f.scaling.toU(initial[f.index]));
  ceres::Problem problem;
  buildProblem(replayer, noise, start, free, options.loss, u, problem);
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(options), &problem, &summary);
  r.iterations = static_cast<int>(summary.iterations.size());
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.solverReport = summary.BriefReport();
  takeSolution(free, u, r);
  predict(replayer, noise, r);
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
