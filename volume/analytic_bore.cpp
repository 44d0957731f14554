#include "volume/analytic_bore.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/error.hpp"
#include "volume/analytic_segment.hpp"
#include "volume/quadrature.hpp"

namespace vcontact::volume {
namespace {

using detail::PieceAt;
using detail::pieceAt;
using detail::Segment;
using Eigen::Vector2d;
using Eigen::Vector3d;

// As for the solids of revolution on a plane (analytic_revolution.cpp): the G7/K15 estimate
// overstates the error of smooth integrands, so 1e-11 asked gives 1e-9 with margin.
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
// arc inside the disc as ∫ n_B ds (x, y); the slice's width across u.
constexpr int kSize = 13;
using SliceVector = Eigen::Matrix<double, kSize, 1>;

// Moments of the slice's region in its own axes (ξ along u from the disc's edge point −r u,
// η along v), with the bore's chord inside the disc, the width across u and δ.
struct InSlice {
  double A = 0.0, S1 = 0.0, S11 = 0.0, S22 = 0.0;
  double chord = 0.0, width = 0.0, depth = 0.0;
};

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

// The disc of radius r less the disc of radius R whose centre is e away along u.
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
  // two segments cut by the chord through the circles' crossings (analytic_bore.hpp)
  const double tPin = detail::segmentAngle(r, delta * (r + e + R) / (2.0 * e));
  const double tBore = detail::segmentAngle(R, delta * (r - e + R) / (2.0 * e));
  const Segment g = detail::shallowSegmentMoments(r, tPin);
  const double width = tPin >= 0.5 * M_PI ? 2.0 * r : 2.0 * r * std::sin(tPin);
  m = {g.A, g.S1, g.S11, g.S22, 2.0 * R * std::sin(tBore), width, delta};
  subtract(m, detail::shallowSegmentMoments(R, tBore), delta);
  return m;
}

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
    const InSlice m = discLessBore(r, bore.radius, e);
    depth = std::max(depth, m.depth);
    // p = O + a + ξ' u + η v + z' e_z over the slice, with a = −r u − o, z' = ζ − zo
    const Vector2d a = -r * u - o, m1 = m.A * a + m.S1 * u;
    const double zp = zeta - zo;
    const Eigen::Matrix2d m2 = m.A * a * a.transpose() +
                               m.S1 * (a * u.transpose() + u * a.transpose()) +
                               m.S11 * u * u.transpose() + m.S22 * v * v.transpose();
    SliceVector x;
    x << m.A, m1.x(), m1.y(), m.A * zp, m2(0, 0), m2(0, 1), m2(1, 1), m1.x() * zp, m1.y() * zp,
        m.A * zp * zp, m.chord * u.x(), m.chord * u.y(), m.width;
    return x;
  }
};

struct Totals {
  SliceVector sum = SliceVector::Zero();
  double relErr = 0.0;
  void add(const QuadratureResult<kSize>& q) {
    sum += q.value;
    relErr = std::max(relErr, q.relative_error);
  }
};

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
    if (!(b > a) || s.condition(0, mid.zeta, mid.r) <= 0.0) continue;  // no crescent
    const bool singA = isChange(a), singB = isChange(b);
    if (singA || singB) {
      out.add(integrateSingularEnds<kSize>(at, a, b, singA, singB, kQuadratureTolerance));
    } else {
      out.add(integrateAdaptive<kSize>([&](double t) { return at(t, 0.0); }, a, b,
                                       kQuadratureTolerance));
    }
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
  const SliceVector& x = t.sum;
  if (!(x(0) > 0.0)) return out;
  // B's boundary inside the pin: the bore's arcs (x(10), x(11)) and the planes' parts, whose
  // outward normals are −e_z at ζ_lo and +e_z at ζ_hi (B lies between them).
  const double areaLo = sliceArea(s, profile, bore.zeta_lo);
  const double areaHi = sliceArea(s, profile, bore.zeta_hi);
  Vector3d n_R(x(10), x(11), areaHi - areaLo);
  if (!(n_R.norm() > 0.0)) n_R = Vector3d(-s.o.x(), -s.o.y(), 0.0);  // no boundary of B inside
  n_R.normalize();
  geometry::Moments M;
  M.m0 = x(0);
  M.m1 = Vector3d(x(1), x(2), x(3));
  M.m2 << x(4), x(5), x(7), x(5), x(6), x(8), x(7), x(8), x(9);
  const double area = x(12) + std::abs(n_R.z()) * (areaLo + areaHi);
  out.cv = contactFromMoments(M, Vector3d(s.o.x(), s.o.y(), s.zo), X_WR, X_WR.linear() * n_R, area,
                              s.depth, Method::kAnalytic);
  out.cv.relative_error = t.relErr;
  out.plane_area = areaLo + areaHi;
  return out;
}

}  // namespace vcontact::volume
