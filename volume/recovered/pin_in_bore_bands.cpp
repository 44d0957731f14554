#include "volume/recovered/pin_in_bore_bands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "volume/analytic/circular_segment.hpp"
#include "volume/recovered/pin_in_bore_slices.hpp"

namespace vcontact::volume::detail {
namespace {

using Eigen::Vector2d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Samples across the band between which a sign change of an event's function is sought. The
// line moves 1/|m| times faster than anything else in the slice (the ellipse's centre moves by
// tan γ a unit of ζ, a crossing point by as much over the crescent's angle), so each function
// is close to linear over the band and changes sign once; 8 intervals separate two changes
// unless a crescent's tips pass the line closer together than an eighth of the band.
constexpr int kBandSamples = 8;
constexpr int kFalsiSteps = 80;   // Illinois steps; each at least halves the bracket's far side
constexpr int kZetaSamples = 16;  // slices a piece between which the region's ends are sought
constexpr int kBisections = 45;   // a sixteenth of a piece to 1e-15 of it
// A region vanishing at a line's event is a sliver near it, whose area the closed form gives
// as rounding (±1e-20 m² for a 5 mm pin): bisection on its sign ends anywhere within ~1e-11
// of the piece. Within 1e-9 of the piece the two are taken for one: the sliver there is at
// most that length times areas of 1e-14 m² (1e-15 of V).
constexpr double kSnap = 1e-9;

// The events of the header, each a function of the slice whose sign changes at it.
enum Event { kCircleBelow, kCircleAbove, kEllipseBelow, kEllipseAbove, kCrossLo, kCrossHi };
constexpr int kEvents = 6;
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

struct Band {
  const ProfilePiece& p;
  const BoreSection& bore;
  Vector2d m;            // the plane's normal across the axis
  double nDotP, nz;      // k(ζ) = n·p − n_z ζ
  double mNorm, smNorm;  // |m|, |S m| (S the ellipse's stretch, the same in every slice)

  SliceEllipse ellipse(double zeta) const {
    return boreEllipse(bore.point_R, bore.axis_R, bore.radius, zeta);
  }
  // The events' functions at t: the line's offset k less the value of m·x at which it would
  // touch the circle (±r|m|) or the ellipse (m·c ± R|S m|), or pass a crossing (NaN where
  // no two crossings are certified). The crossings only `withCrossings`.
  std::array<double, kEvents> at(double t, bool withCrossings = true) const {
    const PieceAt e = pieceAt(p, t);
    const SliceEllipse E = ellipse(e.zeta);
    const double k = nDotP - nz * e.zeta, mc = m.dot(E.c), reach = E.R * smNorm;
    std::array<double, kEvents> g = {k + e.r * mNorm, k - e.r * mNorm, k - mc + reach,
                                     k - mc - reach,  kNone,           kNone};
    Vector2d lo, hi;
    if (withCrossings && circleCrossings(e.r, E, lo, hi)) {
      g[kCrossLo] = k - m.dot(lo);
      g[kCrossHi] = k - m.dot(hi);
    }
    return g;
  }
  // Whether the region changes form where event i's function vanishes at t: the touching
  // point lies on the crescent's boundary (outside the ellipse on the circle, inside the disc
  // on the ellipse); a crossing always does.
  bool changesForm(int i, double t) const {
    const PieceAt e = pieceAt(p, t);
    const SliceEllipse E = ellipse(e.zeta);
    const double side = (i == kCircleAbove || i == kEllipseAbove) ? 1.0 : -1.0;
    if (i == kCircleBelow || i == kCircleAbove) {
      const Vector2d x = side * e.r / mNorm * m;
      return (E.S.inverse() * (x - E.c)).norm() > E.R;
    }
    if (i == kEllipseBelow || i == kEllipseAbove) {
      const Vector2d x = E.c + side * E.R / smNorm * (E.S * (E.S * m));
      return x.norm() < e.r;
    }
    return true;
  }
};

// The root of g in (a, b), where g(a) = ga and g(b) = gb differ in sign: regula falsi with
// the Illinois halving of a stuck end's value.
template <class G>
double falsi(const G& g, double a, double b, double ga, double gb) {
  int kept = 0;  // which end stayed at the last step (−1 a, +1 b)
  double x = 0.5 * (a + b);
  for (int i = 0; i < kFalsiSteps; ++i) {
    const double next = (a * gb - b * ga) / (gb - ga);
    x = next > a && next < b ? next : 0.5 * (a + b);
    const double gx = g(x);
    if (gx == 0.0 || !std::isfinite(gx)) return x;
    if ((gx > 0.0) == (ga > 0.0)) {
      a = x;
      ga = gx;
      if (kept == 1) gb *= 0.5;
      kept = 1;
    } else {
      b = x;
      gb = gx;
      if (kept == -1) ga *= 0.5;
      kept = -1;
    }
    if (b - a <= 4.0 * kEps * (std::abs(a) + std::abs(b))) break;
  }
  return x;
}

}  // namespace

void bandBreakpoints(const ProfilePiece& p, double t0, double t1, double rMax,
                     const BoreSection& bore, const BorePlane& plane,
                     std::vector<Breakpoint>& out) {
  const Eigen::Vector3d& n = plane.normal_R;
  const Vector2d m = n.head<2>();
  if (!(std::abs(n.z()) > 0.0) || !(m.norm() > 0.0)) return;  // the line stands still
  const Band band{p,
                  bore,
                  m,
                  n.dot(plane.point_R),
                  n.z(),
                  m.norm(),
                  (boreEllipse(bore.point_R, bore.axis_R, bore.radius, 0.0).S * m).norm()};
  // the band in ζ where the line crosses the disc of radius rMax, and an eighth of it on
  // either side: the band's edges (the line touching that disc) fall between samples
  const double zc = band.nDotP / n.z(), half = rMax * band.mNorm / std::abs(n.z());
  const double margin = 2.0 * half / kBandSamples;
  const PieceAt e0 = pieceAt(p, t0), e1 = pieceAt(p, t1);
  const double za = std::max(e0.zeta, zc - half - margin);
  const double zb = std::min(e1.zeta, zc + half + margin);
  if (!(zb > za)) return;
  const double ta = std::max(t0, parameterOf(p, za)), tb = std::min(t1, parameterOf(p, zb));
  std::array<std::array<double, kEvents>, kBandSamples + 1> g;
  std::array<double, kBandSamples + 1> t;
  for (int j = 0; j <= kBandSamples; ++j) {
    t[j] = j == kBandSamples ? tb : ta + (tb - ta) * j / kBandSamples;
    g[j] = band.at(t[j]);
  }
  const auto keep = [&](int i, double root) {
    if (root > t0 && root < t1 && band.changesForm(i, root))
      out.push_back({root, i != kCrossLo && i != kCrossHi});
  };
  for (int i = 0; i < kEvents; ++i)
    for (int j = 0; j <= kBandSamples; ++j) {
      if (g[j][i] == 0.0) keep(i, t[j]);
      if (j == kBandSamples) break;
      const double ga = g[j][i], gb = g[j + 1][i];
      if (!(ga < 0.0 && gb > 0.0) && !(ga > 0.0 && gb < 0.0)) continue;  // NaN: no crossings
      const bool crossing = i == kCrossLo || i == kCrossHi;
      keep(i, falsi([&](double x) { return band.at(x, crossing)[i]; }, t[j], t[j + 1], ga, gb));
    }
}

namespace {

// The presence changes of a piece's slices, around the lines' events (pieceBreakpoints).
struct PresenceScan {
  const std::function<bool(double)>& present;
  std::vector<Breakpoint> events;  // ascending
  double snapWidth = 0.0;
  std::vector<Breakpoint> changes;

