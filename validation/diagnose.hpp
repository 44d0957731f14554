#pragma once
// Which physical effect is the model missing? (issues #5, 15)
//
// The model is fitted (the baseline, multistart: fit.hpp), then for every candidate effect that
// it lacks (candidateList: by default every effect of the library, or the user's candidate set,
// validation/candidates.hpp) the effect is added (with
// the effects it requires, MODEL.md §3), the model refitted from the baseline's optimum with a
// multistart design over the added parameters only, and the candidates ranked by
// ΔBIC = BIC_candidate − BIC_baseline, BIC = χ² + k ln n (known σ).
//
// Acceptance: a candidate is accepted when, in ranking order,
//   1. ΔBIC < −margin; margin = 10 is "very strong" evidence on the Kass–Raftery (1995) scale
//      (2 ln B > 10). Under the null, adding k parameters lowers χ² by about a χ²_k variable,
//      so P(ΔBIC < −10) < 1e-3 for k ≤ 2 even at n = 100;
//   2. its parameters are physical: none of the added effects' parameters ends at a bound
//      (relations such as μ_S ≥ μ_C hold by the parametrisation, fit.hpp);
//   3. it predicts data it was not fitted on: its held-out χ² (blocked cross-validation over
//      kCvBlocks contiguous blocks, selection.hpp) is below the baseline's by more than
//      heldOutMargin = 10, the same "very strong" margin in χ² units, and by at least
//      kHeldOutShare = a quarter of the baseline's held-out excess over the noise (H − n): under
//      gross model error every candidate lowers χ² by far more than 10, and a stand-in that
//      removes a small part of what is wrong is not a finding. (A missing library effect removes
//      nearly all of the excess; with two missing, each removes a large share.) Only the
//      kCvCandidates best candidates that pass 1 and 2 are cross-validated (the cost).
// Rig candidates (rig.hpp: offset, gain per output, a motion–force lag) are scored on the
// baseline's residual with the same ΔBIC and reported apart from the effects.
// Verdict, in this order (physics and geometry before the rig, issue 37):
//   the accepted effect, unless a rig candidate has a lower ΔBIC and leaves a χ² lower than
//   the effect's by more than the margin;
//   "<finding> or <effect>: cannot tell" (kind "ambiguous") when a rig finding would be the
//   verdict but a physical candidate (past the ΔBIC margin, parameters within their bounds)
//   explains the residual as well (χ² within the margin of what the finding leaves), or when
//   the finding is a lag on a record of one output: one channel cannot tell a delay of the
//   force from a viscoelastic normal force (its relaxation delays the force too), so the
//   verdict is "lag or viscoelastic: cannot tell" (or the rival that explains it as well);
//   several channels sharing one lag, or one channel of several lagging alone, can tell;
//   "geometry: faceting …" (kind "geometry") when the payload is a mesh read without its
//   recovered surface (DATASET.md "surface"), and the baseline refitted on the recovered
//   surface (from its optimum) lowers χ² by more than the margin and explains the residual at
//   least as well (χ² within the margin) as the best rig finding and the accepted effect: the
//   misfit is the mesh's facets, not the channel, and not a law that stands in for them (a
//   power law bends kv V to a faceted V(d)); geometry adds no parameter;
//   "rig: <finding>" when a rig candidate (refined with the contact model refitted, rig.hpp)
//   passes the margin, removes at least kRigShare = half of the baseline's excess χ² − n
//   (one global correction, not a partial stand-in), and no effect beats it;
//   "none" when the baseline's chi is ≤ explainedChi (explained down to the noise);
//   "unexplained" otherwise, with the share of the residual variance the best candidate
//   explains (1 − χ²_c/χ²_baseline) and a description of the residual (selection.hpp).
// explainedChi = 1.2: chi of a model that explains the data is 1 within the sampling scatter
// of chi over a few hundred samples (sqrt(1 ± sqrt(2/n)) ≈ 1 ± 0.03 at n = 600 residuals;
// 1.2 also leaves room for σ estimated from the data).
//
// `where` locates the baseline's failures: samples whose moving-window chi exceeds
// kWindowChi are merged into time windows, cut where the motion's phase changes
// (validation/phases.hpp: a window lies in one phase, which it names), and each window is
// described by the regime variable (speed, spin ratio, time without tangential motion, rest
// before the motion, penetration rate, load; the tangential ones only for a window with
// tangential motion) in which it is most unlike the rest of the record (mean rank of its
// samples farthest from the middle), as that variable's 10–90 % range over the window and
// what it means.
//
// --iterate adds the accepted effect and repeats while the verdict is an effect (a rig finding
// stops it: correct the record first). An effect added early can become unnecessary once a
// later one is in; at the end each effect added by the iteration is removed in turn and the
// model refitted; an effect whose removal raises BIC by less than the margin is dropped
// (backward elimination), as a new stage.
//
// A candidate whose added effects contain another candidate's, and whose χ² is not lower by
// the margin, is marked redundant (adding spin brings coulomb along; when coulomb alone fits
// as well, the verdict is coulomb).
//
// Candidates are fitted in parallel with TBB (one Replayer each).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "validation/candidates.hpp"
#include "validation/direct_estimates.hpp"
#include "validation/fit.hpp"
#include "validation/rig.hpp"
#include "validation/selection.hpp"

