#pragma once
// Rig candidates (issue 15 item 3): properties of the measuring rig, not of the contact, that
// leave a trace in a fitted model's residual r = y − ŷ (σ per output). Each is the least-squares
// correction of the residual by one parameter with the contact model held fixed, so it costs no
// refit; its χ² drop is exact for offset and gain and for the best integer lag:
//   offset per output   y = ŷ + c:        c = mean r,             drop = n c²/σ²
//   gain per output     y = (1 + g) ŷ:    g = Σ r ŷ / Σ ŷ²,       drop = (Σ r ŷ)² / (σ² Σ ŷ²)
//   lag (all outputs)   y(t) = ŷ(t − τ):  τ = the sample shift within ±kMaxLagFraction of the
//                       record that lowers Σ over outputs of ((y_i − ŷ_{i−τ})/σ)² most, on the
//                       samples both shifts cover; τ > 0: the force columns lag the motion
// (The payload's own inertia, m·a and I·α, needs mass and inertia keys in the sidecar, which
// DATASET.md does not have yet: not a candidate here.)
// Each is scored like a candidate effect with one parameter: ΔBIC = −drop + ln n.
// A fitted contact model absorbs what its own parameters can mimic (a gain on fz is kv), so a
// finding here is what the contact model cannot make.
//
// refineRig then checks the best finding with the contact model free: the record is corrected
// by it (offset subtracted, gain divided out, columns shifted), the model refitted from its
// optimum, and the finding estimated again on the new residual; the value is the sum (offset,
// lag) or product (gain) of the two estimates, and the χ² drop is measured against the refit
// (the contact parameters and the rig parameter are correlated when the record is not
// balanced, e.g. more sliding one way than the other).

#include <string>
#include <vector>

#include "validation/dataset.hpp"
#include "validation/fit.hpp"
#include "validation/replay.hpp"
#include "validation/residuals.hpp"

namespace vcontact::validation {

/// Largest lag tried, as a fraction of the record (and at most kMaxLagSamples).
inline constexpr double kMaxLagFraction = 0.02;
inline constexpr int kMaxLagSamples = 50;

struct RigFinding {
  std::string kind;    ///< "offset", "gain", "lag"
  std::string output;  ///< "fx" …, or "all" for the lag
  double value = 0.0;  ///< offset in the output's unit, gain factor 1 + g, or lag in s
  std::string unit;    ///< "N", "N·m", "–", "s"
  double chi2Drop = 0.0;
  double deltaBic = 0.0;
  std::string text;             ///< e.g. "fx offset 0.21 N"
  double remainingChi2 = -1.0;  ///< after refineRig; −1 before
};

/// Every rig candidate of a fitted model's residual, best (lowest ΔBIC) first.
std::vector<RigFinding> rigCandidates(const Dataset& dataset, const Comparison& fitted);

/// `finding` re-estimated with `model` refitted on the corrected record (see the header);
/// sets remainingChi2, the refit's χ² after the finding's correction.
RigFinding refineRig(const Dataset& dataset, const NoiseLevels& noise, const FitResult& fitted,
                     const RigFinding& finding, const FitOptions& options);

}  // namespace vcontact::validation
