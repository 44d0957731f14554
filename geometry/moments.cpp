#include "geometry/moments.hpp"

namespace vcontact::geometry {

Eigen::Matrix3d Moments::centralSecondMoment() const {
  const Eigen::Vector3d c = centroid();
  return m2 - m0 * c * c.transpose();
}

Eigen::Matrix3d Moments::centralInertia() const {
  const Eigen::Matrix3d S = centralSecondMoment();
  return S.trace() * Eigen::Matrix3d::Identity() - S;
}

Moments transformed(const Moments& M, const Eigen::Isometry3d& X_FM) {
  const Eigen::Matrix3d R = X_FM.linear();
  const Eigen::Vector3d t = X_FM.translation();
  const Eigen::Vector3d Rm1 = R * M.m1;
  Moments F;
  F.m0 = M.m0;
  F.m1 = Rm1 + t * M.m0;
  F.m2 = R * M.m2 * R.transpose() + Rm1 * t.transpose() + t * Rm1.transpose() +
         M.m0 * t * t.transpose();
  return F;
}

Moments tetrahedronMoments(const Eigen::Vector3d& o, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Work relative to o so that small tetrahedra far from the frame origin keep their digits.
  const Eigen::Vector3d u = a - o, v = b - o, w = c - o;
  const double D = u.dot(v.cross(w));  // 6 × signed volume
  const Eigen::Vector3d s = u + v + w;
  Moments local;
  local.m0 = D / 6.0;
  local.m1 = (D / 24.0) * s;
  // ∫ x xᵀ over the tetrahedron (0, u, v, w) = V/20 (Σ_k p_k p_kᵀ + s sᵀ), V = D/6.
  local.m2 =
      (D / 120.0) * (u * u.transpose() + v * v.transpose() + w * w.transpose() + s * s.transpose());
  Moments M;
  M.m0 = local.m0;
  M.m1 = local.m1 + o * local.m0;
  M.m2 =
      local.m2 + o * local.m1.transpose() + local.m1 * o.transpose() + local.m0 * o * o.transpose();
  return M;
}

}  // namespace vcontact::geometry
