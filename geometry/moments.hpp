#pragma once
// Volume moments of a solid up to second order:
//   m0 = ∫ dV,  m1 = ∫ p dV,  m2 = ∫ p pᵀ dV   (p in the frame the moments are expressed in).
// They add over disjoint pieces and transform exactly under a rigid motion, which is what lets
// bounding-volume nodes cache them and lets every backend report through one struct.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vcontact::geometry {

struct Moments {
  double m0 = 0.0;                                 ///< m³
  Eigen::Vector3d m1 = Eigen::Vector3d::Zero();    ///< m⁴
  Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();    ///< m⁵ (symmetric)

  Moments& operator+=(const Moments& o) {
    m0 += o.m0;
    m1 += o.m1;
    m2 += o.m2;
    return *this;
  }
  friend Moments operator+(Moments a, const Moments& b) { return a += b; }
  Moments& operator*=(double s) {
    m0 *= s;
    m1 *= s;
    m2 *= s;
    return *this;
  }

  /// Centroid ∫p dV / V. @pre m0 > 0.
  Eigen::Vector3d centroid() const { return m1 / m0; }
  /// Central second moment Σ = ∫ ρρᵀ dV with ρ = p − centroid.
  Eigen::Matrix3d centralSecondMoment() const;
  /// Inertia tensor about the centroid for unit density: tr(Σ) I − Σ.
  Eigen::Matrix3d centralInertia() const;
};

/// Moments re-expressed in frame F given the moments in frame M and X_FM (p_F = X_FM p_M):
///   m1_F = R m1 + t m0,   m2_F = R m2 Rᵀ + (R m1) tᵀ + t (R m1)ᵀ + m0 t tᵀ.
Moments transformed(const Moments& M, const Eigen::Isometry3d& X_FM);

/// Signed moments of the tetrahedron (o, a, b, c); positive when (a−o, b−o, c−o) is
/// right-handed. Summed over the faces of a closed, outward-oriented mesh with any fixed o
/// they give the moments of the solid (divergence theorem; Tonon 2004, eqs. 2–15).
Moments tetrahedronMoments(const Eigen::Vector3d& o, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace vcontact::geometry
