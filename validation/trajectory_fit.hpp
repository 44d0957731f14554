#pragma once
// One contact model fitted to many dynamic trials at once (docs/DIAGNOSIS.md, "Trajectory
// fits"): the parameters shared, each trial released from its own recorded initial state.
//
// The loss, the mean over trials of e_q (trajectory_compare.hpp), is not smooth in the
// parameters: an impact that moves by one step in time changes it by a jump, and a toss that
// lands on another face jumps it by ~2. Gradients are therefore of no use, and a local method
// started anywhere stops in the first dip. The fit is a derivative-free global search over a
// box (NLopt's DIRECT-L, deterministic: it divides the box and samples the centres of the
// most promising rectangles), then local polishes by Subplex (NLopt's LN_SBPLX, Nelder–Mead on
// subspaces, which tolerates a noisy loss) from the best distinct points of the global phase
// (the multistart), the best result kept.
//
// The search box, per free parameter p with starting value p0 and bounds [lo, hi] (the
// effect's tables, MODEL.md §3): for p0 > 0 and lo ≥ 0 the logarithm of p over
// [p0 / kSearchFactor, p0 · kSearchFactor] ∩ [lo, hi]; otherwise p itself over
// [p0 − 1, p0 + 1] ∩ [lo, hi]. The plate offset (TrajectorySettings::plateOffset, the start
// and, with fitPlateOffset false, the value held) is one more parameter over ±kPlateOffsetRange.
//
// Trials are independent: each evaluation simulates them in parallel (TBB) and sums their
// losses in trial order, so the result does not depend on the thread count.
//
// Cross-validation by trial: the trials are dealt into k folds (trial i into fold i mod k, in
// the order given); each fold's trials are scored by the model fitted on the others, and the
// mean of those held-out e_q is reported beside the fitted one. The fold fits also give each
// parameter's standard error, by the delete-a-group jackknife: the trials, not the samples,
// are the independent units of a trajectory record, and the jackknife's scatter takes in the
// loss's jumps that a local (Gauss–Newton) error cannot see.
//
// The cross-validated fit is k + 1 independent, deterministic fits (the one on all trials and
// one per fold): fitTrajectoryFold runs one of them alone (on any process or machine), and
// assembleTrajectoryFit makes the result from them, the same to the bit as fitTrajectories,
// which is the two in one process (docs/STUDY.md, "Fit studies").

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "validation/trajectory_compare.hpp"

