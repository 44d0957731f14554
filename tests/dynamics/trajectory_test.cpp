// Trajectories (dynamics/trajectory.hpp): the rows are met exactly, the velocities are the
// time derivatives of the interpolated pose, given velocities are met at the rows, and the
// pose is held after the last row.

#include "dynamics/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/rigid_body.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics {
namespace {

// Rows of a body that moves and turns about a changing axis, unevenly spaced in time.
TrajectoryRows wobble(bool with_velocities) {
  TrajectoryRows rows;
  const double times[] = {0.0, 0.1, 0.25, 0.3, 0.5};
  for (double t : times) {
    rows.t.push_back(t);
    rows.p_WB.emplace_back(0.1 * t, std::sin(3.0 * t) * 0.02, 0.05 - 0.2 * t * t);
    const Eigen::Quaterniond q(Eigen::AngleAxisd(2.0 * t, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(1.5 * t * t, Eigen::Vector3d::UnitX()));
    rows.q_WB.push_back(t == 0.25 ? Eigen::Quaterniond(-q.coeffs()) : q);  // same rotation
    if (with_velocities) {
      rows.v_WBo.emplace_back(0.1, 0.06 * std::cos(3.0 * t), -0.4 * t);
      rows.w_WB.emplace_back(3.0 * t, 0.0, 2.0);
    }
  }
  return rows;
}

// The derivative of the pose by central differences against the reported velocities. Step
// 1e-6 s: the difference's truncation error is ~h² |x'''| ≈ 1e-11 and its round-off
// ~1e-16 / h = 1e-10, both far below the 1e-7 asked (of velocities ~0.1 to 3).
void expectConsistent(const Trajectory& traj, double t) {
  const double h = 1e-6;
  const PathPoint a = traj.at(t - h), b = traj.at(t + h), m = traj.at(t);
  const Eigen::Vector3d v = (b.X_WB.translation() - a.X_WB.translation()) / (2.0 * h);
  EXPECT_LT((v - m.v_WBo).norm(), 1e-7) << "t = " << t;
  // Ṙ Rᵀ = [ω]×
  const Eigen::Matrix3d R_dot = (b.X_WB.linear() - a.X_WB.linear()) / (2.0 * h);
  const Eigen::Matrix3d W = R_dot * m.X_WB.linear().transpose();
  const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
  EXPECT_LT((w - m.w_WB).norm(), 1e-7) << "t = " << t;
}

void expectRowsMet(const Trajectory& traj, const TrajectoryRows& rows) {
  for (std::size_t i = 0; i < rows.t.size(); ++i) {
    const PathPoint p = traj.at(rows.t[i]);
    // exact up to the round-off of the interpolation formulas
    EXPECT_LT((p.X_WB.translation() - rows.p_WB[i]).norm(), 1e-15) << i;
    EXPECT_LT(Eigen::Quaterniond(p.X_WB.linear()).angularDistance(rows.q_WB[i]), 1e-9) << i;
  }
}

TEST(Trajectory, LinearMeetsTheRowsWithConsistentVelocities) {
  const TrajectoryRows rows = wobble(false);
  const Trajectory traj(rows, Interpolation::kLinear);
  expectRowsMet(traj, rows);
  for (double t : {0.05, 0.17, 0.26, 0.41}) expectConsistent(traj, t);
  // constant on an interval: the interval's slope
  const PathPoint p = traj.at(0.2);
  EXPECT_LT((p.v_WBo - (rows.p_WB[2] - rows.p_WB[1]) / 0.15).norm(), 1e-12);
}

TEST(Trajectory, CubicMeetsTheRowsAndTheGivenVelocities) {
  for (bool given : {false, true}) {
    const TrajectoryRows rows = wobble(given);
    const Trajectory traj(rows, Interpolation::kCubic);
    expectRowsMet(traj, rows);
    for (double t : {0.05, 0.17, 0.26, 0.41}) expectConsistent(traj, t);
    if (!given) continue;
    for (std::size_t i = 0; i + 1 < rows.t.size(); ++i) {  // the last row is held
      const PathPoint p = traj.at(rows.t[i]);
      EXPECT_LT((p.v_WBo - rows.v_WBo[i]).norm(), 1e-12) << i;
      EXPECT_LT((p.w_WB - rows.w_WB[i]).norm(), 1e-9) << i;
    }
  }
}

// Cubic without velocities reproduces a uniform motion (the three-point tangents of a line are
// its slope) and a steady rotation about one axis.
TEST(Trajectory, CubicIsExactForUniformMotion) {
  TrajectoryRows rows;
  const Eigen::Vector3d v(0.3, -0.1, 0.2), w(0.0, 0.0, 4.0);
  for (double t : {0.0, 0.2, 0.3, 0.7}) {
    rows.t.push_back(t);
    rows.p_WB.push_back(v * t);
    rows.q_WB.emplace_back(Eigen::AngleAxisd(4.0 * t, Eigen::Vector3d::UnitZ()));
  }
  const Trajectory traj(rows, Interpolation::kCubic);
  for (double t : {0.1, 0.25, 0.5}) {
    const PathPoint p = traj.at(t);
    EXPECT_LT((p.X_WB.translation() - v * t).norm(), 1e-15);
    EXPECT_LT((p.v_WBo - v).norm(), 1e-14);
    EXPECT_LT((p.w_WB - w).norm(), 1e-12);
  }
}

TEST(Trajectory, HoldsTheLastPoseAtRest) {
  const TrajectoryRows rows = wobble(true);
  const Trajectory traj(rows, Interpolation::kCubic);
  const PathPoint p = traj.at(0.9);
  EXPECT_EQ(p.X_WB.translation(), rows.p_WB.back());
  EXPECT_EQ(p.v_WBo, Eigen::Vector3d::Zero());
  EXPECT_EQ(p.w_WB, Eigen::Vector3d::Zero());
}

TEST(Trajectory, RefusesBadRows) {
  TrajectoryRows rows = wobble(false);
  rows.t[2] = rows.t[1];
  EXPECT_THROW(Trajectory(rows, Interpolation::kCubic), InputError);
  EXPECT_THROW(Trajectory(wobble(true), Interpolation::kLinear), InputError);
}

// J_r and its inverse are inverses, and J_r maps ṙ to the body angular velocity of Exp(r).
TEST(Trajectory, RightJacobian) {
  const Eigen::Vector3d r(0.4, -1.1, 0.7), r_dot(0.3, 0.2, -0.5);
  EXPECT_LT((rightJacobian(r) * rightJacobianInverse(r) - Eigen::Matrix3d::Identity()).norm(),
            1e-14);
  const double h = 1e-6;  // central difference, error ~h² (see expectConsistent)
  const Eigen::Matrix3d R0 = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  const Eigen::Vector3d ra = r - h * r_dot, rb = r + h * r_dot;
  const Eigen::Matrix3d Ra = Eigen::AngleAxisd(ra.norm(), ra.normalized()).toRotationMatrix();
  const Eigen::Matrix3d Rb = Eigen::AngleAxisd(rb.norm(), rb.normalized()).toRotationMatrix();
  const Eigen::Matrix3d W = R0.transpose() * (Rb - Ra) / (2.0 * h);
  EXPECT_LT((Eigen::Vector3d(W(2, 1), W(0, 2), W(1, 0)) - rightJacobian(r) * r_dot).norm(), 1e-8);
}

}  // namespace
}  // namespace vcontact::dynamics
