#pragma once
// A pose trajectory sampled at rows (t, p, q[, v][, ω]) and interpolated between them: the
// prescribed motion of a body read from a CSV file, or the target of a drive
// (docs/SCENARIO.md, "Prescribed motion from a table").
//
// Position: linear (velocity constant on each interval) or cubic Hermite, whose tangents are
// the given velocities or, without them, the three-point estimates of the neighbouring rows.
// Orientation: slerp (linear; angular velocity constant on each interval) or a cubic Hermite
// curve on the rotation group, q(s) = q_i ⊗ Exp(r(s)) with r a cubic in the tangent space at
// q_i whose end slopes give the rows' angular velocities. Either way the velocities are the
// exact time derivatives of the interpolated pose, and the rows are met exactly. Before the
// first row and after the last the pose is held and the velocities are zero.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace vcontact::dynamics {

enum class Interpolation { kLinear, kCubic };

struct TrajectoryRows {
  std::vector<double> t;                 ///< s, strictly increasing
  std::vector<Eigen::Vector3d> p_WB;     ///< m, origin of the body frame
  std::vector<Eigen::Quaterniond> q_WB;  ///< unit quaternions
  std::vector<Eigen::Vector3d> v_WBo;    ///< m/s, optional (empty: estimated)
  std::vector<Eigen::Vector3d> w_WB;     ///< rad/s, world frame, optional
};

/// Pose and velocities of the body frame origin at one time.
struct PathPoint {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_WBo = Eigen::Vector3d::Zero();  ///< m/s, velocity of the frame origin
  Eigen::Vector3d w_WB = Eigen::Vector3d::Zero();   ///< rad/s, world frame
};

class Trajectory {
 public:
  /// @throws InputError for fewer than one row, times not strictly increasing, columns of
  ///         different lengths, or velocities given with linear interpolation
  Trajectory(TrajectoryRows rows, Interpolation interpolation);

  PathPoint at(double t) const;
  double startTime() const { return rows_.t.front(); }
  double endTime() const { return rows_.t.back(); }
  std::size_t rowCount() const { return rows_.t.size(); }

 private:
  void estimateTangents();
  PathPoint position(std::size_t i, double t) const;

  TrajectoryRows rows_;
  Interpolation interpolation_;
  std::vector<Eigen::Vector3d> dp_;  ///< position tangent at each row (cubic)
  std::vector<Eigen::Vector3d> w_;   ///< angular velocity at each row, world (cubic)
};

/// Right Jacobian of SO(3) at the rotation vector r: body angular velocity = J_r(r) ṙ.
Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& r);
/// Its inverse.
Eigen::Matrix3d rightJacobianInverse(const Eigen::Vector3d& r);
/// Rotation vector of a unit quaternion (angle in [0, π] about the axis).
Eigen::Vector3d rotationVector(const Eigen::Quaterniond& q);

}  // namespace vcontact::dynamics
