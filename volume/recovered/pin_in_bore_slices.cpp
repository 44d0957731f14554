#include "volume/recovered/pin_in_bore_slices.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "volume/analytic/circular_segment.hpp"

namespace vcontact::volume::detail {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The first harmonic of the circle's side of the ellipse must exceed the second this many
// times for its derivative to vanish only twice (more than √20, see discLessEllipse).
constexpr double kHarmonicRatio = 5.0;
// Below −kEmptyMargin R² the largest value of the side (bounded through its harmonics) leaves
// no doubt that the ellipse holds the disc; the harmonics carry a few ε R² of rounding.
constexpr double kEmptyMargin = 64.0 * kEps;
constexpr int kNewtonSteps = 100;    // Newton, else bisection: at most ~60 halvings of π
constexpr double kSmallTurn = 1e-3;  // Newton steps turned by series (turn)
constexpr int kGoldenSteps = 40;     // the deepest ray, to 4e-9 of the arc (its depth to ~1e-17)

Segment wholeDisc(double r) {
  const double A = M_PI * r * r;
  return {A, A * r, 1.25 * A * r * r, 0.25 * A * r * r};
}

// Removes the region g, whose moments are about a point δ further along u.
void subtract(InSlice& m, const Segment& g, double delta) {
  m.A -= g.A;
  m.S1 -= g.S1 + delta * g.A;
  m.S11 -= g.S11 + 2.0 * delta * g.S1 + delta * delta * g.A;
  m.S22 -= g.S22;
}

// (cs, sn) = (cos, sin) of `from` becomes that of `to`: for a small turn δ = to − from by cos δ
// to its δ⁶ term and sin δ to its δ⁵ (the next terms, δ⁸/8! and δ⁷/7!, below 2e-25 for
// |δ| < kSmallTurn), else by new sines.
void turn(double& cs, double& sn, double from, double to) {
  const double d = to - from, d2 = d * d;
  if (!(std::abs(d) < kSmallTurn)) {
    cs = std::cos(to);
    sn = std::sin(to);
    return;
  }
  const double cd = 1.0 - 0.5 * d2 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0));
  const double sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0));
  const double c2 = cs * cd - sn * sd;
  sn = sn * cd + cs * sd;
  cs = c2;
}

// The circle's point at ψ from its direction u (x = r (cos ψ u + sin ψ u⊥)) against the
// ellipse: f(ψ) = |S⁻¹(x − c)|² − R², positive outside.
struct Side {
  double r = 0.0;
  Vector2d u, w;  // u and u⊥
  Vector2d c;
  Matrix2d Sinv;
  double R = 0.0;

  Vector2d at(double psi) const { return r * (std::cos(psi) * u + std::sin(psi) * w); }
  // f and f′ at the circle's point whose direction from u has cosine cs and sine sn.
  std::pair<double, double> fdf(double cs, double sn) const {
    const Vector2d y = Sinv * (r * (cs * u + sn * w) - c);
    const double n = y.norm();
    return {(n - R) * (n + R), 2.0 * y.dot(Sinv * (r * (-sn * u + cs * w)))};
  }
  // The root of f in (a, b), where f changes sign once (positive at a if posA), from the
  // guess x (cosine cs, sine sn): Newton kept in the bracket, bisection where it leaves it.
  // A step δ below kSmallTurn turns (cos, sin) by the rotation's series instead of new sines.
  double root(double a, double b, double x, double cs, double sn, bool posA) const {
    for (int i = 0; i < kNewtonSteps; ++i) {
      const auto [fx, d] = fdf(cs, sn);
      if (fx == 0.0) return x;
      ((fx > 0.0) == posA ? a : b) = x;
      double next = d != 0.0 ? x - fx / d : 0.5 * (a + b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);
      if (std::abs(next - x) <= 4.0 * kEps * std::max(1.0, std::abs(x)) || !(b - a > 0.0))
        return next;
      turn(cs, sn, x, next);
      x = next;
    }
    return x;
  }
  // The ray's radial depth r − ρ_E at ψ (ρ_E its exit from the ellipse, 0 behind the centre).
  double rayDepth(double psi) const { return depthAlong(std::cos(psi) * u + std::sin(psi) * w); }
  // The same along the unit direction v.
  double depthAlong(const Vector2d& v) const {
    const Vector2d d = Sinv * v, s = Sinv * c;
    const double qa = d.squaredNorm(), qb = -2.0 * d.dot(s), qc = (s.norm() - R) * (s.norm() + R);
    const double disc = qb * qb - 4.0 * qa * qc;
    if (!(disc > 0.0)) return r;
    const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
    const double exit = std::max(q / qa, qc / q);
    return std::max(0.0, r - std::max(0.0, exit));
  }
};