  // The change in (a, b), present(a) = from ≠ present(b), by bisection; an event within
  // snapWidth stands for it, singular or not as its kind is (a region going at a crossing
  // goes as the square of the distance, its two corners' triangles).
  void bisect(double a, double b, bool from) {
    for (int k = 0; k < kBisections; ++k) {
      const double m = 0.5 * (a + b);
      if (!(m > a && m < b)) break;
      (present(m) == from ? a : b) = m;
    }
    const double t = 0.5 * (a + b);
    for (const Breakpoint& e : events)
      if (std::abs(e.t - t) <= snapWidth) return;
    changes.push_back({t, true});
  }
};

bool byParameter(const Breakpoint& x, const Breakpoint& y) { return x.t < y.t; }

}  // namespace

std::vector<Breakpoint> pieceBreakpoints(const ProfilePiece& p, double t0, double t1, double rMax,
                                         const BoreSection& bore,
                                         const std::vector<BorePlane>& planes,
                                         const std::function<bool(double)>& present) {
  PresenceScan scan{present, {}, kSnap * (t1 - t0), {}};
  for (const BorePlane& pl : planes) bandBreakpoints(p, t0, t1, rMax, bore, pl, scan.events);
  std::sort(scan.events.begin(), scan.events.end(), byParameter);
  // Presence is tested at the samples, at the lines' events and halfway between any two of
  // them, and bisected between two tests that differ. A region that lives only inside a band
  // (the pin's side pressed against the rim where a plane meets the bore) comes and goes
  // between two samples where there is none: the events and the points between them see it.
  std::vector<double> at;
  for (int i = 0; i <= kZetaSamples; ++i)
    at.push_back(i == kZetaSamples ? t1 : t0 + (t1 - t0) * i / kZetaSamples);
  for (const Breakpoint& e : scan.events) at.push_back(e.t);
  std::sort(at.begin(), at.end());
  bool prev = present(at.front());
  for (std::size_t i = 1; i < at.size(); ++i) {
    const double a = at[i - 1], b = at[i];
    if (!(b > a)) continue;
    const double m = 0.5 * (a + b);
    const bool mid = present(m), next = present(b);
    if (mid != prev) scan.bisect(a, m, prev);
    if (next != mid) scan.bisect(m, b, mid);
    prev = next;
  }
  std::vector<Breakpoint> found = scan.events;
  found.insert(found.end(), scan.changes.begin(), scan.changes.end());
  std::sort(found.begin(), found.end(), byParameter);
  std::vector<Breakpoint> cuts;
  for (const Breakpoint& b : found) {  // points within kNegligible of the piece are one
    if (!cuts.empty() && !(b.t - cuts.back().t > kNegligible * (t1 - t0))) {
      cuts.back().singular = cuts.back().singular || b.singular;
      continue;
    }
    cuts.push_back(b);
  }
  return cuts;
}

}  // namespace vcontact::volume::detail
