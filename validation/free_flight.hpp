#pragma once
// The initial state of a dynamic dataset (docs/DATASET.md, "Dynamic datasets"): the payload's
// pose and velocities at the first sample, given by the record's velocity columns or
// estimated from the free flight before the first contact. Free flight is a parabola of the
// centre of mass under gravity and a torque-free rotation, so the estimate is a least-squares
// fit of those two motions to the samples before the payload first touches the plate; no
// sample after it is used.
//
// Frames: B is the plate frame (the world of the simulation), A the payload frame, Acm the
// payload's centre of mass (p_AAcm = PayloadInertia::com in A).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>

#include "validation/dataset.hpp"

namespace vcontact::validation {

/// The fewest free samples an estimate uses: position and velocity of a parabola with known
/// gravity need two, and a third gives each a residual to average the noise over.
inline constexpr std::size_t kMinFreeFlightSamples = 3;

/// Index of the first sample at which the payload interferes with the plate (interference
/// volume > 0 with the plate at Dataset::X_BP); size() when it never does.
std::size_t firstContact(const Dataset& d);

/// Signed distance from the plate's plane to the payload's lowest point at pose X_BA (m,
/// negative when it is below the plane), for a half-space plate; NaN for any other plate.
double clearance(const Dataset& d, const Eigen::Isometry3d& X_BA);

struct FlightState {
  std::size_t sample = 0;  ///< the sample the state is at (the first)
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_BAcm = Eigen::Vector3d::Zero();  ///< velocity of the centre of mass, m/s
  Eigen::Vector3d w_BA = Eigen::Vector3d::Zero();    ///< angular velocity, plate frame, rad/s
  bool estimated = false;       ///< from the free flight (false: the velocity columns)
  std::size_t samplesUsed = 0;  ///< free samples of the estimate
  double positionRms = 0.0;     ///< m, the parabola's residual over them
  double attitudeRms = 0.0;     ///< rad, the rotation's residual over them
};

/// The payload's state at sample 0. @pre d is dynamic, with mass properties, and has velocity
/// columns or at least kMinFreeFlightSamples samples before firstContact (the reader checks).
FlightState initialState(const Dataset& d);

/// Advances a torque-free rotation by dt (s): attitude R_BA and ω (plate frame) under Euler's
/// equations I ω̇_A + ω_A × I ω_A = 0 in the payload's axes (I about the centre of mass),
/// classic Runge–Kutta in substeps of at most 1e-4 s (the estimate's model, not a simulation).
void advanceTorqueFree(Eigen::Matrix3d& R_BA, Eigen::Vector3d& w_B, const Eigen::Matrix3d& I_A,
                       double dt);

}  // namespace vcontact::validation
