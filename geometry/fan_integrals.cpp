#include "geometry/fan_integrals.hpp"

namespace vcontact::geometry {

FanIntegrals& FanIntegrals::operator+=(const FanIntegrals& o) {
  E += o.E;
  F += o.F;
  C += o.C;
  D += o.D;
  for (int k = 0; k < 3; ++k) B[k] += o.B[k];
  A += o.A;
  return *this;
}

FanIntegrals triangleFanIntegrals(const Eigen::Vector3d& a_r, const Eigen::Vector3d& b_r,
                                  const Eigen::Vector3d& c_r) {
  const Moments cone = tetrahedronMoments(Eigen::Vector3d::Zero(), a_r, b_r, c_r);
  const Eigen::Vector3d areaVector = 0.5 * (b_r - a_r).cross(c_r - a_r);  // A_T n
  const Eigen::Vector3d s = a_r + b_r + c_r;
  // ∫_T y yᵀ dA = A_T/12 (Σ_k v_k v_kᵀ + s sᵀ); times n_k uses the area vector directly.
  const Eigen::Matrix3d yy =
      (a_r * a_r.transpose() + b_r * b_r.transpose() + c_r * c_r.transpose() + s * s.transpose()) /
      12.0;
  FanIntegrals T;
  T.E = 3.0 * cone.m0;
  T.F = areaVector;
  T.C = 4.0 * cone.m1;
  T.D = (s / 3.0) * areaVector.transpose();
  for (int k = 0; k < 3; ++k) T.B[k] = areaVector[k] * yy;
  T.A = 5.0 * cone.m2;
  return T;
}

Moments fanMoments(const FanIntegrals& S, const Eigen::Vector3d& delta) {
  const double xn = S.E + delta.dot(S.F);  // ∫ x·n
  const Eigen::Vector3d Dd = S.D * delta;
  Eigen::Matrix3d xxxn = S.A + S.C * delta.transpose() + delta * S.C.transpose() +
                         Dd * delta.transpose() + delta * Dd.transpose() +
                         xn * delta * delta.transpose();
  for (int k = 0; k < 3; ++k) xxxn += delta[k] * S.B[k];
  Moments M;
  M.m0 = xn / 3.0;
  M.m1 = (S.C + Dd + xn * delta) / 4.0;
  M.m2 = xxxn / 5.0;
  return M;
}

}  // namespace vcontact::geometry
