// The faces' bands of a pin in a tilted bore (volume/recovered/pin_in_bore_bands.hpp,
// volume/recovered/pin_in_bore_slices.hpp): slice by slice across a band, the closed form of the
// disc less the ellipse cut by a face's line against a polar rule in long double; and the band's
// breakpoints against the conditions that define them (the line through a crossing of the
// circle and the ellipse, touching the circle or the ellipse).

#include "volume/recovered/pin_in_bore_bands.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "volume/analytic/circular_segment.hpp"
#include "volume/recovered/pin_in_bore_slices.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using LD = long double;
using V2 = Eigen::Matrix<LD, 2, 1>;

// The pin of the error table (r 5 mm) and the bundled block's bore (5.1 mm).
constexpr double kR = 0.005, kBore = 0.0051;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// The moments of the disc of radius r less the ellipse, on the side m·x ≤ k of one line, by
// Simpson's rule in ψ about the disc's centre (inside the ellipse): on the ray at ψ the region
// is ρ_E(ψ) ≤ ρ ≤ r cut to the line's side (a single interval), closed in ρ. Over ψ the
// integrand changes form only where the circle crosses the ellipse (crossingAngles) or the line
// crosses the circle or the ellipse (closed forms); Simpson's rule with 2000 intervals between each
// two such angles leaves ~2e-14 of the slice (4000 and 8000 agree to 1.3e-15 of the uncut
// crescent on the cases below, the error going as the fourth power). The circle's arcs in the
// region are closed forms
// between the same angles. In long double: r − ρ_E carries ε R of rounding in double, 2e-10 of a
// crescent 1e-6 r deep.
struct Polar {
  LD A = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0, Syy = 0, arcX = 0, arcY = 0, arcLength = 0;
};

// Where the ray at ψ leaves the ellipse (its larger root: the disc's centre inside it).
LD exitOf(const detail::SliceEllipse& E, LD psi) {
  const Eigen::Matrix<LD, 2, 2> Sinv = E.S.cast<LD>().inverse();
  const V2 d = Sinv * V2(std::cos(psi), std::sin(psi)), s = Sinv * E.c.cast<LD>();
  const LD R = E.R, a = d.squaredNorm(), b = -2.0L * d.dot(s), q = s.squaredNorm() - R * R;
  return (-b + std::sqrt(b * b - 4.0L * a * q)) / (2.0L * a);
}

// The angles where the circle of radius r crosses the ellipse: sign changes of ρ_E − r
// between 1024 rays (the crescents here span 0.3 rad or more), bisected 80 times.
std::vector<LD> crossingAngles(double r, const detail::SliceEllipse& E) {
  const LD psi0 = std::atan2(E.c.y(), E.c.x()), twoPi = 2.0L * M_PI;
  const auto g = [&](LD psi) { return exitOf(E, psi) - r; };
  std::vector<LD> out;
  const int n = 1024;
  for (int i = 0; i < n; ++i) {
    LD a = psi0 + twoPi * i / n, b = psi0 + twoPi * (i + 1) / n;
    if ((g(a) > 0.0L) == (g(b) > 0.0L)) continue;
    const bool posA = g(a) > 0.0L;
    for (int j = 0; j < 80; ++j) ((g(0.5L * (a + b)) > 0.0L) == posA ? a : b) = 0.5L * (a + b);
    out.push_back(0.5L * (a + b));
  }
  return out;
}

