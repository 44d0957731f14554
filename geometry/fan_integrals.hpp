#pragma once
// Surface integrals of an open set of triangles S that give, for ANY apex o, the moments of the
// fan of tetrahedra (o, a, b, c) over the triangles of S in O(1).
//
// Derivation (cone formula). Let x = p − o. For a function f homogeneous of degree k in x,
// div(x f) = (3 + k) f, and on the lateral faces of the cone from o over a triangle T the
// normal is orthogonal to x, so the divergence theorem gives
//     ∫_cone f dV = 1/(3 + k) ∫_T f (x·n) dA.
// Hence, with moments taken about o,
//     M0 = 1/3 ∫_S (x·n) dA,  M1 = 1/4 ∫_S x (x·n) dA,  M2 = 1/5 ∫_S x xᵀ (x·n) dA.
// For a closed surface these do not depend on o; for an open S they do, which is why a node
// of a bounding-volume tree cannot simply cache Moments. Write x = y + δ with y = p − r about
// a fixed reference r of S and δ = r − o, and store, about r,
//     E = ∫ y·n,  F = ∫ n,  C = ∫ y (y·n),  D = ∫ y nᵀ,  B_k = ∫ y yᵀ n_k,  A = ∫ y yᵀ (y·n).
// Expanding x·n = y·n + δ·n and x xᵀ = y yᵀ + y δᵀ + δ yᵀ + δ δᵀ:
//     ∫ x·n        = E + δ·F
//     ∫ x (x·n)    = C + D δ + δ (E + δ·F)
//     ∫ x xᵀ (x·n) = A + Σ_k δ_k B_k + C δᵀ + δ Cᵀ + (D δ) δᵀ + δ (D δ)ᵀ + δ δᵀ (E + δ·F).
// Every term is of the size of S and |δ|, so nothing cancels when S and o are small and far
// from the body origin (the reason the clip works about a local origin, MODEL.md §1).
// Per triangle, E, C and A are 3, 4 and 5 times the moments of the tetrahedron (r, a, b, c)
// about r; F = N/2 (N = (b − a) × (c − a)); D = A_T ȳ nᵀ; B_k = n_k ∫_T y yᵀ dA.

#include <Eigen/Core>
#include <array>

#include "geometry/moments.hpp"

namespace vcontact::geometry {

struct FanIntegrals {
  double E = 0.0;                               ///< ∫ y·n dA, m³
  Eigen::Vector3d F = Eigen::Vector3d::Zero();  ///< ∫ n dA, m²
  Eigen::Vector3d C = Eigen::Vector3d::Zero();  ///< ∫ y (y·n) dA, m⁴
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();  ///< ∫ y nᵀ dA, m³
  std::array<Eigen::Matrix3d, 3> B{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                   Eigen::Matrix3d::Zero()};  ///< ∫ y yᵀ n_k dA, m⁴
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();                ///< ∫ y yᵀ (y·n) dA, m⁵

  FanIntegrals& operator+=(const FanIntegrals& o);
};

/// Integrals of the triangle (a, b, c) (counter-clockwise seen from outside), with y = p − r.
/// Inputs are already relative to the reference r.
FanIntegrals triangleFanIntegrals(const Eigen::Vector3d& a_r, const Eigen::Vector3d& b_r,
                                  const Eigen::Vector3d& c_r);

/// Moments, about o, of the fan with apex o over S, where delta = r − o is expressed in the
/// same axes as the integrals (see the derivation above).
Moments fanMoments(const FanIntegrals& S, const Eigen::Vector3d& delta);

}  // namespace vcontact::geometry