double angleBetween(const Vector2d& a, const Vector2d& b) {
  return std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
}

// The moments about the centre of the segment of the disc of radius ρ beyond the chord
// n·y = ρ cos θ (n unit): area, ∫y, ∫y yᵀ.
struct Moments2 {
  double A;
  Vector2d m1;
  Matrix2d m2;
};

Moments2 segmentAbout(double rho, const Vector2d& n, double theta) {
  const Segment g = shallowSegmentMoments(rho, theta);
  const Vector2d t(-n.y(), n.x());
  return {
      g.A, (rho * g.A - g.S1) * n,
      (rho * rho * g.A - 2.0 * rho * g.S1 + g.S11) * n * n.transpose() + g.S22 * t * t.transpose()};
}

// The larger of f's two last golden-section points on [a, b], kGoldenSteps steps towards its
// one crest.
template <class F>
double goldenMax(const F& f, double a, double b) {
  const double k = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - k * (b - a), x2 = a + k * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < kGoldenSteps; ++i) {
    if (f1 < f2) {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + k * (b - a);
      f2 = f(x2);
    } else {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - k * (b - a);
      f1 = f(x1);
    }
  }
  return std::max(f1, f2);
}

// The largest depth over ψ ∈ [lo, hi] by golden section (one crest: the crescent's).
double deepestByAngle(const Side& s, double lo, double hi) {
  const double crest = goldenMax([&](double psi) { return s.rayDepth(psi); }, lo, hi);
  return std::max({crest, s.rayDepth(lo), s.rayDepth(hi)});
}

double deepest(const Side& s, double lo, double hi) {
  // along the tangent τ at the arc's middle direction m (the ray m + τ m⊥), free of sines
  // where the arc is less than π - 0.2 wide
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  if (!(half < 0.5 * M_PI - 0.1)) return deepestByAngle(s, lo, hi);
  const Vector2d m = std::cos(mid) * s.u + std::sin(mid) * s.w, mt(-m.y(), m.x());
  const auto at = [&](double t) { return s.depthAlong((m + t * mt).normalized()); };
  const double end = std::tan(half);
  return std::max({goldenMax(at, -end, end), s.rayDepth(lo), s.rayDepth(hi)});
}

}  // namespace

InSlice discLessBore(double r, double R, double e) {
  InSlice m;
  const double delta = r + e - R;  // the circles' overlap along u
  if (!(r > 0.0) || delta <= 0.0) return m;
  if (e >= r + R || r >= e + R) {  // the bore misses the disc, or lies wholly inside it
    const Segment d = wholeDisc(r);
    m = {d.A, d.S1, d.S11, d.S22, 0.0, 2.0 * r, 2.0 * r};
    if (r >= e + R) subtract(m, wholeDisc(R), delta);
    return m;
  }
  // two segments cut by the chord through the circles' crossings (recovered/pin_in_bore.hpp)
  const double tPin = segmentAngle(r, delta * (r + e + R) / (2.0 * e));
  const double tBore = segmentAngle(R, delta * (r - e + R) / (2.0 * e));
  const Segment g = shallowSegmentMoments(r, tPin);
  const double width = tPin >= 0.5 * M_PI ? 2.0 * r : 2.0 * r * std::sin(tPin);
  m = {g.A, g.S1, g.S11, g.S22, 2.0 * R * std::sin(tBore), width, delta};
  subtract(m, shallowSegmentMoments(R, tBore), delta);
  return m;
}

SliceEllipse boreEllipse(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double R,
                         double zeta) {
  SliceEllipse E;
  E.R = R;
  E.c = (point + axis * ((zeta - point.z()) / axis.z())).head<2>();
  const double s2 = axis.head<2>().squaredNorm();
  if (s2 > 0.0) {  // stretched by 1/cos γ along the axis' shadow u: 1/a_z − 1 = s²/(a_z(1 + a_z))
    const Vector2d u = axis.head<2>() / std::sqrt(s2);
    E.S += s2 / (axis.z() * (1.0 + axis.z())) * u * u.transpose();
  }
  return E;
}

