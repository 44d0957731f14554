#include "volume/analytic/revolution_on_plane.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "volume/analytic/circular_segment.hpp"
#include "volume/kernels/quadrature.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

// Relative tolerance asked of the quadrature. The G7/K15 difference it is checked against
// overstates the K15 error of a smooth integrand by orders of magnitude, so 1e-11 here
// delivers the 1e-9 the backend promises with margin.
constexpr double kQuadratureTolerance = 1e-11;
// Integrate in θ when an end of the piece has θ below this fraction of the other end's
// (d^{3/2} behaviour dominates), unless the θ range is too narrow to carry ζ accurately.
constexpr double kThetaRatio = 0.5;
constexpr double kMinThetaRange = 1e-6;
// Two runs of wetted slices whose ends are closer than this fraction of the solid's length are
// one region: their ends are cuts computed twice (a piece's end and its root of d), equal up to
// round-off; a dry gap of a solid is far wider.
constexpr double kRunJoinFraction = 1e-9;

// ---------------------------------------------------------------------------------------
// Cylinder. In the cylinder frame C the half-space is {p : n·p ≤ h}. Write n = s u + n_z e_z
// with u a unit vector in the xy plane and v = e_z × u. The slice at height ζ is the disc
// x² + y² ≤ R² cut by ξ ≤ w(ζ) = (h − n_z ζ)/s, where ξ = p·u: a circular segment of depth
// d(ζ) = R + w(ζ) from the disc's edge at ξ = −R. With ξ = −R cos φ (φ ∈ [0, θ],
// d = R(1 − cos θ)) the segment moments about the edge point ξ' = ξ + R = 0 are
//   A      = 2R² ∫ sin²φ,           S_ξ'  = 2R³ ∫ (1 − cos φ) sin²φ,
//   S_ξ'ξ' = 2R⁴ ∫ (1 − cos φ)² sin²φ,  S_ηη = (2/3)R⁴ ∫ sin⁴φ.
// (closed forms in volume/analytic/circular_segment.hpp, with a series where they would cancel as θ
// → 0). The slices are then integrated over ζ adaptively, in θ where an end of the interval is a
// tangency (d = 0 or d = 2R: there the slice moments behave like d^{3/2} in ζ but are smooth in θ),
// otherwise in ζ itself.

using detail::absCosIntegral;
using detail::linearSlope;
using detail::parameterOf;
using detail::PieceAt;
using detail::pieceAt;
using detail::Segment;
using detail::segmentAngle;
using detail::segmentMoments;
using detail::shallowSegmentMoments;
using detail::trigRoots;

// Integrated quantities, per unit ζ, about o = −R u + ζ_deep e_z, where z' = ζ − ζ_deep.
struct SliceMoments {
  double area = 0.0;        // A
  double s1 = 0.0;          // S_ξ'
  double s11 = 0.0;         // S_ξ'ξ'
  double s22 = 0.0;         // S_ηη
  double areaZ = 0.0;       // A z'
  double s1Z = 0.0;         // S_ξ' z'
  double areaZZ = 0.0;      // A z'²
  double sideShadow = 0.0;  // ∫|n_s·n| over the slice's wetted arc
  double cutFace = 0.0;     // the chord / s

  SliceMoments& operator+=(const SliceMoments& o) {
    area += o.area;
    s1 += o.s1;
    s11 += o.s11;
    s22 += o.s22;
    areaZ += o.areaZ;
    s1Z += o.s1Z;
    areaZZ += o.areaZZ;
    sideShadow += o.sideShadow;
    cutFace += o.cutFace;
    return *this;
  }
};

// SliceMoments in member order, as the vector-valued quadrature integrates it.
constexpr int kSliceSize = 9;
using SliceVector = Eigen::Matrix<double, kSliceSize, 1>;

SliceVector pack(const SliceMoments& m) {
  SliceVector x;
  x << m.area, m.s1, m.s11, m.s22, m.areaZ, m.s1Z, m.areaZZ, m.sideShadow, m.cutFace;
  return x;
}

SliceMoments unpack(const SliceVector& x) {
  return {x(0), x(1), x(2), x(3), x(4), x(5), x(6), x(7), x(8)};
}

