#include "dynamics/loads.hpp"

#include <algorithm>
#include <cmath>

namespace vcontact::dynamics {
namespace {

// Scales v down to length `limit` when longer (a saturated drive keeps its direction).
Eigen::Vector3d limited(const Eigen::Vector3d& v, double limit) {
  const double n = v.norm();
  return n > limit ? Eigen::Vector3d(v * (limit / n)) : v;
}

// Below this length (m) a spring has no direction: its points coincide to round-off of a
// metre-scale coordinate, and it pulls along no line.
constexpr double kCoincident = 1e-12;

// φ such that Exp(φ) R_from = R_to: the rotation vector from one attitude to another, world.
Eigen::Vector3d rotationFromTo(const Eigen::Matrix3d& R_from, const Eigen::Matrix3d& R_to) {
  return rotationVector(Eigen::Quaterniond(R_to * R_from.transpose()));
}

LoadOutput driveWrench(const ExternalLoad& load, const BodyKinematics& k, double t) {
  const TargetDrive& d = load.drive;
  const PathPoint target = prescribedPath(d.X_WT0, d.motion, t);
  const Eigen::Matrix3d R_WT = target.X_WB.linear();
  LoadOutput out;
  out.p_W = k.X_WB * load.p_BP;
  // where P is to be: P's place in the target frame
  const Eigen::Vector3d p_goal = target.X_WB * load.p_BP;
  const Eigen::Vector3d v_goal =
      target.v_WBo + target.w_WB.cross(p_goal - target.X_WB.translation());
  const Eigen::Vector3d e_T = R_WT.transpose() * (p_goal - out.p_W);
  const Eigen::Vector3d e_dot_T = R_WT.transpose() * (v_goal - k.pointVelocity(out.p_W));
  const Eigen::Vector3d f_T = d.stiffness.cwiseProduct(e_T) + d.damping.cwiseProduct(e_dot_T);
  out.wrench.f_W = limited(R_WT * f_T, d.max_force);
  const Eigen::Vector3d phi_T = R_WT.transpose() * rotationFromTo(k.X_WB.linear(), R_WT);
  const Eigen::Vector3d phi_dot_T = R_WT.transpose() * (target.w_WB - k.w_WB);
  const Eigen::Vector3d tau_T =
      d.torsional_stiffness.cwiseProduct(phi_T) + d.torsional_damping.cwiseProduct(phi_dot_T);
  out.wrench.tau_W = limited(R_WT * tau_T, d.max_torque);
  return out;
}

}  // namespace

Wrench WrenchTable::at(double time) const {
  if (time <= t.front()) return {f_W.front(), tau_W.front()};
  if (time >= t.back()) return {f_W.back(), tau_W.back()};
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
  const double s = (time - t[i]) / (t[i + 1] - t[i]);
  return {f_W[i] + s * (f_W[i + 1] - f_W[i]), tau_W[i] + s * (tau_W[i + 1] - tau_W[i])};
}

LoadOutput loadWrench(const ExternalLoad& load, const BodyKinematics& k, double t) {
  if (load.kind == LoadKind::kDrive) return driveWrench(load, k, t);
  LoadOutput out;
  out.p_W = k.X_WB * load.p_BP;
  out.wrench = load.kind == LoadKind::kTable ? load.table->at(t) : load.constant;
  return out;
}

LoadOutput springWrench(const BodySpring& s, const BodyKinematics& ka, const BodyKinematics& kb) {
  LoadOutput out;
  out.p_W = ka.X_WB * s.p_AP;
  out.q_W = kb.X_WB * s.p_BQ;
  const Eigen::Vector3d d = out.q_W - out.p_W;  // from a's point to b's
  const double length = d.norm();
  if (length > kCoincident) {
    const Eigen::Vector3d u = d / length;
    const double rate = u.dot(kb.pointVelocity(out.q_W) - ka.pointVelocity(out.p_W));
    // stretched (length > rest) or opening: a is pulled towards b
    out.wrench.f_W = (s.stiffness * (length - s.rest_length) + s.damping * rate) * u;
  }
  // B's attitude away from where the rest rotation would put it, seen from A
  const Eigen::Matrix3d R_rest = ka.X_WB.linear() * s.q_AB_rest.toRotationMatrix();
  const Eigen::Vector3d phi = rotationFromTo(R_rest, kb.X_WB.linear());
  out.wrench.tau_W = s.torsional_stiffness * phi + s.torsional_damping * (kb.w_WB - ka.w_WB);
  return out;
}

double springEnergy(const BodySpring& s, const BodyKinematics& ka, const BodyKinematics& kb) {
  const double stretch = (kb.X_WB * s.p_BQ - ka.X_WB * s.p_AP).norm() - s.rest_length;
  const Eigen::Matrix3d R_rest = ka.X_WB.linear() * s.q_AB_rest.toRotationMatrix();
  const Eigen::Vector3d phi = rotationFromTo(R_rest, kb.X_WB.linear());
  return 0.5 * s.stiffness * stretch * stretch + 0.5 * s.torsional_stiffness * phi.squaredNorm();
}

}  // namespace vcontact::dynamics