Polar polarCut(double r, const detail::SliceEllipse& E, const Vector2d& m, double k) {
  const Eigen::Matrix<LD, 2, 2> S = E.S.cast<LD>();
  const V2 c = E.c.cast<LD>(), ml = m.cast<LD>();
  const LD R = E.R, rl = r, kl = k;
  const auto exitAt = [&](LD psi) { return exitOf(E, psi); };
  const LD psi0 = std::atan2(c.y(), c.x()), twoPi = 2.0L * M_PI;
  std::vector<LD> cuts = {psi0, psi0 + twoPi};
  const auto addAngle = [&](LD psi) {  // into [ψ₀, ψ₀ + 2π)
    cuts.push_back(psi0 + std::fmod(std::fmod(psi - psi0, twoPi) + twoPi, twoPi));
  };
  for (LD psi : crossingAngles(r, E)) addAngle(psi);
  const LD mn = ml.norm(), alpha = std::atan2(ml.y(), ml.x());
  if (std::abs(kl) < rl * mn) {  // the line meets the circle at α ± acos(k/(r|m|))
    addAngle(alpha + std::acos(kl / (rl * mn)));
    addAngle(alpha - std::acos(kl / (rl * mn)));
  }
  const V2 a = S * ml;  // on the ellipse x = c + S y, |y| = R: a·y = k − m·c
  const LD h = (kl - ml.dot(c)) / a.norm();
  if (std::abs(h) < R) {
    const LD beta = std::atan2(a.y(), a.x()), turn = std::acos(h / R);
    for (LD y : {beta + turn, beta - turn}) {
      const V2 x = c + S * V2(R * std::cos(y), R * std::sin(y));
      addAngle(std::atan2(x.y(), x.x()));
    }
  }
  std::sort(cuts.begin(), cuts.end());
  Polar p;
  const int steps = 2000;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const LD w = (cuts[i + 1] - cuts[i]) / steps;
    for (int j = 0; j <= steps; ++j) {
      const LD psi = cuts[i] + w * j, cs = std::cos(psi), sn = std::sin(psi);
      const LD wt = ((j == 0 || j == steps) ? 1.0L : (j % 2 ? 4.0L : 2.0L)) * w / 3.0L;
      LD lo = exitAt(psi), hi = rl;
      const LD sm = ml.x() * cs + ml.y() * sn;
      if (sm > 0.0L) hi = std::min(hi, kl / sm);
      if (sm < 0.0L) lo = std::max(lo, kl / sm);
      if (sm == 0.0L && kl < 0.0L) hi = lo;
      if (!(hi > lo)) continue;
      const LD a2 = (hi * hi - lo * lo) / 2.0L, a3 = (hi * hi * hi - lo * lo * lo) / 3.0L;
      const LD a4 = (hi * hi * hi * hi - lo * lo * lo * lo) / 4.0L;
      p.A += wt * a2;
      p.Sx += wt * a3 * cs;
      p.Sy += wt * a3 * sn;
      p.Sxx += wt * a4 * cs * cs;
      p.Sxy += wt * a4 * cs * sn;
      p.Syy += wt * a4 * sn * sn;
    }
    // the circle's arc over the piece, in the region or not as its middle ray is
    const LD from = cuts[i], to = cuts[i + 1], mid = 0.5L * (from + to);
    const LD sm = ml.x() * std::cos(mid) + ml.y() * std::sin(mid);
    if (to > from && exitAt(mid) < rl && !(sm * rl > kl)) {
      p.arcX += rl * (std::sin(to) - std::sin(from));
      p.arcY += rl * (std::cos(from) - std::cos(to));
      p.arcLength += rl * (to - from);
    }
  }
  return p;
}

// The bore tilted by γ, the circle poking out of the ellipse by `ratio`·r at ζ = 0, and the
// block's face across the bore's axis through that slice's centre of the ellipse, its
// material on the side −side·axis (side = 1: the face is the block's top).
struct TiltedFace {
  Vector3d axis, point;
  BorePlane plane;
  TiltedFace(double gamma, double ratio, double side) {
    axis =
        Vector3d(std::sin(gamma) * std::cos(0.7), std::sin(gamma) * std::sin(0.7), std::cos(gamma));
    const double e = kBore / std::cos(gamma) - kR + ratio * kR;
    point = Vector3d(e * std::cos(-2.0), e * std::sin(-2.0), 0.0);
    plane = {side * axis, point};
  }
  // The band's ends in ζ: the line n·(x, y, ζ) = n·p touches the disc.
  double half() const { return kR * plane.normal_R.head<2>().norm() / std::abs(axis.z()); }
  double k(double zeta) const {
    return plane.normal_R.dot(plane.point_R) - plane.normal_R.z() * zeta;
  }
};