namespace vcontact::validation {

inline constexpr double kSearchFactor = 30.0;
inline constexpr double kPlateOffsetRange = 0.005;  ///< m: a board's few millimetres

struct TrajectoryFitOptions {
  TrajectorySettings settings;
  bool fitPlateOffset = true;
  int globalEvaluations = 48;  ///< DIRECT-L's budget
  int localEvaluations = 32;   ///< Subplex's budget per start
  int starts = 2;              ///< local polishes, from the best distinct global points
  int folds = 5;               ///< k of the cross-validation; 0 or 1: none
  /// (what, done, total) after each evaluation; may be empty.
  std::function<void(const std::string&, int, int)> progress;
};

struct TrajectoryParameter {
  std::string name, unit;
  double start = 0.0, value = 0.0, lower = 0.0, upper = 0.0;
  /// The standard error reported: when the fit is cross-validated the larger of the
  /// jackknife's over the folds (jackknifeError) and Gauss–Newton's, else Gauss–Newton's
  /// (gaussNewtonError).
  double stdError = 0.0;
  bool logScale = false;
  /// Gauss–Newton standard error from the residuals' finite-difference Jacobian at the
  /// optimum, σ² (JᵀJ)⁻¹ with σ² = RSS / (N − p); NaN when JᵀJ is singular. It takes the
  /// samples as independent; those of one trajectory are not (an impact a step late shifts
  /// every later sample), so it understates the error by about √(samples per trial).
  double gaussNewtonError = std::numeric_limits<double>::quiet_NaN();
  /// Delete-a-group jackknife over the k fold fits (each without one fold's trials):
  /// sqrt((k − 1)/k Σ_f (θ_f − θ̄)²), trials as the independent units; NaN without folds.
  double jackknifeError = std::numeric_limits<double>::quiet_NaN();
};

struct TrialScore {
  std::string name;
  double e_q_start = 0.0;    ///< with the starting model
  double e_q_fitted = 0.0;   ///< with the model fitted on all trials
  double e_q_heldOut = 0.0;  ///< with the model fitted without this trial's fold (NaN: no CV)
  int fold = -1;
  TrajectoryErrors errors;  ///< the fitted model's, with phases
  /// The phase where the fitted model fails most (largest share of e_q), e.g. "impacts".
  std::string worstPhase;
};

struct TrajectoryFitResult {
  dynamics::Model model;
  double plateOffset = 0.0;                     ///< m
  std::vector<TrajectoryParameter> parameters;  ///< the free ones, then "plate.offset"
  double meanStart = 0.0, meanFitted = 0.0;
  double meanHeldOut = std::numeric_limits<double>::quiet_NaN();
  std::vector<TrialScore> trials;
  long evaluations = 0;  ///< mean-loss evaluations (each simulates every trial)
  long trialSimulations = 0;
  double seconds = 0.0;     ///< wall
  double cpuSeconds = 0.0;  ///< process CPU time
  std::vector<std::string> warnings;
};

/// One of the k + 1 fits of a cross-validated trajectory fit. fold −1: the fit on all trials;
/// fold i in [0, k): the fit on the trials not in fold i (trial j is in fold j mod k), which
/// then scores fold i's trials.
struct TrajectoryFoldFit {
  int fold = -1;
  int folds = 0;                                ///< k
  std::vector<double> u;                        ///< the best point, in the unit search box
  std::vector<TrajectoryParameter> parameters;  ///< its values; standard errors: fold −1's only
  std::vector<std::size_t> heldOut;             ///< fold i's trials (indices), in order
  std::vector<double> heldOutLoss;              ///< their e_q with this fold's model
  long evaluations = 0;
  long trialSimulations = 0;
  double seconds = 0.0, cpuSeconds = 0.0;  ///< wall and process CPU time
};

/// Fold `fold` of `options.folds` (−1: all trials). @throws InputError when the fold is not in
/// [−1, k) or k is not a cross-validation of these trials (k < 2 or more folds than trials).
TrajectoryFoldFit fitTrajectoryFold(const std::vector<Trial>& trials, const dynamics::Model& start,
                                    const TrajectoryFitOptions& options, int fold);

/// The result of the fit on all trials (fold −1) and, when options.folds >= 2 and the trials
/// are enough, every fold's fit, ordered 0 … k−1: the standard errors, the trial scores and the
/// held-out e_q (the standard errors are fold −1's). evaluations and seconds are the parts' sums
/// plus this assembly's time.
/// @throws InputError when the parts are not those folds
TrajectoryFitResult assembleTrajectoryFit(const std::vector<Trial>& trials,
                                          const dynamics::Model& start,
                                          const TrajectoryFitOptions& options,
                                          const TrajectoryFoldFit& all,
                                          const std::vector<TrajectoryFoldFit>& folds);

/// True when options.folds cross-validates these many trials (k >= 2 and k <= trials).
bool crossValidates(const TrajectoryFitOptions& options, std::size_t trials);

/// The mean e_q of `model` with the plate offset over the trials whose index is in `subset`
/// (all when empty), trials in parallel, summed in index order.
double meanTrialLoss(const std::vector<Trial>& trials, const std::vector<std::size_t>& subset,
                     const dynamics::Model& model, TrajectorySettings settings);

TrajectoryFitResult fitTrajectories(const std::vector<Trial>& trials, const dynamics::Model& start,
                                    const TrajectoryFitOptions& options);

}  // namespace vcontact::validation
