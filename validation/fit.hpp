#pragma once
// Least-squares fit of a model's free parameters to a dataset (Ceres).
//
// Objective: Σ ρ((r_i/σ_i)²) over all outputs and samples, r = measured − replayed, ρ the
// identity or a robust loss (Huber c = 1.345, Cauchy c = 2.385: 95 % efficiency under normal
// noise). The record is replayed as a whole (friction states carry from sample to sample), so
// all residuals form one Ceres residual block; the robust loss is applied residual-wise by
// handing Ceres sign(e)·sqrt(ρ(e²)), which has the same objective Σ ρ(e²).
//
// Scaling: each free parameter p is optimised as u, of comparable magnitude for all:
//   lower < 0 (signed, e.g. misalignment angles):  u = p / s,  s = 1 % of the half range
//   lower ≥ 0:  u = asinh(p / s),  s = the default value (1 unit where the default is 0):
//               linear near zero, logarithmic over decades (kv ~ 1e12, a ~ 1e4, μ ~ 0.2).
// Bounds are the ParameterSpec bounds mapped through the same transform.
//
// Relations: a parameter p that an effect declares p ≥ q (Effect::relations(), e.g.
// stribeck.mu_s ≥ coulomb.mu) is optimised as Δ = p − q ≥ 0 (u = asinh(Δ/s), s its default),
// so that every trial point of the solver keeps the relation; a start that breaks it starts
// at Δ = 0. Δ = 0 at the end is reported as the parameter being at its relation bound.
//
// Multistart: the start, plus FitOptions::designPoints points of a Halton sequence (bases
// 2, 3, 5, …; deterministic) over the design range of the explored parameters, the others kept
// at the start. Design range in u: the bounds, narrowed for positive parameters to three
// decades either side of the default (s·10^±3), which covers the physical magnitudes of
// MODEL.md §4 without spending points on 1e-6 or 1e12. Every point is screened by one replay
// (its cost), the `polished` cheapest are run by Levenberg–Marquardt in parallel (TBB, one
// copy of the Replayer each, sharing its geometry) for a few iterations, the cheapest is then
// solved to convergence, and the lowest cost wins (ties: the earlier point, so the result
// does not depend on the thread schedule).
//
// At a bound: a free parameter whose u ends within 1e-6 of the u range from a bound
// (ParameterEstimate::atBound) is flagged with a warning: the data push it out of the
// physical range, so the effect stands in for something else.
//
// Held-out samples (FitOptions::heldOut, for cross-validation): the replay still runs over the
// whole record (friction states carry through), their residuals are weighted 0.
//
// Uncertainty: the covariance of u from ceres::Covariance (dense SVD) on the normalised
// residuals, mapped to p by the Jacobian dp/du, scaled by max(1, χ²/(n − k)) so that a model
// that does not explain the data does not claim precision it has not earned. Parameters in a
// near-null direction of the column-normalised Jacobian (singular value ratio below
// kIdentifiableRatio) are reported as not identifiable and held out of the covariance.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "validation/dataset.hpp"
#include "validation/replay.hpp"
#include "validation/residuals.hpp"

namespace vcontact::validation {

enum class Loss { kSquared, kHuber, kCauchy };

/// "none"/"squared", "huber", "cauchy". @throws InputError naming the accepted values
Loss parseLoss(const std::string& name);
std::string lossName(Loss loss);

/// Told as a long fit or diagnosis advances: what it is doing ("stage 2: candidates") and how
/// far (done of total). Called from worker threads too: the callee serialises.
using ProgressFn = std::function<void(const std::string& what, int done, int total)>;

struct FitOptions {
  Loss loss = Loss::kSquared;
  int maxIterations = 100;
  int designPoints = 16;  ///< Halton points screened besides the start (0: the start alone)
  int polished = 3;       ///< cheapest screened starts solved by LM
  /// Parameters the design varies; empty: every free parameter.
  std::vector<std::string> explore{};
  /// Per sample: true = left out of the objective (cross-validation). Empty: none.
  std::vector<bool> heldOut{};
  /// Screening and polished starts as they finish; empty: nothing reported.
  ProgressFn progress{};
};

struct ParameterEstimate {
  std::string name;  ///< "effect.parameter"
  std::string unit;
  double initial = 0.0;
  double value = 0.0;
  double stdError = 0.0;  ///< NaN when fixed; +inf when not identifiable
  bool fixed = false;
  bool identifiable = true;
  /// Empty, or the bound the fitted value sits at: "lower", "upper", or "≥ q" for a relation.
  std::string atBound;
};

struct FitResult {
  dynamics::Model model;  ///< with the fitted values
  Prediction prediction;
  Comparison comparison;
  double bic = 0.0;
  std::size_t freeCount = 0;  ///< k in the BIC
  std::vector<ParameterEstimate> parameters;
  std::vector<std::string> freeNames;  ///< rows/columns of `correlation`
  Eigen::MatrixXd correlation;         ///< of the free parameters (NaN rows: not identified)
  std::vector<std::string> warnings;
  int iterations = 0;
  bool converged = false;
  int startsPolished = 0;    ///< LM runs of the multistart
  int winningStart = 0;      ///< 0: the given start; i > 0: Halton point i
  std::string solverReport;  ///< Ceres' one-line summary
};

/// Fits every parameter of `start` that is not in start.fixed().
/// @param replayer replays start.dataset; reused across fits of the same dataset (geometry cache)
FitResult fit(Replayer& replayer, const NoiseLevels& noise, const dynamics::Model& start,
              const FitOptions& options = {});

}  // namespace vcontact::validation
