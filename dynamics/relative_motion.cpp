#include "dynamics/relative_motion.hpp"

#include <cassert>
#include <cmath>

namespace vcontact::dynamics {
namespace {

// Every volume method normalises n; its length is 1 to a few ulps, far inside this.
[[maybe_unused]] constexpr double kUnitNormalTolerance = 1e-9;

}  // namespace

RelativeMotion relativeMotion(const BodyKinematics& A, const BodyKinematics& B,
                              const Eigen::Vector3d& p_WC) {
  return {A.pointVelocity(p_WC) - B.pointVelocity(p_WC), A.w_WB - B.w_WB, A.t};
}

ContactKinematics resolve(const RelativeMotion& motion, const Eigen::Vector3d& n_W) {
  assert(std::abs(n_W.norm() - 1.0) < kUnitNormalTolerance);
  const Eigen::Vector3d& v_c = motion.v_c_W;
  ContactKinematics k;
  k.delta_dot = -v_c.dot(n_W);
  k.v_t_W = v_c - v_c.dot(n_W) * n_W;
  k.omega_n = motion.w_W.dot(n_W);
  k.omega_t_W = motion.w_W - k.omega_n * n_W;
  return k;
}

}  // namespace vcontact::dynamics
