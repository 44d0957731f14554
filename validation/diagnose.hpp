#pragma once
// Which physical effect is the model missing? (issue #5)
//
// The model is fitted (the baseline), then for every effect of the library (or of the user's
// candidate set, DiagnoseOptions::candidates) that it lacks the effect is added (with the
// effects it requires, MODEL.md §3), the model refitted, and the
// candidates ranked by ΔBIC = BIC_candidate − BIC_baseline, BIC = χ² + k ln n (known σ).
// Verdict: the best candidate when ΔBIC < −kBicMargin, else "none".
// kBicMargin = 10 is "very strong" evidence on the Kass–Raftery (1995) scale (2 ln B > 10,
// a Bayes factor above 150). Under the null (the effect is absent), adding k parameters lowers
// χ² by about a χ²_k variable, so ΔBIC ≈ k ln n − χ²_k: P(ΔBIC < −10) < 1e-3 for k ≤ 2 even at
// n = 100, while a missing effect whose share of the signal is a few σ over a window of m
// samples lowers χ² by far more. A model that already explains the data stays as it is.
//
// `where` locates the baseline's failures: samples whose moving-window chi exceeds
// kWindowChi are merged into time windows, and each window is described by the regime
// variable (speed, spin ratio, time at rest, rest before the motion, penetration rate, load)
// in which it is most unlike the rest of the record (mean rank of its samples farthest from
// the middle), as that variable's 10–90 % range over the window and what it means.
//
// --iterate adds greedily; an effect added early can become unnecessary once a later one is
// in (it was the best partial stand-in). When the last verdict is "none", each effect added
// by the iteration is removed in turn and the model refitted; an effect whose removal raises
// BIC by less than the margin is dropped (backward elimination), as a new stage.
//
// A candidate whose added effects contain another candidate's, and whose χ² is not lower by
// the margin, is marked redundant (adding spin brings coulomb along; when coulomb alone fits
// as well, the verdict is coulomb).
//
// Candidates are fitted in parallel with TBB (one Replayer each).

#include <optional>
#include <string>
#include <vector>

#include "validation/candidates.hpp"
#include "validation/fit.hpp"

namespace vcontact::validation {

/// Kass–Raftery "very strong": see the header.
inline constexpr double kBicMargin = 10.0;

struct Candidate {
  std::string effect;              ///< the effect ranked
  std::vector<std::string> added;  ///< every effect added with it (itself first)
  FitResult fit;
  double deltaBic = 0.0;
  std::string error;  ///< non-empty: the candidate could not be fitted
  /// Non-empty: a candidate adding a subset of these effects fits as well (χ² within the
  /// margin), so this one adds nothing of its own; ranked after the others.
  std::string redundantWith;
};

struct FailureWindow {
  std::string output;
  double t0 = 0.0, t1 = 0.0;  ///< s
  double chi = 0.0;           ///< sqrt(mean (r/σ)²) over the window
  std::string
      regime;  ///< e.g. "spin ratio r_gyr|ω_n|/|v_t| in [2.1, 8.4] (spin-dominated sliding)"
};

struct DiagnosisStage {
  std::vector<std::string> effects;  ///< of the baseline model
  FitResult baseline;
  std::vector<Candidate> ranking;  ///< best (lowest ΔBIC) first; failed candidates last
  std::vector<FailureWindow> where;
  std::string verdict;  ///< the best candidate's id, or "none"
  std::string removed;  ///< non-empty: this stage dropped an effect (pruning)
};

struct DiagnoseOptions {
  FitOptions fit;
  bool iterate = false;  ///< add the best and repeat until "none"
  double margin = kBicMargin;
  /// The effects tried at each stage (validation/candidates.hpp); the library's by default.
  CandidateSet candidates = CandidateSet::library();
};

struct Diagnosis {
  std::vector<DiagnosisStage> stages;  ///< one without iterate
  /// The last stage's baseline: the final model when iterating.
  const FitResult& final() const { return stages.back().baseline; }
};

Diagnosis diagnose(const Dataset& dataset, const NoiseLevels& noise, const dynamics::Model& start,
                   const DiagnoseOptions& options = {});

/// Failure windows of a fitted model (see the header).
std::vector<FailureWindow> failureWindows(const Dataset& dataset, const Comparison& comparison,
                                          const Prediction& prediction);

}  // namespace vcontact::validation
