#pragma once
// Which effect lowers the error on trials the fit never saw? (docs/DIAGNOSIS.md, "Trajectory
// diagnosis"; issue 34)
//
// The diagnosis of many dynamic trials is the kinematic one's idea on the trajectory fit: the
// start model is fitted to all trials with k-fold cross-validation by trial (the baseline,
// trajectory_fit.hpp), then every candidate effect it lacks (candidateList: the library's, or a
// candidates file's) is added with the effects it requires, at the baseline's fitted values
// and the candidate's own starting ones, and the cross-validated fit is run again from there
// (the plate offset starting at the baseline's). The candidates are ranked by their mean
// held-out e_q, lowest first.
//
// Acceptance is paired by trial: Δ_i = e_q,held out(candidate, i) − e_q,held out(baseline, i),
// and a candidate is accepted when the mean Δ is negative and beyond kPairedSigmas standard
// errors of the mean, s_Δ/√n. The trials are independent (each fold's model never saw the
// trials it scores), so under "the effect adds nothing" the mean Δ is about normal with that
// standard error, and 2 of them is a one-sided 2.3 % chance; pairing removes what the trials
// share (a toss that lands on a corner is hard for every model). The verdict is the accepted
// candidate with the lowest mean held-out e_q, or "none". A candidate whose fit failed
// (an effect the simulation refuses) is ranked last with its error.
//
// Trials no model explains: each trial's best held-out e_q over the baseline and every
// candidate; a trial is named when that exceeds kUnexplainedFactor times the median of the
// trials' best (a robust scale: most trials are explained by some model) and
// kUnexplainedFloor. For each, the phase of the record where the best model fails most (the
// largest share of its e_q) and a hint read from the record: a free flight whose fit before the
// first contact leaves more than kFlightResidualSigmas σ_position of residual is not a free
// body's (a bad marker track, or a toss that starts in hand); a record that sinks below the
// plate by more than the contact margin rests where the plate is not (a table edge, a marker
// swap); otherwise what fails in that phase.
//
// Cost: 1 + candidates cross-validated fits, each k + 1 fits; candidates run one after the
// other, each fit's trials in parallel (TBB), so the result does not depend on the thread
// count.

#include <limits>
#include <string>
#include <vector>

#include "validation/candidates.hpp"
#include "validation/fit.hpp"
#include "validation/trajectory_fit.hpp"

namespace vcontact::validation {

/// Standard errors of the paired mean Δ a candidate must lower the held-out e_q by.
inline constexpr double kPairedSigmas = 2.0;
/// A trial is unexplained past this many times the median of the trials' best held-out e_q…
inline constexpr double kUnexplainedFactor = 3.0;
/// …and past this e_q: a quarter radian of attitude error all along (0.25² ≈ 0.06), the
/// angle at which compare says the paths part.
inline constexpr double kUnexplainedFloor = 0.0625;
/// Residual of the free-flight fit, in σ_position, beyond which the flight is not a free body's.
inline constexpr double kFlightResidualSigmas = 3.0;

struct TrajectoryCandidate {
  std::string effect;              ///< the effect ranked
  std::vector<std::string> added;  ///< every effect added with it (itself first)
  TrajectoryFitResult fit;         ///< the cross-validated fit with the effect
  double meanDelta = std::numeric_limits<double>::quiet_NaN();      ///< mean Δ_i (see the header)
  double deltaStdError = std::numeric_limits<double>::quiet_NaN();  ///< s_Δ / √n
  bool accepted = false;
  std::string rejected;  ///< why not accepted
  std::string error;     ///< non-empty: the candidate could not be fitted
};

struct UnexplainedTrial {
  std::size_t index = 0;  ///< in the trials given
  std::string name;
  double e_q = 0.0;   ///< the best held-out e_q of any model
  std::string model;  ///< the model that gave it: "baseline" or the candidate's effect
  std::string phase;  ///< where that model fails most
  std::string hint;   ///< what the record says (see the header)
};

struct TrajectoryDiagnosis {
  TrajectoryFitResult baseline;
  std::vector<TrajectoryCandidate> ranking;   ///< lowest mean held-out e_q first; failed last
  std::string verdict;                        ///< the accepted effect's id, or "none"
  std::vector<UnexplainedTrial> unexplained;  ///< worst first
  double medianBest = 0.0;                    ///< median over trials of the best held-out e_q
  double seconds = 0.0;                       ///< wall

  /// The verdict's candidate: the first accepted in the ranking; null for "none".
  const TrajectoryCandidate* accepted() const {
    for (const auto& c : ranking)
      if (c.accepted) return &c;
    return nullptr;
  }
  /// The fit the verdict leaves: the accepted candidate's, else the baseline's.
  const TrajectoryFitResult& final() const { return accepted() ? accepted()->fit : baseline; }
};

struct TrajectoryDiagnoseOptions {
  TrajectoryFitOptions fit;  ///< folds >= 2 (the diagnosis is by held-out e_q)
  CandidateSet candidates = CandidateSet::library();
  /// ("baseline" / "candidate i of n: id", done, total) per fit; may be empty. fit.progress
  /// is not used.
  ProgressFn progress{};
};

/// @throws InputError when options.fit.folds does not cross-validate the trials, or on a
/// candidate that requires an unknown effect
TrajectoryDiagnosis diagnoseTrajectories(const std::vector<Trial>& trials,
                                         const dynamics::Model& start,
                                         const TrajectoryDiagnoseOptions& options);

}  // namespace vcontact::validation
