#pragma once
// The seam between geometry and forces (ARCHITECTURE.md): every volume backend fills this
// struct, every force model reads it. Definitions follow docs/MODEL.md §1.
//
// Frames: all quantities are in the world frame W. Body B1 ("a", the payload) and body B2
// ("b", the plate); the normal n points out of B2 into B1.

#include <Eigen/Core>
#include <limits>
#include <string>

namespace vcontact::volume {

enum class Method { kAnalytic, kHalfspace, kCgal, kFast, kColumns };

/// "analytic", "halfspace", "cgal", "fast", "columns".
std::string methodName(Method method);
/// Inverse of methodName; throws InputError naming the accepted values.
Method parseMethod(const std::string& name);

struct ContactVolume {
  double volume = 0.0;                                 ///< V, m³ (0: no contact)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< p_c, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< n, unit, out of B2 into B1
  Eigen::Matrix3d J_v = Eigen::Matrix3d::Zero();  ///< ∫((ρ·ρ)I − ρρᵀ)dV about p_c, m⁵
  Eigen::Matrix3d J_s = Eigen::Matrix3d::Zero();  ///< surface inertia tensor, m⁵
  double area = 0.0;                              ///< contact area A, m²
  double r_gyr = 0.0;                             ///< radius of gyration about n, m
  double depth = 0.0;                             ///< deepest penetration along n, m
  Method method = Method::kAnalytic;
  /// Estimated relative error of V from the method itself (quadrature, grid); NaN where the
  /// method is exact for the shapes it was given (closed forms, polyhedral clips).
  double relative_error = std::numeric_limits<double>::quiet_NaN();
  /// True when J_s was approximated by J_v (Boos); false when computed as defined.
  bool J_s_approximated = false;

  bool inContact() const { return volume > 0.0; }
};

/// Fills a ContactVolume from the region's central moments, all in W.
///   J_v = tr(Σ) I − Σ,  Σ = ∫ρρᵀ dV about p_c;
///   J_s = tr(Σ_s) I − Σ_s,  Σ_s = P Σ P,  P = I − n nᵀ
/// (the Winkler columns run along n, so ∫_S f(s) δ(s) dS = ∫_V f(P p) dV, MODEL.md §1);
///   r_gyr² = nᵀ J_s n / V.
/// @pre V > 0, n unit.
ContactVolume assembleContactVolume(double V, const Eigen::Vector3d& p_c,
                                    const Eigen::Matrix3d& Sigma, const Eigen::Vector3d& n,
                                    double area, double depth, Method method);

/// The same contact seen with the bodies swapped: the normal flips, nothing else changes.
ContactVolume swapped(ContactVolume cv);

}  // namespace vcontact::volume