// f(φ) = |S⁻¹(x − c)|² − R² on the circle x = r(cos φ, sin φ) is, with P = S⁻², the
// trigonometric polynomial A₀ − 2r (Pc)·(cos φ, sin φ) + r² ((P₁₁ − P₂₂)/2 cos 2φ + P₁₂ sin 2φ),
// A₀ = r² tr P/2 + cᵀPc − R². With ρ₁ = 2r|Pc| and ρ₂ the second harmonic's amplitude, f′ is
// −ρ₁ sin ψ plus at most 2ρ₂ (ψ from the first harmonic's crest), with a derivative within 4ρ₂
// of −ρ₁ cos ψ: for ρ₁ > √20 ρ₂ f′ vanishes once near ψ = 0 and once near π, so f has one
// crest and one trough, and two roots when f(0) > 0 > f(π), one on either side of the crest.
namespace {

// The crossings of the circle with the ellipse (the comment above): 0 where the ellipse holds
// the disc, 1 for two crossings ψ = lo < 0 < hi about the direction s.u where f is largest,
// −1 where neither is certified.
int crossings(double r, const SliceEllipse& E, Side& s, double& lo, double& hi) {
  const Matrix2d Sinv = E.S.inverse(), P = Sinv * Sinv;
  const Vector2d Pc = P * E.c;
  const double rho1 = 2.0 * r * Pc.norm();
  const double rho2 = r * r * std::hypot(0.5 * (P(0, 0) - P(1, 1)), P(0, 1));
  const double A0 = 0.5 * r * r * P.trace() + E.c.dot(Pc) - E.R * E.R;
  if (!(rho1 > kHarmonicRatio * rho2)) return -1;
  if (A0 + rho1 + rho2 < -kEmptyMargin * E.R * E.R) return 0;  // the ellipse holds the disc
  if (A0 - rho1 - rho2 > 0.0) return -1;  // no crossing: the disc holds the ellipse, or misses it
  const Vector2d u = -Pc / Pc.norm();
  s = Side{r, u, Vector2d(-u.y(), u.x()), E.c, Sinv, E.R};
  if (!(s.fdf(1.0, 0.0).first > 0.0 && s.fdf(-1.0, 0.0).first < 0.0)) return -1;  // f(0), f(π)
  const double cs = std::clamp(-A0 / rho1, -1.0, 1.0), sn = std::sqrt((1.0 - cs) * (1.0 + cs));
  const double guess = std::acos(cs);
  hi = s.root(0.0, M_PI, guess, cs, sn, true);  // f(0) > 0 > f(±π), checked above
  lo = s.root(-M_PI, 0.0, -guess, cs, -sn, false);
  return 1;
}

}  // namespace

bool circleCrossings(double r, const SliceEllipse& E, Vector2d& lo, Vector2d& hi) {
  Side s;
  double psiLo = 0.0, psiHi = 0.0;
  if (crossings(r, E, s, psiLo, psiHi) != 1) return false;
  lo = s.at(psiLo);
  hi = s.at(psiHi);
  return true;
}

bool discLessEllipse(double r, const SliceEllipse& E, EllipseSlice& out, bool withDepth) {
  Side s;
  double lo = 0.0, hi = 0.0;
  const int k = crossings(r, E, s, lo, hi);
  if (k < 0) return false;
  if (k == 0) {
    out = EllipseSlice{};
    return true;
  }
  const Matrix2d& Sinv = s.Sinv;
  // the disc's arc outside the ellipse is [lo, hi], on the side n of the chord through the
  // crossings; the region is the disc's segment there less the ellipse's (header)
  const double thetaD = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  const Vector2d n = std::cos(mid) * s.u + std::sin(mid) * s.w;
  const Moments2 disc = segmentAbout(r, n, thetaD);
  const Vector2d yHi = Sinv * (s.at(hi) - E.c), yLo = Sinv * (s.at(lo) - E.c);
  const Vector2d m = (E.S * n).normalized();
  const double thetaE = 0.5 * (angleBetween(m, yHi) + angleBetween(m, yLo));
  const Moments2 y = segmentAbout(E.R, m, thetaE);
  const double det = E.S.determinant();
  const Vector2d Sm1 = E.S * y.m1;
  const double AE = det * y.A;
  const Vector2d m1E = det * (y.A * E.c + Sm1);
  const Matrix2d m2E = det * (y.A * E.c * E.c.transpose() + E.c * Sm1.transpose() +
                              Sm1 * E.c.transpose() + E.S * y.m2 * E.S);
  out.A = disc.A - AE;
  out.Sx = disc.m1.x() - m1E.x();
  out.Sy = disc.m1.y() - m1E.y();
  out.Sxx = disc.m2(0, 0) - m2E(0, 0);
  out.Sxy = disc.m2(0, 1) - m2E(0, 1);
  out.Syy = disc.m2(1, 1) - m2E(1, 1);
  out.arcX = 2.0 * r * std::sin(thetaD) * n.x();
  out.arcY = 2.0 * r * std::sin(thetaD) * n.y();
  out.arcLength = 2.0 * r * thetaD;
  out.depth = withDepth ? deepest(s, lo, hi) : 0.0;
  return true;
}

