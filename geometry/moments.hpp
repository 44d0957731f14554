#pragma once
// Volume moments of a solid up to second order:
//   m0 = ∫ dV,  m1 = ∫ p dV,  m2 = ∫ p pᵀ dV   (p in the frame the moments are expressed in).
// They add over disjoint pieces and transform exactly under a rigid motion, which is what lets
// bounding-volume nodes cache them and lets every backend report through one struct.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vcontact::geometry {

struct Moments {
  double m0 = 0.0;                               ///< m³
  Eigen::Vector3d m1 = Eigen::Vector3d::Zero();  ///< m⁴
  Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();  ///< m⁵ (symmetric)

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

/// Running sum of the moments of tetrahedra (0, u, v, w) that share their apex, the inner
/// loop of the exact clips (volume/halfspace_clip, volume/mesh_mesh): the same moments as
/// tetrahedronMoments, kept as plain sums with the constant factors applied once at the end.
/// With D = u·(v × w) (6 × the signed volume) and s = u + v + w:
///   ∫ 1 dV = D/6,   ∫ x dV = (D/24) s,   ∫ x xᵀ dV = (D/120)(u uᵀ + v vᵀ + w wᵀ + s sᵀ).
class TetrahedronSum {
 public:
  /// Adds the tetrahedron (0, u, v, w); returns its D.
  double add(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
    const double D = u.dot(v.cross(w));
    const Eigen::Vector3d s = u + v + w;
    d_ += D;
    ds_ += D * s;
    const Eigen::Vector3d sq =
        u.cwiseProduct(u) + v.cwiseProduct(v) + w.cwiseProduct(w) + s.cwiseProduct(s);
    // the products of each coordinate with the next one: (x y, y z, z x)
    const auto next = [](const Eigen::Vector3d& a) { return Eigen::Vector3d(a.y(), a.z(), a.x()); };
    const Eigen::Vector3d mixed = u.cwiseProduct(next(u)) + v.cwiseProduct(next(v)) +
                                  w.cwiseProduct(next(w)) + s.cwiseProduct(next(s));
    diag_ += D * sq;
    off_ += D * mixed;
    return D;
  }

  /// The summed moments about the apex.
  Moments moments() const {
    Moments M;
    M.m0 = d_ / 6.0;
    M.m1 = ds_ / 24.0;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      M.m2(k, k) = diag_[k] / 120.0;
      M.m2(k, l) = M.m2(l, k) = off_[k] / 120.0;
    }
    return M;
  }

 private:
  double d_ = 0.0;
  Eigen::Vector3d ds_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d diag_ = Eigen::Vector3d::Zero();  ///< Σ D(u uᵀ + v vᵀ + w wᵀ + s sᵀ): xx, yy, zz
  Eigen::Vector3d off_ = Eigen::Vector3d::Zero();  ///< ... xy, yz, zx
};

}  // namespace vcontact::geometry
