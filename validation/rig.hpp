#pragma once
// Rig candidates (issue 15 item 3): properties of the measuring rig, not of the contact, that
// leave a trace in a fitted model's residual r = y − ŷ (σ per output). Each is the least-squares
// correction of the residual by one parameter with the contact model held fixed, so it costs no
// refit; its χ² drop is exact for offset and gain and for the best integer lag:
//   offset per output   y = ŷ + c:        c = mean r,             drop = n c²/σ²
//   gain per output     y = (1 + g) ŷ:    g = Σ r ŷ / Σ ŷ²,       drop = (Σ r ŷ)² / (σ² Σ ŷ²)
//   lag (all outputs)   y(t) = ŷ(t − τ):  τ = the shift within ±kMaxLagFraction of the
//                       record that lowers Σ over outputs of ((y_i − ŷ(i − τ))/σ)² most, on the
//                       samples every shift covers: the best whole-sample shift, then a
//                       golden-section search within a sample either side, ŷ between samples by
//                       Catmull–Rom interpolation (so a lag of 2.5 samples reads 2.5, not 2 or 3);
//                       τ > 0: the force columns lag the motion
//   payload inertia     y = ŷ + k w, w = (m a_c, I α + ω × I ω + r_c × m a_c), only when the
//   (all outputs)       sidecar gives `payload_inertia`: k = Σ r w/σ² / Σ w²/σ²,
//                       drop = (Σ r w/σ²)² / Σ w²/σ². The dataset's columns are the plate's
//                       wrench on the payload; k ≈ −1 says they lack the payload's inertia (a
//                       load cell between the drive and the payload, read as the plate's force),
//                       k ≈ +1 that it was counted twice. a_c (of the centre of mass) and α are
//                       the least-squares slopes of the velocity columns over ±h samples, for
//                       each h of kInertiaHalfWidths (at most a twentieth of the record), and the
//                       h that removes the most χ² is kept: velocities differentiated from a
//                       motion capture are noisy, noise in a regressor shrinks k towards 0
//                       (errors in variables), and a wider slope trades that noise for
//                       smoothing of the true acceleration.
// Each is scored like a candidate effect with one parameter: ΔBIC = −drop + ln n.
// A fitted contact model absorbs what its own parameters can mimic (a gain on fz is kv), so a
// finding here is what the contact model cannot make.
//
// refineRig then checks the best finding with the contact model free: the record is corrected
// by it (offset subtracted, gain divided out, inertial wrench subtracted, columns shifted), the
// model refitted from its optimum, and the finding estimated again on the new residual; the value
// is the sum (offset, lag, inertia) or product (gain) of the two estimates, and the χ² drop is
// measured against the refit (the contact parameters and the rig parameter are correlated when the
// record is not balanced, e.g. more sliding one way than the other).

#include <map>
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
/// Half-widths (samples) of the slopes that differentiate the velocities (payload inertia).
inline constexpr int kInertiaHalfWidths[] = {1, 2, 3, 5, 8, 13};

struct RigFinding {
  std::string kind;    ///< "offset", "gain", "lag", "inertia"
  std::string output;  ///< "fx" …, or "all" for the lag
  /// offset in the output's unit, gain factor 1 + g, lag in s, or the inertia factor k
  double value = 0.0;
  std::string unit;  ///< "N", "N·m", "–", "s"
  double chi2Drop = 0.0;
  double deltaBic = 0.0;
  std::string text;             ///< e.g. "fx offset 0.21 N"
  double remainingChi2 = -1.0;  ///< after refineRig; −1 before
  int halfWidth = 0;            ///< inertia: a and α were slopes over ±halfWidth samples
};

/// Every rig candidate of a fitted model's residual, best (lowest ΔBIC) first.
std::vector<RigFinding> rigCandidates(const Dataset& dataset, const Comparison& fitted);

/// `finding` re-estimated with `model` refitted on the corrected record (see the header);
/// sets remainingChi2, the refit's χ² after the finding's correction.
RigFinding refineRig(const Dataset& dataset, const NoiseLevels& noise, const FitResult& fitted,
                     const RigFinding& finding, const FitOptions& options);

/// The payload's inertial wrench about its origin, in the plate frame, per wrench column, a and
/// α as slopes over ±halfWidth samples (see the header); zeros without `dataset.inertia`.
/// @pre at least 3 samples
std::map<std::string, Eigen::VectorXd> inertialWrench(const Dataset& dataset, int halfWidth = 1);

}  // namespace vcontact::validation
