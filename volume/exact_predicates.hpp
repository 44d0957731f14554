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

namespace vcontact::volume {

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

}  // namespace vcontact::volume
