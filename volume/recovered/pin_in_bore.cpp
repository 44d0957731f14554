#include "volume/recovered/pin_in_bore.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/error.hpp"
#include "volume/analytic/circular_segment.hpp"
#include "volume/kernels/quadrature.hpp"
#include "volume/recovered/pin_in_bore_bands.hpp"
#include "volume/recovered/pin_in_bore_slices.hpp"

namespace vcontact::volume {
namespace {

using detail::Breakpoint;
using detail::InSlice;
using detail::PieceAt;
using detail::pieceAt;
using detail::Segment;
using Eigen::Vector2d;
using Eigen::Vector3d;

// As for the solids of revolution on a plane (analytic/revolution_on_plane.cpp): the G7/K15
// estimate overstates the error of smooth integrands, so 1e-11 asked gives 1e-9 with margin.
constexpr double kQuadratureTolerance = 1e-11;
// Where a slice changes its form (the crescent appears, the bore's circle leaves the disc or
// enters it) is found by bisection between samples of the piece: a line or a constant piece
// crosses each condition at most twice (δ is the line r(ζ) plus the convex e(ζ)), an arc
// (a quarter of a circle at most per side of its crest) at most twice; 8 and 32 intervals
// separate two crossings unless they are closer than that, where the crescent between them
// is thinner than the quadrature sees anyway.
constexpr int kLineSamples = 8;
constexpr int kArcSamples = 32;

// The slice's integrand, per unit of the piece's parameter, about the origin O of the
// moments: area; first moments (x, y, z); second moments (xx, xy, yy, xz, yz, zz); the bore's
// arc inside the disc as ∫ n_B ds (x, y); the slice's width across u; (tilted bores) the
// length of the pin's boundary inside B.
constexpr int kSize = 14;
using SliceVector = Eigen::Matrix<double, kSize, 1>;

struct Slicer {
  const BoreSection& bore;
  Vector2d o = Vector2d::Zero();  // the origin O of the moments: (o, zo)
  double zo = 0.0;
  double depth = 0.0;  // the largest δ seen

  Vector2d centre(double zeta) const {
    const Vector3d c = bore.point_R + bore.axis_R * ((zeta - bore.point_R.z()) / bore.axis_R.z());
    return c.head<2>();
  }
  // f_k(ζ, r): δ (the crescent appears), e − r − R (the bore leaves the disc), r − e − R
  // (the bore's circle lies inside the disc); a slice changes form where one is zero.
  double condition(int k, double zeta, double r) const {
    const double e = centre(zeta).norm(), R = bore.radius;
    return k == 0 ? r + e - R : (k == 1 ? e - r - R : r - e - R);
  }

  SliceVector slice(double zeta, double r) {
    const Vector2d c = centre(zeta);
    const double e = c.norm();
    const Vector2d u = e > 0.0 ? Vector2d(c / e) : Vector2d::UnitX(), v(-u.y(), u.x());
    const InSlice m = detail::discLessBore(r, bore.radius, e);
    depth = std::max(depth, m.depth);
    // p = O + a + ξ' u + η v + z' e_z over the slice, with a = −r u − o, z' = ζ − zo
    const Vector2d a = -r * u - o, m1 = m.A * a + m.S1 * u;
    const double zp = zeta - zo;
    const Eigen::Matrix2d m2 = m.A * a * a.transpose() +
                               m.S1 * (a * u.transpose() + u * a.transpose()) +
                               m.S11 * u * u.transpose() + m.S22 * v * v.transpose();
    SliceVector x;
    x << m.A, m1.x(), m1.y(), m.A * zp, m2(0, 0), m2(0, 1), m2(1, 1), m1.x() * zp, m1.y() * zp,
        m.A * zp * zp, m.chord * u.x(), m.chord * u.y(), m.width, 0.0;
    return x;
  }
};

// The integrals and the error of V: each interval's estimate (the largest over its
// components, relative to their ∫|f|) times its V, summed.
struct Totals {
  SliceVector sum = SliceVector::Zero();
  double volumeError = 0.0;
  /// The connected regions along the axis: runs of consecutive intervals with a region in
  /// their slices, each summed apart (the pin tilted in its bore touches the wall at both ends
  /// on opposite sides, with nothing between: two patches). `sum` is the whole, summed in the
  /// same order as without runs.
  struct Run {
    SliceVector sum = SliceVector::Zero();
    double volumeError = 0.0;
    double depth = 0.0;  ///< the largest δ of its slices
  };
  std::vector<Run> runs;
  bool open = false;  ///< the last interval had a region: the next one continues its run