namespace {

// Moments of a region by Green's theorem over its boundary, counter-clockwise: area, ∫x, ∫y,
// ∫x², ∫xy, ∫y² as ∮ of x dy − y dx over 2, x²/2 dy, −y²/2 dx, x³/3 dy, x²y/2 dy, −y³/3 dx;
// and the circle's arcs on the boundary (∫ρ(cos φ, sin φ) dφ, their length, their angles).
struct Green {
  double A = 0.0, X = 0.0, Y = 0.0, XX = 0.0, XY = 0.0, YY = 0.0;
  Vector2d arc = Vector2d::Zero();
  double arcLength = 0.0;
  std::vector<std::pair<double, double>> arcs;
};

// A segment from P to Q: the integrands are cubics in its parameter, exact by two Gauss points.
void addSegment(Green& g, const Vector2d& P, const Vector2d& Q) {
  const Vector2d d = Q - P;
  const double h = 0.5 / std::sqrt(3.0);
  for (double t : {0.5 - h, 0.5 + h}) {
    const double x = P.x() + t * d.x(), y = P.y() + t * d.y();
    g.A += 0.25 * (x * d.y() - y * d.x());
    g.X += 0.25 * x * x * d.y();
    g.Y -= 0.25 * y * y * d.x();
    g.XX += x * x * x * d.y() / 6.0;
    g.XY += 0.25 * x * x * y * d.y();
    g.YY -= y * y * y * d.x() / 6.0;
  }
}

// The arc of the circle of radius ρ about the origin from angle a to b > a.
void addArc(Green& g, double rho, double a, double b) {
  const double r2 = rho * rho, r3 = r2 * rho, r4 = r2 * r2;
  const auto at = [&](double p, double k) {  // the antiderivatives at p, as k = 1
    const double sp = std::sin(p), cp = std::cos(p), s2 = std::sin(2.0 * p), s4 = std::sin(4.0 * p);
    return std::array<double, 5>{k * (sp - sp * sp * sp / 3.0), k * (-cp + cp * cp * cp / 3.0),
                                 k * (3.0 * p / 8.0 + s2 / 4.0 + s4 / 32.0),
                                 k * (-cp * cp * cp * cp / 4.0),
                                 k * (3.0 * p / 8.0 - s2 / 4.0 + s4 / 32.0)};
  };
  const std::array<double, 5> fa = at(a, 1.0), fb = at(b, 1.0);
  g.A += 0.5 * r2 * (b - a);
  g.X += 0.5 * r3 * (fb[0] - fa[0]);
  g.Y += 0.5 * r3 * (fb[1] - fa[1]);
  g.XX += r4 / 3.0 * (fb[2] - fa[2]);
  g.XY += 0.5 * r4 * (fb[3] - fa[3]);
  g.YY += r4 / 3.0 * (fb[4] - fa[4]);
  g.arc += rho * Vector2d(std::sin(b) - std::sin(a), std::cos(a) - std::cos(b));
  g.arcLength += rho * (b - a);
  g.arcs.emplace_back(a, b);
}

// The disc of radius ρ about the origin cut by the half-planes a·y ≤ b (a convex region: the
// circle's arcs inside them all, and each line's chord inside the others).
Green clippedDisc(double rho, const HalfPlanes& hp) {
  Green g;
  std::vector<double> cuts;
  for (const auto& [a, b] : hp) {
    const double na = a.norm();
    if (!(na > 0.0)) {
      if (b < 0.0) return Green{};
      continue;
    }
    const double q = b / (rho * na);
    if (q <= -1.0) return Green{};  // the disc is outside
    if (q >= 1.0) continue;
    const double alpha = std::atan2(a.y(), a.x()), beta = std::acos(q);
    cuts.push_back(alpha - beta);
    cuts.push_back(alpha + beta);
  }
  if (cuts.empty()) {
    addArc(g, rho, -M_PI, M_PI);
    return g;
  }
  const double c0 = cuts[0];
  for (double& c : cuts) c = c0 + std::fmod(std::fmod(c - c0, 2.0 * M_PI) + 2.0 * M_PI, 2.0 * M_PI);
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(c0 + 2.0 * M_PI);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
    const Vector2d p = rho * Vector2d(std::cos(mid), std::sin(mid));
    if (cuts[i + 1] > cuts[i] && std::all_of(hp.begin(), hp.end(), [&](const auto& h) {
          return h.first.dot(p) <= h.second;
        }))
      addArc(g, rho, cuts[i], cuts[i + 1]);
  }
  for (std::size_t i = 0; i < hp.size(); ++i) {
    const auto& [a, b] = hp[i];
    const double na = a.norm(), dist = std::abs(b) / na;
    if (!(na > 0.0) || !(dist < rho)) continue;
    const Vector2d foot = a * (b / (na * na)), t = Vector2d(-a.y(), a.x()) / na;
    double lo = -std::sqrt((rho - dist) * (rho + dist)), hi = -lo;
    for (std::size_t j = 0; j < hp.size() && lo < hi; ++j) {
      if (j == i) continue;
      const double k = hp[j].first.dot(t), rhs = hp[j].second - hp[j].first.dot(foot);
      if (k > 0.0) hi = std::min(hi, rhs / k);
      if (k < 0.0) lo = std::max(lo, rhs / k);
      if (k == 0.0 && rhs < 0.0) hi = lo;
    }
    if (hi > lo) addSegment(g, foot + lo * t, foot + hi * t);
  }
  return g;
}

}  // namespace

