#pragma once
// Exact orientation predicates for the mesh–mesh intersection, with a symbolic perturbation
// that makes every configuration generic (Edelsbrunner & Mücke 1990, "Simulation of
// Simplicity", here in its translation form).
//
// Body A is moved by the infinitesimal translation τ = (ε, ε², ε³), 0 < ε → 0, relative to
// body B. Every orientation this module evaluates mixes points of both bodies and is affine
// in τ, D(τ) = D₀ + g·τ, so its sign is sign(D₀) when D₀ ≠ 0 and otherwise the sign of the
// first non-zero component of g (all evaluated exactly). Faces that touch exactly, coplanar
// faces and a vertex exactly on a face therefore all get a definite, consistent answer: the
// one they have in the configuration of A + τ against B, whose intersection's moments tend
// to those of A ∩ B as ε → 0 (the moments are continuous under translation).
//
// Signs: orient3d(a, b, c, d) = sign(((b − a) × (c − a))·(d − a)): +1 when d is on the side
// the normal of the counter-clockwise triangle (a, b, c) points to (outside, for a face of an
// outward-oriented mesh). CGAL types stay in the .cpp (ARCHITECTURE.md).

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace vcontact::volume {

/// Sign of ((b − a) × (c − a))·(d − a) when a double evaluation certainly has it, else 0
/// (the semi-static filter of orient3d below; inline so that the callers' hot loops can
/// reject most cases without a call). The determinant of the rounded differences
/// u = b − a, v = c − a, w = d − a is within (7 + 56ε)ε of the permanent of the exact value
/// (Shewchuk 1997, orient3d errboundA, ε = 2⁻⁵³); 8·2⁻⁵² is used for margin.
inline int orient3dFiltered(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
  const double vywz = v.y() * w.z(), vzwy = v.z() * w.y();
  const double vzwx = v.z() * w.x(), vxwz = v.x() * w.z();
  const double vxwy = v.x() * w.y(), vywx = v.y() * w.x();
  const double det = u.x() * (vywz - vzwy) + u.y() * (vzwx - vxwz) + u.z() * (vxwy - vywx);
  const double permanent = std::abs(u.x()) * (std::abs(vywz) + std::abs(vzwy)) +
                           std::abs(u.y()) * (std::abs(vzwx) + std::abs(vxwz)) +
                           std::abs(u.z()) * (std::abs(vxwy) + std::abs(vywx));
  const double bound = 8.0 * std::numeric_limits<double>::epsilon() * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 0;
}

/// Exact sign (−1, 0, +1) of ((b − a) × (c − a))·(d − a) for the double coordinates given.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d);

/// How a segment (p, q) crosses a triangle (a, b, c) under the perturbation, where the
/// segment's body is moved by s·τ relative to the triangle's (s = +1 for a segment of A
/// against a triangle of B, s = −1 for a segment of B against a triangle of A).
/// @return 0 when the perturbed segment misses the perturbed triangle; +1 when it crosses
///   with p on the outer side (p → q enters the triangle's body); −1 when p is on the inner
///   side. Never 0 for a crossing: the perturbation leaves no touching case.
/// @pre (a, b, c) has non-zero area (a degenerate triangle is never crossed).
/// The answer is exact and depends only on the geometry, so the crossing of one edge with
/// one triangle is decided the same way by every caller.
/// @param knownP, knownQ  sign of orient3d(a, b, c, p) (resp. q) when the caller has already
///   established it (non-zero, e.g. by a filtered evaluation), else 0 to evaluate it here
int perturbedSegmentCrossing(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                             const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c, int s, int knownP = 0, int knownQ = 0);

/// perturbedSegmentCrossing for a segment whose ends are known to lie certainly on opposite
/// sides of the triangle's plane (knownP = −knownQ ≠ 0), the common case of the mesh–mesh
/// crossing test: the three sides of the segment's line against the triangle's edges are
/// first judged by the double filter (orient3dFiltered); two certain and different signs
/// mean a miss and three certain equal ones a crossing, both as the exact test decides, and
/// only an uncertain side takes the exact, perturbed path.
inline int perturbedSegmentCrossingStraddling(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                              const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              const Eigen::Vector3d& c, int s, int knownP) {
  const int ab = orient3dFiltered(p, q, a, b);
  const int bc = orient3dFiltered(p, q, b, c);
  if (ab * bc < 0) return 0;
  const int ca = orient3dFiltered(p, q, c, a);
  if (ab * ca < 0 || bc * ca < 0) return 0;
  if (ab != 0 && bc != 0 && ca != 0) return knownP;
  return perturbedSegmentCrossing(p, q, a, b, c, s, knownP, -knownP);
}

}  // namespace vcontact::volume