/// The segment of angle θ on radius R and sin θ, remembered for the next call with the same
/// θ: along a cylinder lying parallel to the plane every slice is the same segment.
struct SegmentCache {
  double theta = -1.0;
  Segment g{};
  double sinT = 0.0;
  const Segment& at(double R, double t) {
    if (t != theta) {
      theta = t;
      g = segmentMoments(R, t);
      sinT = std::sin(t);
    }
    return g;
  }
};

SliceVector sliceIntegrand(double R, double s, double theta, double zp, SegmentCache& cache) {
  const Segment g = cache.at(R, theta);
  const double sinT = cache.sinT;
  return pack({g.A, g.S1, g.S11, g.S22, g.A * zp, g.S1 * zp, g.A * zp * zp,
               s * R * 2.0 * (theta <= 0.5 * M_PI ? sinT : 2.0 - sinT), 2.0 * R * sinT / s});
}

struct CylinderSetup {
  double R, L, s, nz, h;
  Vector3d u, v;
  double zetaDeep;
  double depth(double zeta) const { return R + (h - nz * zeta) / s; }  // segment depth d(ζ)
};

// One run of wetted slices along the axis, ζ ∈ [z0, z1]: one connected region of the contact.
// The slices of a run meet: each is the segment of its disc on the plane's side, the segments
// of neighbouring slices overlap, and at a step of the radius the smaller disc's segment lies in
// the larger one's. Two runs are apart: the slices between them are dry.
struct WettedRun {
  double z0 = 0.0, z1 = 0.0;
  SliceMoments m;
  double capArea = 0.0;  // |n_z| × the wetted area of the end faces and steps in the run
};

// The slices integrated over the cylinder's length, with what the projected area needs; for a
// tilted axis also run by run (the caller asks for `runs` by setting a positive join gap).
struct CylinderIntegrals {
  SliceMoments total;
  double relErr = 0.0;
  double capArea = 0.0;  // |n_z| × wetted cap area, both caps
  std::vector<WettedRun> runs;
  double joinGap = 0.0;  // runs closer than this along ζ are one (the round-off of the cuts)

  // The wetted slices of ζ ∈ [z0, z1] (ascending from one call to the next), moments m.
  void add(double z0, double z1, const SliceMoments& m) {
    total += m;
    if (!(joinGap > 0.0)) return;
    if (!runs.empty() && z0 <= runs.back().z1 + joinGap) {
      runs.back().m += m;
      runs.back().z1 = std::max(runs.back().z1, z1);
      return;
    }
    runs.push_back({z0, z1, m, 0.0});
  }
  // A face at ζ, wetted area times |n_z| `shadow`: into the run it bounds.
  void addFace(double zeta, double shadow) {
    capArea += shadow;
    if (!(shadow > 0.0) || runs.empty()) return;
    WettedRun* nearest = &runs.front();
    double best = std::numeric_limits<double>::infinity();
    for (WettedRun& r : runs) {
      const double gap = std::max({0.0, r.z0 - zeta, zeta - r.z1});
      if (gap < best) best = gap, nearest = &r;
    }
    nearest->capArea += shadow;
  }
};

/// Axis along the normal: every slice is a full disc or empty. Wetted length ℓ.
CylinderIntegrals integrateAxisAlongNormal(CylinderSetup& c, double depth) {
  const double R = c.R, L = c.L;
  const double ell = std::min(depth / std::abs(c.nz), L);
  const double A = M_PI * R * R;
  CylinderIntegrals out;
  out.total.area = A * ell;
  out.total.s1 = A * R * ell;
  out.total.s11 = 1.25 * M_PI * R * R * R * R * ell;
  out.total.s22 = 0.25 * M_PI * R * R * R * R * ell;
  out.total.areaZ = A * ell * ell / 2.0;
  out.total.s1Z = A * R * ell * ell / 2.0;
  out.total.areaZZ = A * ell * ell * ell / 3.0;
  c.u = Vector3d::UnitX();
  c.v = Vector3d::UnitY();
  // Seen along n: the deep cap, plus the cut face while the plane crosses the body, or
  // the far cap once the cylinder is wholly sunk.
  out.capArea = ell < L ? A : 2.0 * A;
  out.total.cutFace = ell < L ? A : 0.0;
  return out;
}