bool discLessEllipseCut(double r, const SliceEllipse& E, const HalfPlanes& lines, EllipseSlice& out,
                        bool withDepth) {
  Side s;
  double lo = 0.0, hi = 0.0;
  const int k = crossings(r, E, s, lo, hi);
  if (k < 0) return false;
  out = EllipseSlice{};
  if (k == 0) return true;
  // (disc ∩ {n·x ≥ h} less ellipse ∩ {n·x ≥ h}) ∩ the lines' half-planes, as discLessEllipse
  const double thetaD = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  const Vector2d n = std::cos(mid) * s.u + std::sin(mid) * s.w;
  HalfPlanes hp = lines;
  hp.emplace_back(-n, -r * std::cos(thetaD));
  const Green D = clippedDisc(r, hp);
  for (auto& [a, b] : hp) {  // a·(c + S y) ≤ b
    b -= a.dot(E.c);
    a = E.S * a;
  }
  const Green Y = clippedDisc(E.R, hp);
  const double det = E.S.determinant();
  const Vector2d Sm1 = E.S * Vector2d(Y.X, Y.Y);
  Matrix2d m2;
  m2 << Y.XX, Y.XY, Y.XY, Y.YY;
  const Vector2d m1E = det * (Y.A * E.c + Sm1);
  const Matrix2d m2E = det * (Y.A * E.c * E.c.transpose() + E.c * Sm1.transpose() +
                              Sm1 * E.c.transpose() + E.S * m2 * E.S);
  out.A = D.A - det * Y.A;
  out.Sx = D.X - m1E.x();
  out.Sy = D.Y - m1E.y();
  out.Sxx = D.XX - m2E(0, 0);
  out.Sxy = D.XY - m2E(0, 1);
  out.Syy = D.YY - m2E(1, 1);
  out.arcX = D.arc.x();
  out.arcY = D.arc.y();
  out.arcLength = D.arcLength;
  const double phiU = std::atan2(s.u.y(), s.u.x());
  if (!withDepth) return true;
  for (const auto& [a, b] : D.arcs) {  // the deepest ray whose end lies in B
    const double shift = std::round((0.5 * (a + b) - phiU) / (2.0 * M_PI)) * 2.0 * M_PI;
    out.depth = std::max(out.depth, deepest(s, a - phiU - shift, b - phiU - shift));
  }
  return true;
}

}  // namespace vcontact::volume::detail