namespace vcontact::validation {

/// Kass–Raftery "very strong": see the header.
inline constexpr double kBicMargin = 10.0;
/// Held-out χ² drop an accepted effect must reach: see the header.
inline constexpr double kHeldOutMargin = 10.0;
/// Share of the baseline's held-out excess χ² an accepted effect must remove.
inline constexpr double kHeldOutShare = 0.25;
/// chi at or below which the verdict is "none": see the header.
inline constexpr double kExplainedChi = 1.2;
/// Share of the baseline's excess χ² a rig finding must remove to be the verdict.
inline constexpr double kRigShare = 0.5;
/// Candidates cross-validated per stage.
inline constexpr std::size_t kCvCandidates = 3;

struct Candidate {
  std::string effect;              ///< the effect ranked
  std::vector<std::string> added;  ///< every effect added with it (itself first)
  FitResult fit;
  double deltaBic = 0.0;
  std::string error;  ///< non-empty: the candidate could not be fitted
  /// Non-empty: a candidate adding a subset of these effects fits as well (χ² within the
  /// margin), so this one adds nothing of its own; ranked after the others.
  std::string redundantWith;
  double heldOutChi2 = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not cross-validated
  std::string rejected;  ///< why a candidate past the ΔBIC margin was not accepted
  bool accepted = false;
};

struct FailureWindow {
  std::string output;
  double t0 = 0.0, t1 = 0.0;  ///< s
  double chi = 0.0;           ///< sqrt(mean (r/σ)²) over the window
  std::string
      regime;  ///< e.g. "spin ratio r_gyr|ω_n|/|v_t| in [2.1, 8.4] (spin-dominated sliding)"
  std::string phase;  ///< the motion's phase over the window (phases.hpp): "sliding", …
};

/// The faceting check (see the header): the baseline refitted on the mesh payload's
/// recovered surface.
struct GeometryCheck {
  double chi2 = 0.0, chi = 0.0;  ///< of the refit on the recovered surface
  std::string text;              ///< "faceting: the recovered surface gives chi 1.02 (mesh 7.3)"
};

struct DiagnosisStage {
  std::vector<std::string> effects;  ///< of the baseline model
  FitResult baseline;
  std::vector<Candidate> ranking;  ///< best (lowest ΔBIC) first; failed candidates last
  std::vector<FailureWindow> where;
  /// The accepted effect's id, "rig: <finding>", "<finding> or <effect>: cannot tell", "none"
  /// or "unexplained" (see the header).
  std::string verdict;
  std::string kind;     ///< "effect", "rig", "ambiguous", "none" or "unexplained"
  std::string removed;  ///< non-empty: this stage dropped an effect (pruning)
  double heldOutChi2 = std::numeric_limits<double>::quiet_NaN();  ///< of the baseline
  std::vector<RigFinding> rig;                                    ///< best first
  /// What the record says without the model, beside the baseline's values (far ones flagged
  /// in baseline.warnings).
  std::vector<DirectEstimate> direct;
  /// Tried for a mesh payload on a half-space plate read without its recovered surface.
  std::optional<GeometryCheck> geometry;
  double explainedFraction = 0.0;  ///< 1 − χ²_best candidate / χ²_baseline, ≥ 0
  ResidualDescription residual;    ///< of the baseline
  /// Wall-clock seconds of the stage's parts: baseline fit, candidate fits, cross-validation
  /// (baseline and candidates), rig candidates and residual description.
  struct {
    double baseline = 0.0, candidates = 0.0, crossValidation = 0.0, rest = 0.0;
  } seconds;
};

struct DiagnoseOptions {
  FitOptions fit;
  bool iterate = false;  ///< add the accepted effect and repeat while there is one
  double margin = kBicMargin;
  double heldOutMargin = kHeldOutMargin;
  double explainedChi = kExplainedChi;
  /// The effects tried at each stage (validation/candidates.hpp); the library's by default.
  CandidateSet candidates = CandidateSet::library();
  /// Each stage's steps as they run (baseline, candidates i of n, cross-validation, rig);
  /// empty: nothing reported. fit.progress is not used (the fits run in parallel).
  ProgressFn progress{};
};

/// The candidates for `model`: each effect of options.candidates that the model lacks, with the
/// effects it requires. @throws InputError on an unknown id
std::vector<Candidate> candidateList(const dynamics::Model& model, const DiagnoseOptions& options);

/// The candidate's model: the baseline's values, the added effects at the values of the
/// candidate set (the defaults for the library's), the baseline's fixed parameters held; a
/// relation such as μ_S ≥ μ_C is kept by the fit's parametrisation (fit.hpp).
dynamics::Model candidateModel(const dynamics::Model& baseline, const CandidateSet& set,
                               const Candidate& c);

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
