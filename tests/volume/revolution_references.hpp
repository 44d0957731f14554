#pragma once
// Closed forms and references of solids of revolution on a plate, shared by the tests of the
// slices (revolution_on_plane_test), of the recovered profiles (recovered_revolution_body_test), of
// the refinement (recovered_refinement_test), of the recovered sphere (recovered_surface_test)
// and of the pin in a bore (recovered_bore_pair_test).

#include <cmath>

#include "geometry/tessellate.hpp"

namespace vcontact::test {

/// Area of a circular segment of height h on a circle of radius ρ (0 for h ≤ 0), stable for
/// h ≪ ρ: acos(1 − x) = 2 asin(√(x/2)).
inline double segment(double rho, double h) {
  if (h <= 0.0) return 0.0;
  return rho * rho * 2.0 * std::asin(std::sqrt(h / (2.0 * rho))) -
         (rho - h) * std::sqrt(h * (2.0 * rho - h));
}

/// Volume of the cap of height d of a sphere of radius R.
inline double sphereCap(double R, double d) { return M_PI * d * d * (3.0 * R - d) / 3.0; }

/// A pin of radius r and length L along z from z = 0, with 45° chamfers c at both ends,
/// `segments` around.
inline geometry::TriangleMesh chamferedPin(double r, double L, double c, int segments = 64) {
  return geometry::tessellateRevolution({{r - c, 0.0}, {r, c}, {r, L - c}, {r - c, L}}, segments);
}

/// V of that pin lying on its side, pressed d < c into a plate: the straight part's segment
/// times its length, and each chamfer, whose section at t from the rim is a segment of height
/// d − t on radius r − t (45°), integrated by Simpson's rule on 20,000 intervals after the
/// substitution t = d(1 − u²), which removes the (d − t)^{3/2} end behaviour (error < 1e-9).
inline double pinOnItsSide(double r, double L, double c, double d) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    const double t = d * (1.0 - u * u);
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * segment(r - t, d - t) * 2.0 * d * u;  // dt = 2 d u du
  }
  return (L - 2.0 * c) * segment(r, d) + 2.0 * sum / (3.0 * n);
}

/// The part of a pin's disk (radius r, centre at e from the bore's) outside the bore's disk
/// (radius R): 0 when the disk lies inside the bore (r + e ≤ R); otherwise, with the circles
/// crossing (|r − R| < e < r + R), beyond the chord through their crossings the pin's segment
/// (height h_B + d, d = r + e − R) less the bore's (height h_B = (r − R + e)(r + R − e)/(2e)),
/// written without the cancellation of πr² − lens at d ≪ r.
inline double pinOutsideBore(double r, double R, double e) {
  if (r + e <= R) return 0.0;
  const double hB = (r - R + e) * (r + R - e) / (2.0 * e);
  return segment(r, hB + (r + e - R)) - segment(R, hB);
}

/// V of the pin of chamferedPin (its axis at e from the bore's and parallel to it) between
/// ζ = a and b along its own axis (L − c < b): the straight part's pinOutsideBore times its
/// length in [a, L − c], and the top chamfer's slices (radius r − (ζ − L + c)), whose crescent
/// vanishes at ζ_v = L − c + d (d = r + e − R), by Simpson's rule on 20,000 intervals after
/// ζ = ζ_v − d u², which removes the (ζ_v − ζ)^{3/2} end behaviour.
inline double chamferedPinInBore(double r, double L, double c, double R, double e, double a,
                                 double b) {
  const double d = r + e - R, top = L - c, zv = top + d;
  const double straight = (top - a) * pinOutsideBore(r, R, e);
  const double uLo = b < zv ? std::sqrt((zv - b) / d) : 0.0;
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = uLo + (1.0 - uLo) * i / n, zeta = zv - d * u * u;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * pinOutsideBore(r - (zeta - top), R, e) * 2.0 * d * u;  // |dζ| = 2 d u du
  }
  return straight + (1.0 - uLo) * sum / (3.0 * n);
}

}  // namespace vcontact::test
