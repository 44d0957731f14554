#pragma once
// A dynamic dataset against the model (docs/DATASET.md, "Dynamic datasets"; docs/MODEL.md):
// the payload is released from the record's initial state (free_flight.hpp) as a free body
// over the fixed plate and simulated with the model by the engine's Simulator (an in-memory
// Scenario of two bodies and one pair), and its path is set against the recorded one sample
// by sample.
//
// Frames: B is the plate frame and the simulation's world; A is the payload frame.
//
// The loss of one trial (SOURCE.md of the cube tosses, Acosta et al. 2022):
//   e_q = mean_i |p_sim,i − p_i|² / h  +  mean_i θ_i²
// over every sample from the first, p the payload origin (m), θ the angle of the rotation
// between the simulated and recorded attitudes (rad), h a length (the payload's half
// smallest extent unless given).
//
// evaluateTrial is the one function a fit calls per trial and per parameter vector: model
// parameters and one trial in, loss and residuals out, no state kept, so that it can be
// called from any thread or process (issue 35's Dask workers).

#include <limits>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/scenario.hpp"
#include "validation/dataset.hpp"
#include "validation/free_flight.hpp"

namespace vcontact::validation {

/// How one trial is simulated.
struct TrajectorySettings {
  /// The integrator: the discrete stepper by default (one analytic box clip per 1 ms step,
  /// stiff friction implicit, impacts resolved by Dormand–Prince: ~20 ms of CPU per toss of the
  /// cube record, 2–3 times fewer than dopri5 at these tolerances, and a lower e_q there).
  dynamics::Integrator integrator = dynamics::Integrator::kDiscrete;
  double absTol = 1e-7;  ///< per-step error bounds (m, m/s, rad): far below mocap noise
  double relTol = 1e-5;
  double step = 1e-3;  ///< s, the discrete integrator's step
  /// m, along the plate's normal: where the plate's surface really is relative to the record's
  /// plate frame (a board below its markers' zero); a fitted parameter of the trajectory fit.
  double plateOffset = 0.0;
  /// m, the e_q length h; NaN: half the payload's smallest bounding-box extent.
  double h = std::numeric_limits<double>::quiet_NaN();
};

/// The simulated payload at every sample time of the record.
struct SimulatedPath {
  std::vector<Eigen::Isometry3d> X_BA;
  std::vector<Eigen::Vector3d> v_BA;  ///< velocity of the payload origin, m/s
  std::vector<Eigen::Vector3d> w_BA;  ///< rad/s
  std::vector<double> penetration;    ///< m, deepest point of the payload below the plate
  std::string stopped;                ///< why the run stopped early ("" when it did not)
  double stopTime = 0.0;              ///< s after the first sample, when it stopped
};

/// What the record does at a sample, read from the record alone (never from the model).
enum class TrajectoryPhase { kFlight, kImpact, kSliding, kRest };
/// "flight", "impacts", "sliding or rolling", "rest"
const char* trajectoryPhaseName(TrajectoryPhase p);
inline constexpr int kPhaseCount = 4;

/// The record's phase at every sample: flight while the payload's lowest point is more than
/// max(3 σ_position, 2 % of its size) above the plate (half-space) or the interference volume
/// is zero (other plates); in contact, an impact at the first kImpactSamples samples after
/// flight; rest while the payload's points move slower than kTossRestSpeed on average over
/// kRestWindow (twice that once at rest); sliding or rolling else.
std::vector<TrajectoryPhase> recordPhases(const Dataset& d);
/// m: the contact margin of the phases, max(3 σ_position, 2 % of the payload's smallest extent).
double contactMargin(const Dataset& d);
/// m: how far the recorded payload's lowest point goes below a half-space plate at its deepest
/// (negative when it never reaches it); NaN for another plate.
double recordedSink(const Dataset& d);
inline constexpr int kImpactSamples = 3;
inline constexpr double kTossRestSpeed = 0.02;  ///< m/s: a few mocap noise levels at 148 Hz
/// s: rest is judged on the mean speed over this window (the poses at its ends), so that the
/// ringing of a resting body on its contact and the markers' noise do not read as motion.
inline constexpr double kRestWindow = 0.1;

struct PhaseErrors {
  TrajectoryPhase phase = TrajectoryPhase::kFlight;
  std::size_t samples = 0;
  double e_q = 0.0;
  double positionFraction = 0.0;  ///< mean |Δp| over the payload's smallest extent
  double rotationDeg = 0.0;       ///< mean θ, degrees
  double maxPenetration = 0.0;    ///< m, simulated
};

struct TrajectoryErrors {
  double h = 0.0;     ///< m, the e_q length used
  double size = 0.0;  ///< m, the payload's smallest extent
  double e_q = 0.0;
  double e_position = 0.0;  ///< mean |Δp|²/h
  double e_attitude = 0.0;  ///< mean θ²
  double positionFraction = 0.0;
  double rotationDeg = 0.0;
  double maxPenetration = 0.0;
  std::vector<double> dp;           ///< m, per sample
  std::vector<double> dtheta;       ///< rad, per sample
  std::vector<PhaseErrors> phases;  ///< the phases the record has, in TrajectoryPhase order
  /// s after the first sample: the first sample where |Δp| > h/2 or θ > 0.25 rad (they part);
  /// NaN when they never do.
  double partTime = std::numeric_limits<double>::quiet_NaN();
};

/// One record ready to be simulated many times: the dataset, its initial state and phases.
struct Trial {
  Dataset data;
  FlightState start;
  std::vector<TrajectoryPhase> phases;
};
Trial prepareTrial(Dataset data);

/// The two-body scenario of a trial: the plate fixed at X_BP (moved by plateOffset along its
/// normal), the payload free from the initial state, one pair with `model`.
dynamics::Scenario trialScenario(const Trial& trial, const dynamics::Model& model,
                                 const TrajectorySettings& settings);

SimulatedPath simulateTrial(const Trial& trial, const dynamics::Model& model,
                            const TrajectorySettings& settings);

TrajectoryErrors trajectoryErrors(const Trial& trial, const SimulatedPath& path,
                                  const TrajectorySettings& settings);

struct TrialEvaluation {
  double loss = 0.0;  ///< e_q
  /// Per sample: |Δp|/sqrt(h) and θ, interleaved (their squares' means sum to e_q).
  Eigen::VectorXd residuals;
  SimulatedPath path;
  TrajectoryErrors errors;
};

/// Model parameters and one trial → its loss and residuals (thread-safe, no shared state).
TrialEvaluation evaluateTrial(const dynamics::Model& model, const Trial& trial,
                              const TrajectorySettings& settings);

}  // namespace vcontact::validation