// Across the band of a face tilted 1 and 10 mrad from the slices, the crescent 1e-3 and 1e-2
// of r deep, either side of the face: 61 slices from just before the band to just after,
// each the closed form against polarCut. Tolerance: the uncut crescent's 1e-12 and its
// 8 ε R/d rounding (recovered_bore_pair_test's DiscLessEllipseIsThePolarRule) as a share of its
// area, and the rounding of Green's theorem: the cut region is a difference of sectors and
// triangles of up to r² (a dozen terms, for the disc's part and the ellipse's), 16 ε r²; times r^k
// for the moments.
TEST(AnalyticBoreBands, CutSlicesAreThePolarRule) {
  int compared = 0;
  for (double gamma : {1e-3, 1e-2})
    for (double ratio : {1e-3, 1e-2})
      for (double side : {1.0, -1.0}) {
        const TiltedFace f(gamma, ratio, side);
        const Vector2d m = f.plane.normal_R.head<2>();
        for (int i = 0; i <= 40; ++i) {
          const double zeta = f.half() * (-1.1 + 2.2 * i / 40.0);
          const detail::SliceEllipse E = detail::boreEllipse(f.point, f.axis, kBore, zeta);
          const Polar ref = polarCut(kR, E, m, f.k(zeta));
          detail::EllipseSlice uncut, got;
          ASSERT_TRUE(detail::discLessEllipse(kR, E, uncut)) << gamma << ' ' << ratio << ' ' << i;
          ASSERT_TRUE(detail::discLessEllipseCut(kR, E, {{m, f.k(zeta)}}, got))
              << gamma << ' ' << ratio << ' ' << i;
          const double tol =
              (1e-12 + 8.0 * kEps * kBore / (ratio * kR)) * uncut.A + 16.0 * kEps * kR * kR;
          const auto where = [&] {
            return ::testing::Message() << gamma << ' ' << ratio << ' ' << side << " slice " << i;
          };
          EXPECT_NEAR(got.A, static_cast<double>(ref.A), tol) << where();
          EXPECT_NEAR(got.Sx, static_cast<double>(ref.Sx), tol * kR) << where();
          EXPECT_NEAR(got.Sy, static_cast<double>(ref.Sy), tol * kR) << where();
          EXPECT_NEAR(got.Sxx, static_cast<double>(ref.Sxx), tol * kR * kR) << where();
          EXPECT_NEAR(got.Sxy, static_cast<double>(ref.Sxy), tol * kR * kR) << where();
          EXPECT_NEAR(got.Syy, static_cast<double>(ref.Syy), tol * kR * kR) << where();
          // the arcs, in closed form between the angles of both: the crossings' placement, as
          // the crescent's area, to 1e-12 and 8 ε R/d of the uncut arc
          const double arcTol = (1e-12 + 8.0 * kEps * kBore / (ratio * kR)) * uncut.arcLength;
          EXPECT_NEAR(got.arcLength, static_cast<double>(ref.arcLength), arcTol) << where();
          EXPECT_NEAR(got.arcX, static_cast<double>(ref.arcX), arcTol) << where();
          EXPECT_NEAR(got.arcY, static_cast<double>(ref.arcY), arcTol) << where();
          ++compared;
        }
      }
  EXPECT_EQ(compared, 8 * 41);
}

// A cylinder's piece across the band: the breakpoints are where the line touches the circle
// on the crescent's side (C) and the ellipse inside the disc (E), singular, and where it
// passes each of the two crossings (X, found here by crossingAngles, independent of the
// closed form's Newton), in the order C E X X as the line sweeps in from the crescent's side
// (X X E C in ascending ζ when it comes from the other). Residuals within 1e-12 r|m|: the
// crossings' rounding is ε R²/|f′| ~ 1e-14 rad at these crescents (1e-14 r|m| along m), the
// touchings' a few ε r|m|.
TEST(AnalyticBoreBands, BreakpointsAreTheLinesEvents) {
  for (double gamma : {1e-3, 1e-2})
    for (double side : {1.0, -1.0}) {
      const TiltedFace f(gamma, 1e-2, side);
      const ProfilePiece piece{ProfilePiece::Kind::kConstant, -0.01, 0.01, kR, kR};
      BoreSection bore;
      bore.point_R = f.point;
      bore.axis_R = f.axis;
      bore.radius = kBore;
      std::vector<detail::Breakpoint> got;
      detail::bandBreakpoints(piece, -0.01, 0.01, kR, bore, f.plane, got);
      std::sort(got.begin(), got.end(), [](auto& x, auto& y) { return x.t < y.t; });
      ASSERT_EQ(got.size(), 4u) << gamma << ' ' << side;
      const Vector2d m = f.plane.normal_R.head<2>();
      std::string kinds;
      for (const detail::Breakpoint& b : got) {
        const double k = f.k(b.t);
        const detail::SliceEllipse E = detail::boreEllipse(f.point, f.axis, kBore, b.t);
        double crossing = std::numeric_limits<double>::infinity();
        for (LD psi : crossingAngles(kR, E)) {
          const double q = static_cast<double>(psi);
          crossing =
              std::min(crossing, std::abs(k - m.dot(kR * Vector2d(std::cos(q), std::sin(q)))));
        }
        const std::array<double, 3> residual = {
            std::abs(std::abs(k) - kR * m.norm()),
            std::abs(std::abs(k - m.dot(E.c)) - kBore * (E.S * m).norm()), crossing};
        const auto best = std::min_element(residual.begin(), residual.end());
        EXPECT_LE(*best, 1e-12 * kR * m.norm()) << gamma << ' ' << side << ' ' << b.t;
        kinds += "CEX"[best - residual.begin()];
        EXPECT_EQ(b.singular, kinds.back() != 'X') << gamma << ' ' << side << ' ' << b.t;
      }
      EXPECT_TRUE(kinds == "CEXX" || kinds == "XXEC") << kinds << ' ' << gamma << ' ' << side;
    }
}

}  // namespace
}  // namespace vcontact::volume