/// Sorted ζ in [z0, z1] (a constant piece of radius c.R) where the integrand is not smooth:
/// the piece's ends, the tangencies (returned in `tangency` too) and the axis crossing.
std::vector<double> sliceCuts(const CylinderSetup& c, double z0, double z1,
                              std::vector<double>& tangency) {
  std::vector<double> cuts = {z0, z1};
  if (c.nz != 0.0) {
    for (double zeta : {(c.h + c.s * c.R) / c.nz, (c.h - c.s * c.R) / c.nz}) {
      if (zeta > z0 && zeta < z1) {
        cuts.push_back(zeta);
        tangency.push_back(zeta);
      }
    }
    // Where the cut passes the axis (d = R, θ = π/2) the side-shadow term switches from
    // 2 sin θ to 2(2 − sin θ): continuous with its slope, but its curvature jumps, and an
    // adaptive rule would bisect towards that point for a long time. Cut there instead.
    const double axis = c.h / c.nz;
    if (axis > z0 && axis < z1) cuts.push_back(axis);
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

/// Full discs on ζ ∈ [a, b]: polynomial in z'.
SliceMoments fullDiscs(const CylinderSetup& c, double a, double b) {
  const double R = c.R;
  const double za = a - c.zetaDeep, zb = b - c.zetaDeep;
  const double A = M_PI * R * R, len = b - a;
  const double p1 = (zb * zb - za * za) / 2.0, p2 = (zb * zb * zb - za * za * za) / 3.0;
  return {A * len,
          A * R * len,
          1.25 * A * R * R * len,
          0.25 * A * R * R * len,
          A * p1,
          A * R * p1,
          A * p2,
          4.0 * c.s * R * len,
          0.0};
}

/// Segment slices on ζ ∈ [a, b], integrated adaptively in θ or ζ.
QuadratureResult<kSliceSize> integrateSegments(const CylinderSetup& c, double a, double b,
                                               bool tangentA, bool tangentB) {
  const double R = c.R;
  SegmentCache cache;
  const double ta = tangentA ? (c.depth(a) < R ? 0.0 : M_PI) : segmentAngle(R, c.depth(a));
  const double tb = tangentB ? (c.depth(b) < R ? 0.0 : M_PI) : segmentAngle(R, c.depth(b));
  // θ is the better variable where d runs close to 0 (or 2R) relative to its range: the
  // slice moments go like d^{3/2} there. ζ is kept where θ barely moves (the axis almost
  // parallel to the plane), since ζ(θ) would then be ill-conditioned.
  const double tLo = std::min(ta, tb), tHi = std::max(ta, tb);
  const bool nearTangency = tLo < kThetaRatio * tHi || (M_PI - tHi) < kThetaRatio * (M_PI - tLo);
  if (tangentA || tangentB || (nearTangency && tHi - tLo > kMinThetaRange)) {
    // ζ(θ) − a = (sR/n_z)(cos θ − cos θ_a), the difference of cosines written as a
    // product so that it keeps its digits; |dζ/dθ| = sR sin θ / |n_z|.
    auto f = [&](double theta) -> SliceVector {
      const double dcos = -2.0 * std::sin(0.5 * (theta + ta)) * std::sin(0.5 * (theta - ta));
      const double zeta = a + c.s * R * dcos / c.nz;
      return sliceIntegrand(R, c.s, theta, zeta - c.zetaDeep, cache) *
             (c.s * R * std::sin(theta) / std::abs(c.nz));
    };
    return integrateAdaptive<kSliceSize>(f, tLo, tHi, kQuadratureTolerance);
  }
  auto f = [&](double zeta) -> SliceVector {
    return sliceIntegrand(R, c.s, segmentAngle(R, c.depth(zeta)), zeta - c.zetaDeep, cache);
  };
  return integrateAdaptive<kSliceSize>(f, a, b, kQuadratureTolerance);
}

// ---------------------------------------------------------------------------------------
// Profiles. A piece is walked by a parameter t: ζ itself on constant and linear pieces, the
// angle α on an arc (ζ = z_c + a sin α, r = ρ_c + σ a cos α, α ∈ [−π/2, π/2]), in which the
// arc's radius stays smooth where its slope dr/dζ is infinite (a fillet meeting an end face).
// The slice of a radius r ≠ R is taken about its own edge point ξ = −r and moved to the
// common origin ξ = −R (R the largest radius) by δ = R − r.

/// The half-space n·p ≤ h in the solid's frame, n = s u + n_z e_z, and the moments' origin
/// o = −rRef u + zetaDeep e_z.
struct Revolution {
  double s, nz, h;
  double rRef = 0.0, zetaDeep = 0.0;
  Vector3d u = Vector3d::UnitX(), v = Vector3d::UnitY();
  double w(double zeta) const { return (h - nz * zeta) / s; }  // the cut at ξ ≤ w
};

/// Moments of a slice about its own edge point moved to the common origin, δ further out.
SliceMoments shifted(SliceMoments m, double delta) {
  if (delta == 0.0) return m;
  m.s11 += 2.0 * delta * m.s1 + delta * delta * m.area;
  m.s1 += delta * m.area;
  m.s1Z += delta * m.areaZ;
  return m;
}

/// The slice at a point of a curved piece, times dζ/dt, for the segment of angle θ (π: the
/// whole disc), sin θ and cos θ given.
SliceVector curvedSlice(const Revolution& rv, const PieceAt& e, double theta, double sinT,
                        double cosT) {
  const double r = e.r;
  const bool full = theta == M_PI;
  const Segment g = shallowSegmentMoments(r, theta);
  const double zp = e.zeta - rv.zetaDeep;
  SliceMoments m{g.A, g.S1, g.S11, g.S22, g.A * zp, g.S1 * zp, g.A * zp * zp, 0.0, 0.0};
  SliceVector x = pack(shifted(m, rv.rRef - r)) * e.J;
  // The side's shadow: its element r(e_r − r' e_z) dψ dζ against n, over the wetted arc.
  x(7) = 2.0 * r * absCosIntegral(rv.s * e.J, e.drdt * rv.nz, theta, sinT, cosT);
  x(8) = full ? 0.0 : 2.0 * r * sinT / rv.s * e.J;
  return x;
}

SliceVector curvedSlice(const Revolution& rv, const PieceAt& e, double theta) {
  return curvedSlice(rv, e, theta, std::sin(theta), std::cos(theta));
}

double angleOf(double r, double d) { return r > 0.0 ? segmentAngle(r, d) : 0.0; }

/// An arc's segment depth d = r + w at α = tA + off, from its value at a singular end tA (0, or 2r
/// where the segment fills the disc) plus its change, so that near a tangency it keeps its
/// digits: r + w itself would be the difference of two numbers of the size of ζ, and near an
/// axis along the normal the whole segment interval is narrower than their rounding.
double anchoredDepth(const Revolution& rv, const ProfilePiece& p, double tA, double off) {
  const PieceAt e = pieceAt(p, tA);
  const double dA = e.r + rv.w(e.zeta) > e.r ? 2.0 * e.r : 0.0;
  // sin t − sin tA and cos t − cos tA as products
  const double half = std::sin(0.5 * off), mean = tA + 0.5 * off;
  const double dz = 2.0 * p.a * std::cos(mean) * half;
  const double dr = -2.0 * p.sign * p.a * std::sin(mean) * half;
  return dA + dr - rv.nz / rv.s * dz;
}

/// The parameters in (t0, t1) of an arc where a slice's segment appears (d = 0) or
/// fills the disc (w = r): `singular`, the slice moments go like a power 3/2 there; and
/// where the cut passes the axis (w = 0), where the side's shadow has a kink.
void curvedCuts(const Revolution& rv, const ProfilePiece& p, double t0, double t1,
                std::vector<double>& singular, std::vector<double>& plain) {
  const double s = rv.s, nz = rv.nz, h = rv.h;
  const double base = h - nz * p.z_c, sa = p.sign * s * p.a;
  trigRoots(sa, -nz * p.a, -(s * p.rho_c + base), t0, t1, singular);
  trigRoots(sa, nz * p.a, base - s * p.rho_c, t0, t1, singular);
  if (nz != 0.0 && std::abs(base / (nz * p.a)) < 1.0) {
    const double alpha = std::asin(base / (nz * p.a));
    if (alpha > t0 && alpha < t1) plain.push_back(alpha);
  }
}

/// A curved piece's slices on t ∈ [a, b] (a segment of an arc, or whole discs), after t = a + (b −
/// a)u² at a singular end a (and its mirror at b, or t = a + (b − a)(1 − cos πu)/2 at both), which
/// makes a (t − a)^{3/2} end behaviour smooth in u.
QuadratureResult<kSliceSize> integrateCurved(const Revolution& rv, const ProfilePiece& p, double a,
                                             double b, bool singA, bool singB, bool full) {
  if (full || (!singA && !singB)) {
    const auto at = [&](double t) {
      const PieceAt e = pieceAt(p, t);
      return curvedSlice(rv, e, full ? M_PI : angleOf(e.r, e.r + rv.w(e.zeta)));
    };
    return integrateAdaptive<kSliceSize>(at, a, b, kQuadratureTolerance);
  }
  // t = tA + off with the offset from the nearer singular end, computed without cancellation.
  const auto at = [&](double tA, double off) {
    const PieceAt e = pieceAt(p, tA + off);
    return curvedSlice(rv, e, angleOf(e.r, anchoredDepth(rv, p, tA, off)));
  };
  return integrateSingularEnds<kSliceSize>(at, a, b, singA, singB, kQuadratureTolerance);
}

void addArcPiece(const Revolution& rv, const ProfilePiece& p, CylinderIntegrals& out) {
  const double t0 = parameterOf(p, p.z0), t1 = parameterOf(p, p.z1);
  std::vector<double> singular, plain;
  curvedCuts(rv, p, t0, t1, singular, plain);
  std::vector<double> cuts = {t0, t1};
  cuts.insert(cuts.end(), singular.begin(), singular.end());
  cuts.insert(cuts.end(), plain.begin(), plain.end());
  std::sort(cuts.begin(), cuts.end());
  const auto isSingular = [&](double t) {
    return std::find(singular.begin(), singular.end(), t) != singular.end();
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (!(b > a)) continue;
    const PieceAt mid = pieceAt(p, 0.5 * (a + b));
    const double d = mid.r + rv.w(mid.zeta);
    if (d <= 0.0 || !(mid.r > 0.0)) continue;
    const QuadratureResult<kSliceSize> q =
        integrateCurved(rv, p, a, b, isSingular(a), isSingular(b), d >= 2.0 * mid.r);
    out.add(pieceAt(p, a).zeta, pieceAt(p, b).zeta, unpack(q.value));
    out.relErr = std::max(out.relErr, q.relative_error);
  }
}

/// A linear piece (a cone), tilted axis. d and r are linear in ζ, so θ is monotone along the
/// piece and ζ(θ) is closed: from the root ζ_A of d (extended beyond the piece if need be),
/// ζ(θ) − ζ_A = s r_A (1 − cos θ)/(s k cos θ − n_z). The segments are integrated in θ, as the
/// cylinder's are near a tangency, between the θ of the piece's ends (split at π/2, where the
/// side's shadow has a kink), and the whole discs in ζ from ζ(π): no width of a segment
/// interval comes from a difference of ζ, which near an axis along the normal is narrower
/// than their rounding.
void addLinearPiece(const Revolution& rv, const ProfilePiece& p, CylinderIntegrals& out) {
  const double k = linearSlope(p), s = rv.s;
  const double x0 = (s * p.r0 + rv.h - rv.nz * p.z0) / (rv.nz - s * k);  // s·d = 0
  const double th0 = angleOf(p.r0, p.r0 + rv.w(p.z0)), th1 = angleOf(p.r1, p.r1 + rv.w(p.z1));
  const double lo = std::min(th0, th1), hi = std::max(th0, th1);
  // d is linear in ζ: the piece's wetted slices are one interval, from an end or the root of d
  const double d0 = p.r0 + rv.w(p.z0), d1 = p.r1 + rv.w(p.z1);
  const double root =
      d0 != d1 ? std::clamp(p.z0 + (p.z1 - p.z0) * d0 / (d0 - d1), p.z0, p.z1) : p.z0;
  const double wet0 = d0 > 0.0 ? p.z0 : root, wet1 = d1 > 0.0 ? p.z1 : root;
  const auto add = [&](const QuadratureResult<kSliceSize>& q) {
    out.add(wet0, wet1, unpack(q.value));
    out.relErr = std::max(out.relErr, q.relative_error);
  };
  // As for the cylinder: θ where the segment runs close to a tangency relative to its range,
  // ζ where θ barely moves (then ζ_A is far away and ζ(θ) ill-conditioned).
  const bool nearTangency = lo < kThetaRatio * hi || (M_PI - hi) < kThetaRatio * (M_PI - lo);
  if (!std::isfinite(x0) || !nearTangency || hi - lo <= kMinThetaRange) {
    if (hi > 0.0) add(integrateCurved(rv, p, p.z0, p.z1, false, false, lo == M_PI));
    return;
  }
  const double zA = p.z0 + x0, rA = p.r0 + k * x0;
  const auto zetaOf = [&](double theta) {
    const double h = std::sin(0.5 * theta);
    return zA + 2.0 * s * rA * h * h / (s * k * std::cos(theta) - rv.nz);
  };
  const auto f = [&](double theta) -> SliceVector {
    // one sine: sin²(θ/2) keeps its digits near θ = 0, cos θ = 1 − 2 sin²(θ/2)
    const double h = std::sin(0.5 * theta), h2 = h * h;
    const double sinT = 2.0 * h * std::sqrt(1.0 - h2), cosT = 1.0 - 2.0 * h2;
    const double N = 2.0 * rA * h2;
    const double D = s * k * cosT - rv.nz;
    const double dzdt = s * sinT * (rA * D + N * s * k) / (D * D);
    return curvedSlice(rv, pieceAt(p, zA + s * N / D), theta, sinT, cosT) * std::abs(dzdt);
  };
  for (const auto& [a, b] :
       {std::pair{lo, std::min(hi, 0.5 * M_PI)}, std::pair{std::max(lo, 0.5 * M_PI), hi}})
    if (b > a) add(integrateAdaptive<kSliceSize>(f, a, b, kQuadratureTolerance));
  if (hi < M_PI) return;
  // The whole discs, from where the segment fills the disc to the piece's end beyond it.
  const double zFull = std::clamp(zetaOf(M_PI), p.z0, p.z1);
  const double a = th0 == M_PI ? p.z0 : zFull,
               b = th0 == M_PI ? (th1 == M_PI ? p.z1 : zFull) : p.z1;
  if (b > a) add(integrateCurved(rv, p, a, b, false, false, true));
}

/// A constant piece, tilted axis: the cylinder's slices between its cuts.
void addConstantPiece(const Revolution& rv, const ProfilePiece& p, CylinderIntegrals& out) {
  const CylinderSetup c{p.r0, p.z1 - p.z0, rv.s, rv.nz, rv.h, rv.u, rv.v, rv.zetaDeep};
  const double R = c.R, delta = rv.rRef - R;
  std::vector<double> tangency;
  const std::vector<double> cuts = sliceCuts(c, p.z0, p.z1, tangency);
  auto isTangency = [&](double z) {
    return std::find(tangency.begin(), tangency.end(), z) != tangency.end();
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (!(b > a)) continue;
    const double dMid = c.depth(0.5 * (a + b));
    if (dMid <= 0.0) continue;
    if (dMid >= 2.0 * R) {
      out.add(a, b, shifted(fullDiscs(c, a, b), delta));
      continue;
    }
    const QuadratureResult<kSliceSize> r = integrateSegments(c, a, b, isTangency(a), isTangency(b));
    out.add(a, b, shifted(unpack(r.value), delta));
    out.relErr = std::max(out.relErr, r.relative_error);
  }
}

/// Wetted area of the plane of a slice at ζ between radii rIn and rOut (an end face: rIn = 0;
/// a step between two pieces), times |n_z|: its shadow along n.
double faceShadow(const Revolution& rv, double zeta, double rIn, double rOut) {
  const auto wetted = [&](double r) {
    return r > 0.0 ? segmentMoments(r, segmentAngle(r, r + (rv.h - rv.nz * zeta) / rv.s)).A : 0.0;
  };
  return std::abs(rv.nz) * std::abs(wetted(rOut) - wetted(rIn));
}

/// Radii on both sides of each breakpoint of the profile: 0 outside it.
struct Breakpoint {
  double zeta, rBelow, rAbove;
};

std::vector<Breakpoint> breakpoints(const RevolutionProfile& profile) {
  std::vector<Breakpoint> out;
  double below = 0.0;
  for (const ProfilePiece& p : profile) {
    out.push_back({p.z0, below, pieceAt(p, parameterOf(p, p.z0)).r});
    below = pieceAt(p, parameterOf(p, p.z1)).r;
  }
  out.push_back({profile.back().z1, below, 0.0});
  return out;
}

CylinderIntegrals integrateTilted(Revolution& rv, const Vector3d& n_C,
                                  const RevolutionProfile& profile) {
  rv.u = Vector3d(n_C.x() / rv.s, n_C.y() / rv.s, 0.0);
  rv.v = Vector3d::UnitZ().cross(rv.u);
  CylinderIntegrals out;
  // One piece whose radius is linear or concave in ζ (a cylinder, a cone, a sphere, a torus'
  // outer half) has a concave slice depth d(ζ), wetted in one run: no runs to keep.
  const bool oneRun =
      profile.size() == 1 && (profile[0].kind != ProfilePiece::Kind::kArc || profile[0].sign > 0.0);
  if (!oneRun) out.joinGap = kRunJoinFraction * (profile.back().z1 - profile.front().z0);
  for (const ProfilePiece& p : profile) {
    if (p.kind == ProfilePiece::Kind::kConstant) {
      addConstantPiece(rv, p, out);
    } else if (p.kind == ProfilePiece::Kind::kLinear) {
      addLinearPiece(rv, p, out);
    } else {
      addArcPiece(rv, p, out);
    }
  }
  for (const Breakpoint& b : breakpoints(profile))
    out.addFace(b.zeta,
                faceShadow(rv, b.zeta, std::min(b.rBelow, b.rAbove), std::max(b.rBelow, b.rAbove)));
  return out;
}

/// Axis along the normal, several pieces: whole discs where n_z ζ ≤ h.
CylinderIntegrals integrateAlongNormal(Revolution& rv, const RevolutionProfile& profile) {
  const double cut = rv.h / rv.nz;
  CylinderIntegrals out;
  for (const ProfilePiece& p : profile) {
    const double a = rv.nz > 0.0 ? p.z0 : std::max(p.z0, cut);
    const double b = rv.nz > 0.0 ? std::min(p.z1, cut) : p.z1;
    if (!(b > a)) continue;
    if (p.kind == ProfilePiece::Kind::kConstant) {
      const CylinderSetup c{p.r0, p.z1 - p.z0, rv.s, rv.nz, rv.h, rv.u, rv.v, rv.zetaDeep};
      out.total += shifted(fullDiscs(c, a, b), rv.rRef - p.r0);
      continue;
    }
    const QuadratureResult<kSliceSize> q =
        integrateCurved(rv, p, parameterOf(p, a), parameterOf(p, b), false, false, true);
    out.total += unpack(q.value);
    out.relErr = std::max(out.relErr, q.relative_error);
  }
  for (const Breakpoint& b : breakpoints(profile))
    if (rv.nz * b.zeta < rv.h)
      out.capArea += std::abs(rv.nz) * M_PI * std::abs(b.rAbove * b.rAbove - b.rBelow * b.rBelow);
  for (const ProfilePiece& p : profile)
    if (cut > p.z0 && cut < p.z1) out.total.cutFace = M_PI * std::pow(profileRadius(p, cut), 2);
  return out;
}

/// The deepest point's depth below the plane, h − min n·p over the solid's slices in
/// ζ ∈ [z0, z1] (all of them by default).
double deepest(const Revolution& rv, const RevolutionProfile& profile,
               double z0 = -std::numeric_limits<double>::infinity(),
               double z1 = std::numeric_limits<double>::infinity()) {
  double depth = -std::numeric_limits<double>::infinity();
  const auto at = [&](const PieceAt& e) {
    depth = std::max(depth, rv.h + rv.s * e.r - rv.nz * e.zeta);
  };
  for (const ProfilePiece& p : profile) {
    if (p.z1 < z0 || p.z0 > z1) continue;
    const double t0 = parameterOf(p, std::max(p.z0, z0)), t1 = parameterOf(p, std::min(p.z1, z1));
    at(pieceAt(p, t0));
    at(pieceAt(p, t1));
    // An arc's outer half is deepest where its normal is −n: α = atan2(−n_z, s).
    const double alpha = std::atan2(-rv.nz, rv.s);
    if (p.kind == ProfilePiece::Kind::kArc && p.sign > 0.0 && alpha > t0 && alpha < t1)
      at(pieceAt(p, alpha));
  }
  return depth;
}

// One region from its integrated slices: moments about o in C, m1 = S_ξ' u + (∫A z') e_z, m2
// assembled from the slice terms; the projected area of a convex region, half of ∫|n_s·n| over
// its boundary. Not in contact when V is not positive.
ContactVolume regionOf(const Revolution& rv, const SliceMoments& total, double capArea,
                       double depth, double relErr, const Isometry3d& X_WC, const Vector3d& n_W) {
  const double V = total.area;
  if (!(V > 0.0)) return ContactVolume{.method = Method::kAnalytic};
  const Vector3d& u = rv.u;
  const Vector3d& v = rv.v;
  const Vector3d e = Vector3d::UnitZ();
  geometry::Moments M;
  M.m0 = V;
  M.m1 = total.s1 * u + total.areaZ * e;
  M.m2 = total.s11 * u * u.transpose() + total.s22 * v * v.transpose() +
         total.s1Z * (u * e.transpose() + e * u.transpose()) + total.areaZZ * e * e.transpose();
  const Vector3d o = -rv.rRef * u + rv.zetaDeep * e;
  const double area = 0.5 * (total.sideShadow + total.cutFace + capArea);
  // o and the offset are mapped separately: o + offset would round the offset (~d) against
  // the radius, losing digits for shallow contact.
  ContactVolume cv = contactFromMoments(M, o, X_WC, n_W, area, depth, Method::kAnalytic);
  cv.relative_error = relErr;
  return cv;
}

ContactPatches revolutionInOwnFrame(const RevolutionProfile& profile, const Vector3d& n_C, double h,
                                    const Isometry3d& X_WC, const Vector3d& n_W) {
  Revolution rv{std::hypot(n_C.x(), n_C.y()), n_C.z(), h};
  rv.zetaDeep = rv.nz > 0.0 ? profile.front().z0 : profile.back().z1;
  for (const Breakpoint& b : breakpoints(profile))
    rv.rRef = std::max({rv.rRef, b.rBelow, b.rAbove});
  for (const ProfilePiece& p : profile)
    if (p.kind == ProfilePiece::Kind::kArc && p.sign > 0.0 && p.z0 <= p.z_c && p.z_c <= p.z1)
      rv.rRef = std::max(rv.rRef, p.rho_c + p.a);
  const double depth = deepest(rv, profile);
  if (!(depth > 0.0)) return singlePatch(ContactVolume{.method = Method::kAnalytic});

  const bool cylinder = profile.size() == 1 && profile[0].kind == ProfilePiece::Kind::kConstant;
  CylinderIntegrals in;
  if (rv.s != 0.0) {
    in = integrateTilted(rv, n_C, profile);
  } else if (cylinder) {
    CylinderSetup c{rv.rRef, profile[0].z1 - profile[0].z0, 0.0, rv.nz, h, {}, {}, rv.zetaDeep};
    in = integrateAxisAlongNormal(c, depth);
  } else {
    in = integrateAlongNormal(rv, profile);  // the wetted slices: one run from the deep end
  }
  ContactPatches out = singlePatch(regionOf(rv, in.total, in.capArea, depth, in.relErr, X_WC, n_W));
  if (in.runs.size() < 2 || !out.inContact()) return out;
  // Several runs: each its own region, the aggregate as computed over all of them.
  out.patches.clear();
  for (const WettedRun& r : in.runs) {
    const ContactVolume cv =
        regionOf(rv, r.m, r.capArea, deepest(rv, profile, r.z0, r.z1), in.relErr, X_WC, n_W);
    if (cv.inContact()) out.patches.push_back(cv);
  }
  sortPatches(out.patches);
  return out;
}

}  // namespace

RevolutionProfile cylinderProfile(double radius, double length) {
  ProfilePiece p;
  p.z0 = -0.5 * length;
  p.z1 = 0.5 * length;
  p.r0 = p.r1 = radius;
  return {p};
}

ContactPatches revolutionHalfspacePatches(const RevolutionProfile& profile, const Isometry3d& X_WR,
                                          const Isometry3d& X_WH) {
  detail::checkProfile(profile, "revolutionHalfspace");
  const Isometry3d X_HR = X_WH.inverse() * X_WR;
  // z_H = n_R·p_R + t_z ≤ 0  ⇔  n_R·p_R ≤ h = −t_z, with n_R the third row of R_HR.
  const Vector3d n_R = X_HR.linear().row(2).transpose();
  return revolutionInOwnFrame(profile, n_R, -X_HR.translation().z(), X_WR, X_WH.linear().col(2));
}

ContactVolume revolutionHalfspace(const RevolutionProfile& profile, const Isometry3d& X_WR,
                                  const Isometry3d& X_WH) {
  return revolutionHalfspacePatches(profile, X_WR, X_WH).aggregate;
}

}  // namespace vcontact::volume