  /// An interval with a region, whose slices reached `depth`.
  void add(const QuadratureResult<kSize>& q, double depth) {
    sum += q.value;
    volumeError += q.relative_error * std::abs(q.value(0));
    if (!open) runs.emplace_back();
    open = true;
    Run& run = runs.back();
    run.sum += q.value;
    run.volumeError += q.relative_error * std::abs(q.value(0));
    run.depth = std::max(run.depth, depth);
  }
  /// An interval without a region: the run before it, if any, has ended.
  void gap() { open = false; }
  double relErr() const { return sum(0) > 0.0 ? volumeError / sum(0) : 0.0; }
};

// ∫_a^b of at(anchor, offset) over t = anchor + offset, after the substitution that smooths a
// (t − e)^{3/2} end behaviour at an end e where the slice changes form.
template <class F>
QuadratureResult<kSize> integrateSlices(const F& at, double a, double b, bool singA, bool singB,
                                        double tol = kQuadratureTolerance) {
  if (singA || singB) return integrateSingularEnds<kSize>(at, a, b, singA, singB, tol);
  return integrateAdaptive<kSize>([&](double t) { return at(t, 0.0); }, a, b, tol);
}

// The root in (a, b) of g, which changes sign there, by bisection to the last bit.
template <class G>
double bisect(const G& g, double a, double b) {
  const bool negA = g(a) < 0.0;
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    if ((g(m) < 0.0) == negA) {
      a = m;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

// The parameters in (t0, t1) of piece p where a slice changes form.
std::vector<double> formChanges(const Slicer& s, const ProfilePiece& p, double t0, double t1) {
  const int n = p.kind == ProfilePiece::Kind::kArc ? kArcSamples : kLineSamples;
  std::vector<double> out;
  for (int k = 0; k < 3; ++k) {
    const auto g = [&](double t) {
      const PieceAt e = pieceAt(p, t);
      return s.condition(k, e.zeta, e.r);
    };
    for (int i = 0; i < n; ++i) {
      const double a = t0 + (t1 - t0) * i / n, b = i + 1 == n ? t1 : t0 + (t1 - t0) * (i + 1) / n;
      if ((g(a) < 0.0) != (g(b) < 0.0)) out.push_back(bisect(g, a, b));
    }
  }
  return out;
}

// The slices of piece p over ζ ∈ [zlo, zhi], in the piece's parameter.
void addPiece(Slicer& s, const ProfilePiece& p, double zlo, double zhi, Totals& out) {
  const double t0 = detail::parameterOf(p, zlo), t1 = detail::parameterOf(p, zhi);
  if (!(t1 > t0)) return;
  const std::vector<double> changes = formChanges(s, p, t0, t1);
  std::vector<double> cuts = changes;
  cuts.push_back(t0);
  cuts.push_back(t1);
  std::sort(cuts.begin(), cuts.end());
  const auto isChange = [&](double t) {
    return std::find(changes.begin(), changes.end(), t) != changes.end();
  };
  const auto at = [&](double anchor, double offset) -> SliceVector {
    const PieceAt e = pieceAt(p, anchor + offset);
    return s.slice(e.zeta, e.r) * e.J;
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    const PieceAt mid = pieceAt(p, 0.5 * (a + b));
    if (!(b > a)) continue;
    if (s.condition(0, mid.zeta, mid.r) <= 0.0) {  // no crescent
      out.gap();
      continue;
    }
    // the run's own deepest slice; the whole's is the largest of the runs'
    const double deepest = s.depth;
    s.depth = 0.0;
    const QuadratureResult<kSize> q = integrateSlices(at, a, b, isChange(a), isChange(b));
    out.add(q, s.depth);
    s.depth = std::max(deepest, s.depth);
  }
}

void checkBore(const RevolutionProfile& profile, const BoreSection& bore) {
  detail::checkProfile(profile, "revolutionInBore");
  if (!(bore.radius > 0.0) || !std::isfinite(bore.radius))
    throw InputError("revolutionInBore", "the bore's radius must be positive and finite");
  if (!(bore.axis_R.z() > 0.0) || !bore.point_R.allFinite())
    throw InputError("revolutionInBore",
                     "the bore's axis must advance along the pin's (a positive z component)");
}

// The region's area in the slice at ζ (a bounding plane), 0 outside the profile.
double sliceArea(Slicer& s, const RevolutionProfile& profile, double zeta) {
  if (!std::isfinite(zeta) || zeta < profile.front().z0 || zeta > profile.back().z1) return 0.0;
  for (const ProfilePiece& p : profile)
    if (zeta <= p.z1) return s.slice(zeta, profileRadius(p, zeta))(0);
  return 0.0;
}

// ---------------------------------------------------------------------------------------
// Tilted axes: the slice's region in polar coordinates (ρ, ψ) about the disc's centre.

// The slices of a tilted bore are themselves quadratures (over ψ, 1e-12 asked) whose
// breakpoints are bisected to 1e-15 of their range: as functions of ζ they are smooth only
// to about 1e-12, and asking the outer rule for 1e-11 would bisect that noise to its limit
// of intervals (thousands of slices). 1e-9 asked of it delivers V to 1e-9 or better.
constexpr double kInnerTolerance = 1e-12;
constexpr double kTiltedTolerance = 1e-9;
// Where a plane's line crosses the disc (a band 2r tan γ wide, γ the plane's tilt from the
// slice) the band is integrated to 1e-4 of itself, which for a band a 2r tan γ / L share of
// the part's length L is 1e-4 of that share of V (5e-7 of V at 10 mrad for the 5 mm pin in a
// 20 mm block), and enters the reported error so. Between the band's breakpoints
// (recovered/pin_in_bore_bands.hpp) one Kronrod rule does far better than its estimate says: on the
// benchmark's pose asking 1e-9 takes 225 slices instead of 75 and moves V by 1e-17 of itself.
constexpr double kBandTolerance = 1e-4;
// A ray's bounds (roots of a quadratic, a line's crossing) carry the rounding of coordinates
// of the size of r, 1e-16 r: an interval narrower than 1e-13 r is taken for that rounding.
// Such ghosts (a line tangent to the disc, an ellipse grazing it) have areas of 1e-40 m² and
// would send the quadratures chasing their noise; a real region narrower than that on some
// rays (a crescent's tips) loses less than (1e-13 r)² per radian of them.
constexpr double kRayNoise = 1e-13;
// The floors added to the area: over ψ, kFloor r² a radian; over ζ, kFloorZeta L² per unit
// length (L the part's size). The quadratures then stop on 1e-12 (1e-9) of the floor where
// the region is a sliver. The crescent of a 5 mm pin at d/r = 1e-5 in a 0.1 mm clearance is
// 4e-7 r² a radian and 2.4e-8 r² a slice (L = 3r): the floors cost it at most 2.5e-12 and
// 4e-10 of itself.
constexpr double kFloor = 1e-6;
constexpr double kFloorZeta = 1e-9;
constexpr int kAngleSamples = 64;  // rays between which the intervals' changes are bisected
constexpr int kBisections = 45;    // 2π/64 to 1e-15 of it

// Per ray: area, ∫x, ∫y, ∫x², ∫xy, ∫y² per unit ψ (about the disc's centre); the pin's
// boundary inside B as ∫ r (cos ψ, sin ψ) and ∫ r per unit ψ.
constexpr int kRaySize = 9;
using RayVector = Eigen::Matrix<double, kRaySize, 1>;

struct PolarSlice {
  double zeta = 0.0, r = 0.0;
  Vector3d a, w0;  // the bore's axis, and the disc's centre less the axis point
  double R2 = 0.0;
  std::vector<std::pair<Vector2d, double>> lines;  // a plane's trace: m·(ρ d) ≤ k
  double psi0 = 0.0;  // the direction away from where the bore's axis crosses the slice
  double depth = 0.0;
  detail::SliceEllipse ellipse;  // the bore's section
  bool touched = false;          // whether a ray met the region
  bool withDepth = true;         // false: the area is all that is wanted

  // The ray's allowed radii [lo, hi] (the disc and the planes) and the bore's (r1, r2).
  struct Ray {
    double lo, hi, r1, r2;
    bool bore;
  };
  Ray ray(double c, double s) const {
    const Vector3d D(c, s, 0.0);
    const double Da = D.dot(a), Wa = w0.dot(a);
    const double qa = 1.0 - Da * Da, qb = 2.0 * (D.dot(w0) - Da * Wa);
    const double qc = w0.squaredNorm() - Wa * Wa - R2;
    const double disc = qb * qb - 4.0 * qa * qc;
    Ray out{0.0, r, 0.0, 0.0, disc > 0.0};
    if (out.bore) {  // the roots without cancellation
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      out.r1 = std::min(q / qa, qc / q);
      out.r2 = std::max(q / qa, qc / q);
    }
    for (const auto& [m, k] : lines) {
      const double sm = m.x() * c + m.y() * s;
      if (sm > 0.0) out.hi = std::min(out.hi, k / sm);
      if (sm < 0.0) out.lo = std::max(out.lo, k / sm);
      if (sm == 0.0 && k < 0.0) out.hi = -1.0;
    }
    return out;
  }
  // Which of the conditions that shape the ray's intervals hold, as bits.
  unsigned signature(double psi) const {
    const Ray q = ray(std::cos(psi), std::sin(psi));
    unsigned bits = q.bore;
    int i = 1;
    for (double x : {q.r1 - q.lo, q.r1 - q.hi, q.r2 - q.lo, q.r2 - q.hi, q.hi - q.lo})
      bits |= (q.bore && x > 0.0 ? 1u : 0u) << i++;
    for (const auto& [m, k] : lines) {  // which side of the ray the line is, and where it cuts
      const double sm = m.x() * std::cos(psi) + m.y() * std::sin(psi);
      bits |= (sm > 0.0 ? 1u : 0u) << i++;
      bits |= (sm > 0.0 && k < sm * r ? 1u : 0u) << i++;  // the line bounds the ray inside r
      bits |= (sm < 0.0 && k < 0.0 ? 1u : 0u) << i++;     // or from beyond the centre
    }
    return bits;
  }
  RayVector at(double psi) {
    const double c = std::cos(psi), s = std::sin(psi);
    const Ray q = ray(c, s);
    RayVector x = RayVector::Zero();
    const auto add = [&](double lo, double hi) {
      if (!(hi - lo > kRayNoise * r)) return;
      touched = true;
      const double w = hi - lo, A = 0.5 * w * (hi + lo);
      const double m1 = w * (hi * hi + hi * lo + lo * lo) / 3.0;
      const double m2 = 0.25 * w * (hi + lo) * (hi * hi + lo * lo);
      x(0) += A;
      x(1) += m1 * c;
      x(2) += m1 * s;
      x(3) += m2 * c * c;
      x(4) += m2 * c * s;
      x(5) += m2 * s * s;
      if (hi == r) {  // the pin's side lies in B here
        x(6) += r * c;
        x(7) += r * s;
        x(8) += r;
        depth = std::max(depth, w);
      }
    };
    if (q.bore) {
      add(q.lo, std::min(q.hi, q.r1));
      add(std::max(q.lo, q.r2), q.hi);
    } else {
      add(q.lo, q.hi);
    }
    return x;
  }
};

// The angles in [ψ₀, ψ₀ + 2π] where a ray's intervals change, with both ends. The rays
// sampled start at ψ₀, away from the bore's centre, where a thin crescent is deepest: one
// narrower than the samples' spacing is still seen (at d/r = 1e-5 in a 0.1 mm clearance the
// crescent spans 0.06 rad, the spacing is 0.1).
std::vector<double> rayChanges(const PolarSlice& sl) {
  const double psi0 = sl.psi0;
  std::vector<double> cuts = {psi0, psi0 + 2.0 * M_PI};
  const double step = 2.0 * M_PI / kAngleSamples;
  unsigned from = sl.signature(psi0);
  for (int i = 1; i <= kAngleSamples; ++i) {
    const double end = psi0 + i * step;
    const unsigned next = sl.signature(end);
    // each change in turn: bisect to where the signature leaves `from`, then go on from there
    // (several conditions may change between two samples: the ellipse and a plane's line)
    double a = psi0 + (i - 1) * step;
    for (int changes = 0; from != next && changes < 8; ++changes) {
      double b = end;
      for (int k = 0; k < kBisections; ++k) {
        const double m = 0.5 * (a + b);
        if (sl.signature(m) == from) {
          a = m;
        } else {
          b = m;
        }
      }
      cuts.push_back(b);
      a = b;
      from = sl.signature(b);
    }
    from = next;
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

// The slice's region over ψ. As over ζ (Tilted::slice), the moments are integrated with the
// area times r^k added and N with the boundary's length, so that a moment that vanishes by
// symmetry is asked for accuracy relative to the slice's scale, not to its own rounding.
RayVector integrateRays(PolarSlice& sl) {
  const std::vector<double> cuts = rayChanges(sl);
  const double r = sl.r;
  sl.touched = false;
  // the area with a floor of kFloor r² a radian too: a subinterval holding only a sliver
  // (a crescent's tip cut by a line) is asked for accuracy relative to the slice, not to the
  // sliver, whose width is a difference of numbers of the size of r
  const double floor = kFloor * r * r;
  const auto f = [&](double psi) {
    RayVector x = sl.at(psi);
    x(0) += floor;
    x.segment<2>(1) += r * x(0) * Vector2d::Ones();
    x.segment<3>(3) += r * r * x(0) * Vector3d::Ones();
    x.segment<2>(6) += (x(8) + floor / r) * Vector2d::Ones();
    return x;
  };
  RayVector sum = RayVector::Zero();
  double range = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] > cuts[i]) {
      sum += integrateAdaptive<kRaySize>(f, cuts[i], cuts[i + 1], kInnerTolerance).value;
      range += cuts[i + 1] - cuts[i];
    }
  if (!sl.touched) return RayVector::Zero();  // not the floor's rounding: an empty slice is 0
  sum.segment<2>(1) -= r * sum(0) * Vector2d::Ones();
  sum.segment<3>(3) -= r * r * sum(0) * Vector3d::Ones();
  sum.segment<2>(6) -= (sum(8) + floor / r * range) * Vector2d::Ones();
  sum(0) -= floor * range;
  return sum;
}

// The slice's moments as integrateRays gives them: by closed forms
// (recovered/pin_in_bore_slices.hpp) where the circle crosses the ellipse twice or lies in it, the
// faces' lines cutting the region or not; by rays elsewhere or when `polarOnly`.
RayVector sliceMoments(PolarSlice& sl, bool polarOnly) {
  if (polarOnly) return integrateRays(sl);
  bool cut = false;  // a line crosses the disc
  for (const auto& [m, k] : sl.lines) {
    if (k <= -sl.r * m.norm()) return RayVector::Zero();  // the disc outside B
    cut = cut || k < sl.r * m.norm();
  }
  detail::EllipseSlice e;
  const bool closed = cut ? detail::discLessEllipseCut(sl.r, sl.ellipse, sl.lines, e, sl.withDepth)
                          : detail::discLessEllipse(sl.r, sl.ellipse, e, sl.withDepth);
  if (!closed) return integrateRays(sl);
  sl.depth = std::max(sl.depth, e.depth);
  RayVector x;
  x << e.A, e.Sx, e.Sy, e.Sxx, e.Sxy, e.Syy, e.arcX, e.arcY, e.arcLength;
  return x;
}

struct Tilted {
  const BoreSection& bore;
  std::vector<BorePlane> planes;
  Vector2d o = Vector2d::Zero();
  double zo = 0.0, depth = 0.0;
  double L = 0.0;  // the part's size, m

  PolarSlice sliceAt(double zeta, double r) const {
    PolarSlice sl;
    sl.zeta = zeta;
    sl.r = r;
    sl.a = bore.axis_R;
    sl.w0 = Vector3d(0.0, 0.0, zeta) - bore.point_R;
    sl.R2 = bore.radius * bore.radius;
    const Vector3d c = bore.point_R + bore.axis_R * ((zeta - bore.point_R.z()) / bore.axis_R.z());
    sl.psi0 = std::atan2(-c.y(), -c.x());
    sl.ellipse = detail::boreEllipse(bore.point_R, bore.axis_R, bore.radius, zeta);
    for (const BorePlane& p : planes)
      sl.lines.emplace_back(p.normal_R.head<2>(),
                            p.normal_R.dot(p.point_R) - p.normal_R.z() * zeta);
    return sl;
  }
  // Whether ζ lies where a plane's line crosses a disc of radius rMax.
  bool inBand(double zeta, double rMax) const {
    return std::any_of(planes.begin(), planes.end(), [&](const BorePlane& pl) {
      const Vector3d& m = pl.normal_R;
      return std::abs(m.dot(pl.point_R) - m.z() * zeta) <= rMax * m.head<2>().norm();
    });
  }
  double area(double zeta, double r) const {
    PolarSlice sl = sliceAt(zeta, r);
    sl.withDepth = false;
    return sliceMoments(sl, bore.polar_slices)(0);
  }
  // The slice's moments about O and the pin's boundary inside B, per unit of the piece's
  // parameter (J = dζ/dt, drdt = dr/dt). The quadrature asks each component for its accuracy
  // relative to its own ∫|f|, which a component that vanishes by symmetry (a moment across
  // the plane of the axes) never meets; so each moment is integrated with the area times
  // L^k added (L the part's size: the scale the moment is wanted to), and N with the
  // boundary's length (x(13)) added, and they are taken off after (untilt).
  SliceVector slice(const PieceAt& e) {
    PolarSlice sl = sliceAt(e.zeta, e.r);
    // the ellipse holds the circle of radius R about c: no ray is deeper than r + |c| − R,
    // and a slice that cannot beat the deepest so far is not searched
    const double c = sl.ellipse.c.norm();
    sl.withDepth = !(c < bore.radius && e.r + c - bore.radius <= depth);
    const RayVector q = sliceMoments(sl, bore.polar_slices);
    depth = std::max(depth, sl.depth);
    const double A = q(0), zp = e.zeta - zo, ox = o.x(), oy = o.y();
    const double mx = q(1) - ox * A, my = q(2) - oy * A;
    SliceVector x;
    x << A, mx, my, A * zp, q(3) - 2.0 * ox * q(1) + ox * ox * A,
        q(4) - ox * q(2) - oy * q(1) + ox * oy * A, q(5) - 2.0 * oy * q(2) + oy * oy * A, mx * zp,
        my * zp, A * zp * zp, q(6), q(7), 0.0, q(8);
    x.head<12>() *= e.J;
    x(12) = -e.drdt * q(8);  // the side's element r(e_r − r' e_z) dψ dζ, r' J = dr/dt
    x(13) = (std::abs(e.J) + std::abs(e.drdt)) * (q(8) + L);
    x(0) += kFloorZeta * L * x(13);  // a floor, as over ψ (integrateRays)
    x.segment<3>(1) += L * x(0) * Eigen::Vector3d::Ones();
    x.segment<6>(4) += L * L * x(0) * Eigen::Matrix<double, 6, 1>::Ones();
    x.segment<3>(10) += x(13) * Eigen::Vector3d::Ones();
    return x;
  }
  // Takes the offsets of slice() off the integrals.
  void untilt(SliceVector& x) const {
    x.segment<3>(1) -= L * x(0) * Eigen::Vector3d::Ones();
    x.segment<6>(4) -= L * L * x(0) * Eigen::Matrix<double, 6, 1>::Ones();
    x.segment<3>(10) -= x(13) * Eigen::Vector3d::Ones();
    x(0) -= kFloorZeta * L * x(13);
  }
};

void addTiltedPiece(Tilted& T, const ProfilePiece& p, double rMax, Totals& out) {
  const double t0 = detail::parameterOf(p, p.z0), t1 = detail::parameterOf(p, p.z1);
  std::vector<Breakpoint> cuts =
      detail::pieceBreakpoints(p, t0, t1, rMax, T.bore, T.planes, [&](double t) {
        const PieceAt e = pieceAt(p, t);
        return T.area(e.zeta, e.r) > 0.0;
      });
  cuts.insert(cuts.begin(), {t0, false});
  cuts.push_back({t1, false});
  const auto at = [&](double anchor, double offset) -> SliceVector {
    return T.slice(pieceAt(p, anchor + offset));
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i].t, b = cuts[i + 1].t;
    // an interval of 1e-12 of the piece (a breakpoint at the piece's end) holds at most 1e-12
    // of the piece's length times its largest slice
    if (!(b - a > detail::kNegligible * (t1 - t0))) continue;
    const PieceAt mid = pieceAt(p, 0.5 * (a + b));
    if (T.area(mid.zeta, mid.r) == 0.0) {  // no region: none appears within
      out.gap();
      continue;
    }
    const double tol = T.inBand(mid.zeta, rMax) ? kBandTolerance : kTiltedTolerance;
    // the run's own deepest slice (slice() searches a slice only when it can beat the depth
    // so far, so a run's depth is searched against its own); the whole's is the largest
    const double deepest = T.depth;
    T.depth = out.open ? out.runs.back().depth : 0.0;
    const QuadratureResult<kSize> q =
        integrateSlices(at, a, b, cuts[i].singular, cuts[i + 1].singular, tol);
    out.add(q, T.depth);
    T.depth = std::max(deepest, T.depth);
  }
}

}  // namespace

BoreContact revolutionInBore(const RevolutionProfile& profile, const Eigen::Isometry3d& X_WR,
                             const BoreSection& bore) {
  checkBore(profile, bore);
  const double lo = std::max(profile.front().z0, bore.zeta_lo);
  const double hi = std::min(profile.back().z1, bore.zeta_hi);
  BoreContact out;
  out.cv.method = Method::kAnalytic;
  if (!(hi > lo)) return out;
  // O near the region for the digits of the central moments: on the pin's largest radius,
  // away from the bore's centre, in the middle of the range.
  Slicer s{bore};
  s.zo = 0.5 * (lo + hi);
  const Vector2d cMid = s.centre(s.zo);
  const double eMid = cMid.norm();
  s.o = -largestRadius(profile) * (eMid > 0.0 ? Vector2d(cMid / eMid) : Vector2d::UnitX());
  Totals t;
  for (const ProfilePiece& p : profile) addPiece(s, p, std::max(p.z0, lo), std::min(p.z1, hi), t);
  if (!(t.sum(0) > 0.0)) return out;
  // B's boundary inside the pin: the bore's arcs (x(10), x(11)) and the planes' parts, whose
  // outward normals are −e_z at ζ_lo and +e_z at ζ_hi (B lies between them). A plane's part
  // belongs to the run that reaches it: the first run the one at ζ_lo, the last the one at
  // ζ_hi (where no run reaches a plane, its part is empty).
  const double areaLo = sliceArea(s, profile, bore.zeta_lo);
  const double areaHi = sliceArea(s, profile, bore.zeta_hi);
  const auto region = [&](const SliceVector& x, double lowPlane, double highPlane, double depth,
                          double relErr) {
    Vector3d n_R(x(10), x(11), highPlane - lowPlane);
    if (!(n_R.norm() > 0.0)) n_R = Vector3d(-s.o.x(), -s.o.y(), 0.0);  // no boundary of B inside
    n_R.normalize();
    geometry::Moments M;
    M.m0 = x(0);
    M.m1 = Vector3d(x(1), x(2), x(3));
    M.m2 << x(4), x(5), x(7), x(5), x(6), x(8), x(7), x(8), x(9);
    const double area = x(12) + std::abs(n_R.z()) * (lowPlane + highPlane);
    ContactVolume cv = contactFromMoments(M, Vector3d(s.o.x(), s.o.y(), s.zo), X_WR,
                                          X_WR.linear() * n_R, area, depth, Method::kAnalytic);
    cv.relative_error = relErr;
    return cv;
  };
  out.cv = region(t.sum, areaLo, areaHi, s.depth, t.relErr());
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    const Totals::Run& run = t.runs[i];
    if (!(run.sum(0) > 0.0)) continue;
    out.patches.push_back(region(run.sum, i == 0 ? areaLo : 0.0,
                                 i + 1 == t.runs.size() ? areaHi : 0.0, run.depth,
                                 run.volumeError / run.sum(0)));
  }
  sortPatches(out.patches);
  out.plane_area = areaLo + areaHi;
  return out;
}

BoreContact revolutionInTiltedBore(const RevolutionProfile& profile, const Eigen::Isometry3d& X_WR,
                                   const BoreSection& bore, const std::vector<BorePlane>& planes) {
  checkBore(profile, bore);
  BoreContact out;
  out.cv.method = Method::kAnalytic;
  Tilted T{bore, planes};
  const double rMax = largestRadius(profile);
  T.zo = 0.5 * (profile.front().z0 + profile.back().z1);
  const Vector3d c = bore.point_R + bore.axis_R * ((T.zo - bore.point_R.z()) / bore.axis_R.z());
  const double e = c.head<2>().norm();
  T.o = -rMax * (e > 0.0 ? Vector2d(c.head<2>() / e) : Vector2d::UnitX());
  T.L = std::max(rMax, 0.5 * (profile.back().z1 - profile.front().z0));
  Totals t;
  for (const ProfilePiece& p : profile) addTiltedPiece(T, p, rMax, t);
  T.untilt(t.sum);
  if (!(t.sum(0) > 0.0)) return out;
  // the pin's boundary inside B: its side, and its end faces (normals ∓e_z), the bottom's
  // part in the first run, the top's in the last
  const double bottom =
      T.area(profile.front().z0, profileRadius(profile.front(), profile.front().z0));
  const double top = T.area(profile.back().z1, profileRadius(profile.back(), profile.back().z1));
  const auto region = [&](const SliceVector& x, double low, double high, double depth,
                          double relErr) {
    const Vector3d N(x(10), x(11), x(12) - low + high);
    Vector3d n_R = N.norm() > 0.0 ? Vector3d(-N) : Vector3d(-T.o.x(), -T.o.y(), 0.0);
    n_R.normalize();
    geometry::Moments M;
    M.m0 = x(0);
    M.m1 = Vector3d(x(1), x(2), x(3));
    M.m2 << x(4), x(5), x(7), x(5), x(6), x(8), x(7), x(8), x(9);
    ContactVolume cv = contactFromMoments(M, Vector3d(T.o.x(), T.o.y(), T.zo), X_WR,
                                          X_WR.linear() * n_R, N.norm(), depth, Method::kAnalytic);
    cv.relative_error = relErr;
    return cv;
  };
  out.cv = region(t.sum, bottom, top, T.depth, t.relErr());
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    Totals::Run run = t.runs[i];
    T.untilt(run.sum);
    if (!(run.sum(0) > 0.0)) continue;
    out.patches.push_back(region(run.sum, i == 0 ? bottom : 0.0, i + 1 == t.runs.size() ? top : 0.0,
                                 run.depth, run.volumeError / run.sum(0)));
  }
  sortPatches(out.patches);
  return out;
}

}  // namespace vcontact::volume
