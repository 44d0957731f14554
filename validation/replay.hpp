#pragma once
// Kinematic replay of a rig record through a contact model (DATASET.md "mode": kinematic).
//
// Bodies and frames: body A is the payload, body B the plate; the plate is placed at the
// identity, so its frame B is the world frame W of MODEL.md. For every sample the replay
//   1. places the payload at X_BA (after the model's geometry-only effects, misalignment),
//   2. computes the ContactVolume with the plate (analytic where the pair allows),
//   3. forms the relative motion at the centroid, v_c = v_BA + w_BA × (p_c − p_BAo)
//      (MODEL.md §2, dynamics::relativeMotion),
//   4. evaluates the model with the friction states integrated along the record,
//   5. moves the wrench from p_c to the payload origin Ao: τ_Ao = τ_c + (p_c − p_BAo) × f.
// A payload that touches the plate in several regions (feet, a ring, a rocking part) has one
// contact patch per region: steps 3–5 run per patch, each with its own friction states, and
// the wrenches are summed about Ao. Patches are followed from sample to sample by the
// simulator's rule (dynamics/trackers/patch_tracker.hpp): a new patch starts from rest, a vanished
// one is dropped. A record whose contact is one region throughout is replayed exactly as before.
//
// Friction states (bristle z, θ_n, dwell s_dw) are integrated from sample i to i+1 with the
// exponential Euler method on the kinematics of sample i:
//   x_{i+1} = x_i + ẋ_i φ(d Δt) Δt,   φ(a) = (e^a − 1)/a,   d = ∂ẋ/∂x (diagonal).
// MODEL.md's state equations are affine and uncoupled per component for frozen kinematics
// (ż = b − (1 − s)(σ0/σ1) z, θ̇ likewise, ṡ_dw = (s − s_dw)/τ_dw), so this step is their exact
// solution over the interval, stable for any σ0/σ1 and τ_dw however stiff; d is measured
// through Model::evaluate (one extra evaluation), so the replay needs no effect internals.
// After each step Model::settle applies the discrete updates (projection, dwell jump, reset
// when contact is lost). The first sample starts from the zero state.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "validation/dataset.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::validation {

/// One contact region of a sample (MODEL.md §1): its volume, the relative motion at its
/// centroid and the lever from the payload origin to that centroid.
struct PatchGeometry {
  volume::ContactVolume cv;
  dynamics::RelativeMotion motion;
  Eigen::Vector3d p_AoC_B = Eigen::Vector3d::Zero();  ///< payload origin → centroid, m
};

/// Geometry and relative motion of one sample, for one payload pose adjustment: the whole
/// A ∩ B as one region (the regime is described on it), and its patches.
struct SampleGeometry : PatchGeometry {
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();  ///< the adjusted payload pose
  /// Each connected region when there are two or more; empty when the contact is one region
  /// (then it is the sample's own PatchGeometry, and a payload that never touches in two
  /// places costs nothing).
  std::vector<PatchGeometry> patches;
};

/// The physical regime of one sample: what `where` windows are described by.
struct RegimeSample {
  double speed = 0.0;             ///< sliding speed |v_t|, m/s
  double spin_ratio = 0.0;        ///< r_gyr |ω_n| / max(|v_t|, v_ε), –
  double time_at_rest = 0.0;      ///< time since v_avg fell below kRestSpeed (0 moving), s
  double preceding_rest = 0.0;    ///< moving: length of the rest before this motion, s
  double penetration_rate = 0.0;  ///< δ̇_c, m/s
  double load = 0.0;              ///< f_n, N
  bool in_contact = false;        ///< the payload touches the plate (V > 0)
  double volume = 0.0;            ///< V, m³
  double depth = 0.0;             ///< deepest penetration, m
  /// Out of contact: the payload's approach speed along the plate's e_z (−v_z), m/s.
  double approach_rate = 0.0;
  /// The speed at which the payload's surface rolls over the contact: |ω_t| times the lever
  /// from the payload origin to the centroid, m/s.
  double roll_speed = 0.0;
  double spin_speed = 0.0;  ///< r_gyr |ω_n|, m/s
};

/// Below this sliding-plus-spin speed a sample counts as "at rest": a tenth of the smallest
/// stick–slip speed v_s a rig resolves (1e-4 m/s against the default v_s = 1e-3 m/s).
inline constexpr double kRestSpeed = 1e-4;  // m/s

/// The first sample where the model's wrench is not finite (inf or NaN), and the effect whose
/// share is not; a prediction with one cannot be compared with the record.
struct NonFinitePrediction {
  std::size_t sample = 0;
  std::string effect;  ///< the first effect (in stage order) with a non-finite share
};

struct Prediction {
  /// n × 6, columns in kWrenchColumns order: force on the payload by the plate (N) and torque
  /// about the payload origin (N·m), both in B (the plate frame).
  Eigen::MatrixXd wrench;
  std::vector<RegimeSample> regime;
  /// Set when some sample's wrench is not finite (the first such sample).
  std::optional<NonFinitePrediction> nonFinite;
  /// The predicted column named `output` ("fx" … "tz").
  Eigen::VectorXd column(const std::string& output) const;
};

/// Index of a wrench column name in kWrenchColumns. @pre it is one of them
int wrenchIndex(const std::string& output);

/// Replays one dataset through many models (a fit evaluates thousands): the geometry of every
/// sample is computed once per value of the model's geometry-only parameters and cached.
/// Not thread-safe; use one Replayer per thread. A copy shares the cached geometry (immutable,
/// reference-counted): the parallel starts, candidates and folds of one record copy one
/// replayer instead of computing every sample's contact volume again.
class Replayer {
 public:
  /// @pre dataset outlives the replayer
  explicit Replayer(const Dataset& dataset);

  /// @param regime  false: leave Prediction::regime at its defaults (a fit's residuals do not
  ///   read it, and describing every sample's regime is a tenth of a replay's cost)
  /// @throws InputError when no volume method handles the payload/plate pair
  Prediction run(const dynamics::Model& model, bool regime = true);

  const Dataset& dataset() const { return dataset_; }

 private:
  const std::vector<SampleGeometry>& geometryFor(const dynamics::Model& model);
  Prediction runWhole(const dynamics::Model& model, bool regime);
  Prediction runPatches(const dynamics::Model& model, int slots, bool regime);

  const Dataset& dataset_;
  std::vector<double> cachedKey_;
  bool cached_ = false;
  std::shared_ptr<const std::vector<SampleGeometry>> geometry_;
};

}  // namespace vcontact::validation
