#include "volume/kernels/exact_predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>
#include <limits>

namespace vcontact::volume {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Eigen::Vector3d;

Kernel::Point_3 point(const Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// Exact sign of component k of (u1 − u0) × (w1 − w0): u_i w_j − u_j w_i with (k, i, j)
/// cyclic. A double evaluation decides when it clears its error bound (the orient2d bound
/// of Shewchuk 1997, (3 + 16ε)ε of the permanent, rounded up to 4ε); rationals otherwise.
int crossComponentSign(const Vector3d& u0, const Vector3d& u1, const Vector3d& w0,
                       const Vector3d& w1, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double l = (u1[i] - u0[i]) * (w1[j] - w0[j]);
  const double r = (u1[j] - u0[j]) * (w1[i] - w0[i]);
  const double bound = 4.0 * std::numeric_limits<double>::epsilon() * (std::abs(l) + std::abs(r));
  if (l - r > bound) return 1;
  if (r - l > bound) return -1;
  using Q = CGAL::Exact_rational;
  const Q det =
      (Q(u1[i]) - Q(u0[i])) * (Q(w1[j]) - Q(w0[j])) - (Q(u1[j]) - Q(u0[j])) * (Q(w1[i]) - Q(w0[i]));
  return CGAL::sign(det);
}

/// Sign of D₀ + s·g·τ with τ = (ε, ε², ε³): D₀'s sign when it is not zero, else that of the
/// first non-zero component of s·g, g = (u1 − u0) × (w1 − w0).
int perturbedSign(int d0, const Vector3d& u0, const Vector3d& u1, const Vector3d& w0,
                  const Vector3d& w1, int s) {
  if (d0 != 0) return d0;
  for (int k = 0; k < 3; ++k) {
    if (const int g = crossComponentSign(u0, u1, w0, w1, k); g != 0) return s * g;
  }
  return 0;
}

/// orient3d(a, b, c, p + sτ) = D₀ + s τ·((b − a) × (c − a)).
int perturbedPointSide(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& p,
                       int s) {
  return perturbedSign(orient3d(a, b, c, p), a, b, a, c, s);
}

/// orient3d(p + sτ, q + sτ, a, b) = D₀ + s τ·((q − p) × (b − a)): the side of the line
/// through the edge (a, b) the segment's line passes (derivation: expand the determinant
/// det[q − p, a − p − sτ, b − p − sτ], whose τ² term vanishes).
int perturbedLineSide(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b,
                      int s) {
  return perturbedSign(orient3d(p, q, a, b), p, q, a, b, s);
}

}  // namespace

int orient3d(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  // The semi-static filter first: most calls end there, without the rounding-mode switches
  // of CGAL's interval filter, which then decides exactly.
  if (const int s = orient3dFiltered(a, b, c, d); s != 0) return s;
  return static_cast<int>(CGAL::orientation(point(a), point(b), point(c), point(d)));
}

int perturbedSegmentCrossing(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                             const Vector3d& b, const Vector3d& c, int s, int knownP, int knownQ) {
  assert(!Vector3d((b - a).cross(c - a)).isZero(0.0));
  const int sp = knownP != 0 ? knownP : perturbedPointSide(a, b, c, p, s);
  const int sq = knownQ != 0 ? knownQ : perturbedPointSide(a, b, c, q, s);
  // Both ends share the translation, so an edge lying in the plane stays on one side.
  if (sp == 0 || sp == sq) return 0;
  // The segment now crosses the plane transversally, so it is parallel to no edge of the
  // triangle and the three line sides below are never 0.
  const int s1 = perturbedLineSide(p, q, a, b, s);
  if (perturbedLineSide(p, q, b, c, s) != s1 || perturbedLineSide(p, q, c, a, s) != s1) return 0;
  return sp;
}

}  // namespace vcontact::volume
