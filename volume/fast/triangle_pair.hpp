#pragma once
// The triangle-pair and box tests of the exact mesh–mesh intersection
// (fast/surface_integration.hpp, step 1): faces placed in W, their boxes, the sides of one face's
// corners against the other's plane (a double filter with orient3d's rounding bound) and the
// Guigue–Devillers interval test. Each test answers "certainly apart" or "maybe": a pair is dropped
// only when it certainly misses, so the exact predicates of step 2 see every pair that could cross.

#include <Eigen/Geometry>
#include <cassert>
#include <limits>
#include <utility>

#include "volume/kernels/exact_predicates.hpp"

namespace vcontact::volume::internal {

/// A double orient3d det[u, v, w] of rounded differences is within this factor times
/// ‖u‖₁‖v‖₁‖w‖₁ (≥ the permanent) of the exact value: ≈ 8ε from the differences, products
/// and sums (Shewchuk 1997 bounds orient3d by 7ε of the permanent); 32ε for margin.
constexpr double kOrientBound = 32.0 * std::numeric_limits<double>::epsilon();

/// A face placed in W for one query, with what the face-pair tests use of it.
struct PlacedFace {
  Eigen::Vector3d corner[3];  ///< W
  Eigen::Vector3d n;          ///< (c1 − c0) × (c2 − c0), unnormalised
  double nBound;              ///< kOrientBound·‖c1 − c0‖₁‖c2 − c0‖₁ (planeSides)
  Eigen::Vector3d lo, hi;     ///< axis-aligned box in W
};

/// Face (c0, c1, c2) placed in W: its corners, unnormalised normal, rounding bound and box.
inline PlacedFace placedFace(const Eigen::Vector3d& c0, const Eigen::Vector3d& c1,
                             const Eigen::Vector3d& c2) {
  PlacedFace F;
  F.corner[0] = c0;
  F.corner[1] = c1;
  F.corner[2] = c2;
  const Eigen::Vector3d u = F.corner[1] - F.corner[0], v = F.corner[2] - F.corner[0];
  F.n = u.cross(v);
  F.nBound = kOrientBound * u.lpNorm<1>() * v.lpNorm<1>();
  F.lo = F.corner[0].cwiseMin(F.corner[1]).cwiseMin(F.corner[2]);
  F.hi = F.corner[0].cwiseMax(F.corner[1]).cwiseMax(F.corner[2]);
  return F;
}

/// Side of the plane of triangle T each point P[i] lies on, judged in double with the
/// rounding bound of orient3d: +1 or −1 when certain (the exact sign then agrees and no
/// perturbation is involved), 0 when within rounding of the plane.
/// @return +1 or −1 when all three are certainly on that side, else 0
inline int planeSides(const PlacedFace& T, const Eigen::Vector3d* P, int* side) {
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d w = P[i] - T.corner[0];
    const double d = T.n.dot(w);
    const double bound = T.nBound * w.lpNorm<1>();
    side[i] = int(d > bound) - int(d < -bound);  // without branches: the sign is data
  }
  return (side[0] == side[1]) & (side[1] == side[2]) ? side[0] : 0;
}

inline bool allCertain(const int* side) { return side[0] * side[1] * side[2] != 0; }

/// Index of the corner whose side differs from the other two's. @pre not all three equal
inline int loneCorner(const int* side) {
  assert(!(side[0] == side[1] && side[1] == side[2]));
  return side[0] == side[1] ? 2 : (side[0] == side[2] ? 1 : 0);
}

/// Are two triangles, each with corners certainly on both sides of the other's plane, certainly
/// disjoint? Guigue & Devillers 2003 ("Fast and robust triangle-triangle overlap test using
/// orientation predicates"): with the corners named so that p1 is alone on the positive side of
/// (p2, q2, r2) and p2 alone on the positive side of (p1, q1, r1) (a cyclic shift keeps a
/// triangle's plane, swapping its last two corners flips it), the triangles meet iff
/// orient3d(q1, p2, p1, q2) ≤ 0 and orient3d(p1, p2, r1, r2) ≤ 0: the two segments
/// tᵢ ∩ plane(tⱼ) overlap on the planes' common line. Only a certain positive sign (the double
/// filter) rejects, so a rejected pair is disjoint exactly and, every sign used being non-zero,
/// also under the perturbation: none of its edge–face tests could report a crossing.
/// @param sideA, sideB  certain sides (±1, none 0, not all equal) of A's corners against B's
///   plane and of B's against A's
inline bool certainlyDisjoint(const Eigen::Vector3d* A, const int* sideA, const Eigen::Vector3d* B,
                              const int* sideB) {
  const int i = loneCorner(sideA);
  const Eigen::Vector3d* T1[3] = {&A[i], &A[(i + 1) % 3], &A[(i + 2) % 3]};
  int b[3] = {0, 1, 2};                     // B's corners in T2's order
  if (sideA[i] < 0) std::swap(b[1], b[2]);  // flip T2 so that p1 is on its positive side
  const int sideT2[3] = {sideB[b[0]], sideB[b[1]], sideB[b[2]]};
  const int j = loneCorner(sideT2);
  const Eigen::Vector3d& p2 = B[b[j]];
  const Eigen::Vector3d& q2 = B[b[(j + 1) % 3]];
  const Eigen::Vector3d& r2 = B[b[(j + 2) % 3]];
  if (sideT2[j] < 0) std::swap(T1[1], T1[2]);  // flip T1 so that p2 is on its positive side
  const Eigen::Vector3d &p1 = *T1[0], &q1 = *T1[1], &r1 = *T1[2];
  return orient3dFiltered(q1, p2, p1, q2) > 0 || orient3dFiltered(p1, p2, r1, r2) > 0;
}

/// Are all three of a ≤ b? Evaluated without short-circuit branches: in the descent the
/// outcome is data, and one branch on the combined flag mispredicts less than three.
inline bool allLessEqual(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a.x() <= b.x()) & (a.y() <= b.y()) & (a.z() <= b.z());
}

/// The faces' axis-aligned boxes overlap (grown by `margin`)?
inline bool faceBoxesOverlap(const PlacedFace& A, const PlacedFace& B, double margin) {
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(margin);
  return allLessEqual(A.lo, B.hi + grow) & allLessEqual(B.lo, A.hi + grow);
}

/// Axis-aligned box of a body-frame box placed by X (conservative), as {centre, half-size}.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> placedBox(const Eigen::Isometry3d& X,
                                                             const Eigen::Vector3d& center,
                                                             const Eigen::Vector3d& half) {
  return {X * center, X.linear().cwiseAbs() * half};
}

/// Do two boxes {centre, half-sizes} of one frame overlap when grown by `grow` on every side?
/// Forced inline: the descent's node test (out of line it costs 2–3 % of a query).
[[gnu::always_inline]] inline bool boxesOverlap(const Eigen::Vector3d& centerA,
                                                const Eigen::Vector3d& halfA,
                                                const Eigen::Vector3d& centerB,
                                                const Eigen::Vector3d& halfB, double grow) {
  return allLessEqual((centerA - centerB).cwiseAbs(),
                      halfA + halfB + Eigen::Vector3d::Constant(grow));
}

/// Segment p0 + t (p1 − p0), t ∈ [0, 1], meets the box (centre c, half-sizes h)?
bool segmentMeetsBox(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& h);

}  // namespace vcontact::volume::internal
