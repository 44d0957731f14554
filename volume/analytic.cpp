#include "volume/analytic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/quadrature.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

// Relative tolerance asked of the quadrature. The G7/K15 difference it is checked against
// overstates the K15 error of a smooth integrand by orders of magnitude, so 1e-11 here
// delivers the 1e-9 the backend promises with margin.
constexpr double kQuadratureTolerance = 1e-11;
// Integrate in θ when an end of the piece has θ below this fraction of the other end's
// (d^{3/2} behaviour dominates), unless the θ range is too narrow to carry ζ accurately.
constexpr double kThetaRatio = 0.5;
constexpr double kMinThetaRange = 1e-6;

// ---------------------------------------------------------------------------------------
// Sphere (MODEL.md §5). u is the height above the sphere's lowest point, u ∈ [0, d]; the
// slice at u is a disc of area π(2Ru − u²). All moments are polynomials in d.

ContactVolume sphereInHalfspaceFrame(double R, const Vector3d& c_H, const Isometry3d& X_WH) {
  const double d = std::min(R - c_H.z(), 2.0 * R);  // penetration of the lowest point
  if (!(d > 0.0)) return ContactVolume{.method = Method::kAnalytic};
  const double d2 = d * d, d3 = d2 * d;
  const double V = M_PI * d2 * (3.0 * R - d) / 3.0;
  const double uBar = d * (8.0 * R - 3.0 * d) / (4.0 * (3.0 * R - d));  // centroid height
  // ∫u² dV − V ū², with ∫u² dV = π(R d⁴/2 − d⁵/5).
  const double Suu = M_PI * d2 * d2 * (R / 2.0 - d / 5.0) - V * uBar * uBar;
  const double Jnn = M_PI * d3 * (20.0 * R * R - 15.0 * R * d + 3.0 * d2) / 30.0;  // polar
  Matrix3d Sigma_H = Vector3d(Jnn / 2.0, Jnn / 2.0, Suu).asDiagonal();
  const Vector3d p_H(c_H.x(), c_H.y(), c_H.z() - R + uBar);
  const double area = d <= R ? M_PI * d * (2.0 * R - d) : M_PI * R * R;
  const Matrix3d R_WH = X_WH.linear();
  return assembleContactVolume(V, X_WH * p_H, R_WH * Sigma_H * R_WH.transpose(), R_WH.col(2), area,
                               d, Method::kAnalytic);
}

// ---------------------------------------------------------------------------------------
// Cylinder. In the cylinder frame C the half-space is {p : n·p ≤ h}. Write n = s u + n_z e_z
// with u a unit vector in the xy plane and v = e_z × u. The slice at height ζ is the disc
// x² + y² ≤ R² cut by ξ ≤ w(ζ) = (h − n_z ζ)/s, where ξ = p·u: a circular segment of depth
// d(ζ) = R + w(ζ) from the disc's edge at ξ = −R. With ξ = −R cos φ (φ ∈ [0, θ],
// d = R(1 − cos θ)) the segment moments about the edge point ξ' = ξ + R = 0 are
//   A      = 2R² ∫ sin²φ,           S_ξ'  = 2R³ ∫ (1 − cos φ) sin²φ,
//   S_ξ'ξ' = 2R⁴ ∫ (1 − cos φ)² sin²φ,  S_ηη = (2/3)R⁴ ∫ sin⁴φ.
// (closed forms below, with a series where they would cancel as θ → 0).
// The slices are then integrated over ζ adaptively, in θ where an end of the interval is
// a tangency (d = 0 or d = 2R: there the slice moments behave like d^{3/2} in ζ but are
// smooth in θ), otherwise in ζ itself.

// Each integrand is a trigonometric polynomial Σ_k a_k cos kφ (k ≤ 4):
//   sin²φ                 = 1/2 − cos 2φ/2
//   (1 − cos φ) sin²φ     = 1/2 − cos φ/4 − cos 2φ/2 + cos 3φ/4
//   (1 − cos φ)² sin²φ    = 5/8 − cos φ/2 − cos 2φ/2 + cos 3φ/2 − cos 4φ/8
//   sin⁴φ                 = 3/8 − cos 2φ/2 + cos 4φ/8
// so ∫_0^θ = a_0 θ + Σ_k a_k sin kθ / k, from one sincos and the multiple-angle recurrence.
// For small θ those terms cancel down to the θ³…θ⁷ leading order; there the Taylor series
//   ∫_0^θ = Σ_j (−1)^j θ^{2j+1}/(2j+1)! · Σ_k a_k k^{2j}
// is used instead: its coefficients are exact (k ≤ 4, a_k in eighths) and its terms do not
// cancel. Switching at θ = 0.75 keeps both sides within ~1e-13 relative.
constexpr int kTrigTerms = 5;
using TrigPoly = std::array<double, kTrigTerms>;  // a_0 … a_4
constexpr TrigPoly kSin2 = {0.5, 0.0, -0.5, 0.0, 0.0};
constexpr TrigPoly kOmcSin2 = {0.5, -0.25, -0.5, 0.25, 0.0};
constexpr TrigPoly kOmc2Sin2 = {0.625, -0.5, -0.5, 0.5, -0.125};
constexpr TrigPoly kSin4 = {0.375, 0.0, -0.5, 0.0, 0.125};
constexpr double kSeriesBelow = 0.75;
constexpr int kSeriesTerms = 18;  // (4·0.75)^{37}/37! < 1e-17

double integrateClosed(const TrigPoly& a, double theta,
                       const std::array<double, kTrigTerms>& sinK) {
  double sum = a[0] * theta;
  for (int k = 1; k < kTrigTerms; ++k) sum += a[k] * sinK[k] / k;
  return sum;
}

/// Σ_k a_k k^{2j} for j < kSeriesTerms: the series coefficients, exact in binary.
std::array<double, kSeriesTerms> seriesMoments(const TrigPoly& a) {
  std::array<double, kSeriesTerms> m{};
  for (int j = 0; j < kSeriesTerms; ++j) {
    m[j] = j == 0 ? a[0] : 0.0;
    for (int k = 1; k < kTrigTerms; ++k) m[j] += a[k] * std::pow(static_cast<double>(k), 2 * j);
  }
  return m;
}

double integrateSeries(const std::array<double, kSeriesTerms>& m, double theta) {
  double sum = 0.0, power = theta;  // θ^{2j+1}/(2j+1)!
  for (int j = 0; j < kSeriesTerms; ++j) {
    sum += (j % 2 == 0 ? power : -power) * m[j];
    power *= theta * theta / ((2.0 * j + 2.0) * (2.0 * j + 3.0));
  }
  return sum;
}

struct Segment {
  double A, S1, S11, S22;  // area, ∫ξ', ∫ξ'², ∫η² (about the edge point)
};

Segment segmentMoments(double R, double theta) {
  double i20, i21, i22, i40;
  if (theta < kSeriesBelow) {
    static const auto m20 = seriesMoments(kSin2), m21 = seriesMoments(kOmcSin2),
                      m22 = seriesMoments(kOmc2Sin2), m40 = seriesMoments(kSin4);
    i20 = integrateSeries(m20, theta);
    i21 = integrateSeries(m21, theta);
    i22 = integrateSeries(m22, theta);
    i40 = integrateSeries(m40, theta);
  } else {
    std::array<double, kTrigTerms> sinK{};
    const double s1 = std::sin(theta), c1 = std::cos(theta);
    double sPrev = 0.0, sCur = s1;
    sinK[1] = s1;
    for (int k = 2; k < kTrigTerms; ++k) {  // sin kθ = 2 cos θ sin (k−1)θ − sin (k−2)θ
      const double next = 2.0 * c1 * sCur - sPrev;
      sPrev = sCur;
      sCur = next;
      sinK[k] = sCur;
    }
    i20 = integrateClosed(kSin2, theta, sinK);
    i21 = integrateClosed(kOmcSin2, theta, sinK);
    i22 = integrateClosed(kOmc2Sin2, theta, sinK);
    i40 = integrateClosed(kSin4, theta, sinK);
  }
  const double R2 = R * R;
  return {2.0 * R2 * i20, 2.0 * R2 * R * i21, 2.0 * R2 * R2 * i22, (2.0 / 3.0) * R2 * R2 * i40};
}

/// θ with d = R(1 − cos θ), accurate for small d; d is clamped to [0, 2R].
double segmentAngle(double R, double d) {
  const double r = std::clamp(d / (2.0 * R), 0.0, 1.0);
  return 2.0 * std::asin(std::sqrt(r));
}

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

SliceVector sliceIntegrand(double R, double s, double theta, double zp) {
  const Segment g = segmentMoments(R, theta);
  const double sinT = std::sin(theta);
  return pack({g.A, g.S1, g.S11, g.S22, g.A * zp, g.S1 * zp, g.A * zp * zp,
               s * R * 2.0 * (theta <= 0.5 * M_PI ? sinT : 2.0 - sinT), 2.0 * R * sinT / s});
}

struct CylinderSetup {
  double R, L, s, nz, h;
  Vector3d u, v;
  double zetaDeep;
  double depth(double zeta) const { return R + (h - nz * zeta) / s; }  // segment depth d(ζ)
};

// The slices integrated over the cylinder's length, with what the projected area needs.
struct CylinderIntegrals {
  SliceMoments total;
  double relErr = 0.0;
  double capArea = 0.0;  // |n_z| × wetted cap area, both caps
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

/// Sorted ζ where the integrand is not smooth: the caps, the tangencies (returned in
/// `tangency` too) and the axis crossing.
std::vector<double> sliceCuts(const CylinderSetup& c, std::vector<double>& tangency) {
  const double L = c.L;
  std::vector<double> cuts = {-0.5 * L, 0.5 * L};
  if (c.nz != 0.0) {
    for (double zeta : {(c.h + c.s * c.R) / c.nz, (c.h - c.s * c.R) / c.nz}) {
      if (zeta > -0.5 * L && zeta < 0.5 * L) {
        cuts.push_back(zeta);
        tangency.push_back(zeta);
      }
    }
    // Where the cut passes the axis (d = R, θ = π/2) the side-shadow term switches from
    // 2 sin θ to 2(2 − sin θ): continuous with its slope, but its curvature jumps, and an
    // adaptive rule would bisect towards that point for a long time. Cut there instead.
    const double axis = c.h / c.nz;
    if (axis > -0.5 * L && axis < 0.5 * L) cuts.push_back(axis);
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
      return sliceIntegrand(R, c.s, theta, zeta - c.zetaDeep) *
             (c.s * R * std::sin(theta) / std::abs(c.nz));
    };
    return integrateAdaptive<kSliceSize>(f, tLo, tHi, kQuadratureTolerance);
  }
  auto f = [&](double zeta) -> SliceVector {
    return sliceIntegrand(R, c.s, segmentAngle(R, c.depth(zeta)), zeta - c.zetaDeep);
  };
  return integrateAdaptive<kSliceSize>(f, a, b, kQuadratureTolerance);
}

/// General axis: circular-segment slices, integrated piece by piece between the cuts.
CylinderIntegrals integrateTiltedAxis(CylinderSetup& c, const Vector3d& n_C) {
  const double R = c.R, L = c.L;
  c.u = Vector3d(n_C.x() / c.s, n_C.y() / c.s, 0.0);
  c.v = Vector3d::UnitZ().cross(c.u);
  std::vector<double> tangency;
  const std::vector<double> cuts = sliceCuts(c, tangency);
  auto isTangency = [&](double z) {
    return std::find(tangency.begin(), tangency.end(), z) != tangency.end();
  };
  CylinderIntegrals out;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (!(b > a)) continue;
    const double dMid = c.depth(0.5 * (a + b));
    if (dMid <= 0.0) continue;
    if (dMid >= 2.0 * R) {
      out.total += fullDiscs(c, a, b);
      continue;
    }
    const QuadratureResult<kSliceSize> r = integrateSegments(c, a, b, isTangency(a), isTangency(b));
    out.total += unpack(r.value);
    out.relErr = std::max(out.relErr, r.relative_error);
  }
  for (double zeta : {-0.5 * L, 0.5 * L}) {
    out.capArea += std::abs(c.nz) * segmentMoments(R, segmentAngle(R, c.depth(zeta))).A;
  }
  return out;
}

ContactVolume cylinderInOwnFrame(double R, double L, const Vector3d& n_C, double h,
                                 const Isometry3d& X_WC, const Vector3d& n_W) {
  CylinderSetup c{R, L, std::hypot(n_C.x(), n_C.y()), n_C.z(), h, {}, {}, 0.0};
  c.zetaDeep = c.nz > 0.0 ? -0.5 * L : 0.5 * L;
  const double depth = h + c.s * R + std::abs(c.nz) * 0.5 * L;  // max of h − n·p
  if (!(depth > 0.0)) return ContactVolume{.method = Method::kAnalytic};

  const CylinderIntegrals in =
      c.s == 0.0 ? integrateAxisAlongNormal(c, depth) : integrateTiltedAxis(c, n_C);
  const SliceMoments& total = in.total;
  const double V = total.area;
  if (!(V > 0.0)) return ContactVolume{.method = Method::kAnalytic};
  // Moments about o in C: m1 = S_ξ' u + (∫A z') e_z, m2 assembled from the slice terms.
  const Vector3d& u = c.u;
  const Vector3d& v = c.v;
  const Vector3d e = Vector3d::UnitZ();
  geometry::Moments M;
  M.m0 = V;
  M.m1 = total.s1 * u + total.areaZ * e;
  M.m2 = total.s11 * u * u.transpose() + total.s22 * v * v.transpose() +
         total.s1Z * (u * e.transpose() + e * u.transpose()) + total.areaZZ * e * e.transpose();
  const Vector3d o = -R * u + c.zetaDeep * e;
  // Projected area of a convex region: half of ∫|n_s·n| over its boundary.
  const double area = 0.5 * (total.sideShadow + total.cutFace + in.capArea);
  // o and the offset are mapped separately: o + offset would round the offset (~d) against
  // the radius, losing digits for shallow contact.
  ContactVolume cv = contactFromMoments(M, o, X_WC, n_W, area, depth, Method::kAnalytic);
  cv.relative_error = in.relErr;
  return cv;
}

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

bool isBoundedPrimitive(const geometry::Shape& s) {
  return std::holds_alternative<geometry::Sphere>(s) ||
         std::holds_alternative<geometry::Cylinder>(s) || std::holds_alternative<geometry::Box>(s);
}

ContactVolume primitiveHalfspace(const geometry::Shape& body, const Isometry3d& X_WB,
                                 const Isometry3d& X_WH) {
  return std::visit(
      Overloaded{[&](const geometry::Sphere& s) { return sphereHalfspace(s.radius, X_WB, X_WH); },
                 [&](const geometry::Cylinder& c) {
                   return cylinderHalfspace(c.radius, c.length, X_WB, X_WH);
                 },
                 [&](const geometry::Box& b) { return boxHalfspace(b.size, X_WB, X_WH); },
                 [&](const auto&) -> ContactVolume {
                   throw InputError("volume method analytic", "not a bounded primitive");
                 }},
      body);
}

}  // namespace

ContactVolume sphereHalfspace(double radius, const Isometry3d& X_WS, const Isometry3d& X_WH) {
  const Vector3d c_H = X_WH.inverse() * X_WS.translation();
  return sphereInHalfspaceFrame(radius, c_H, X_WH);
}

ContactVolume cylinderHalfspace(double radius, double length, const Isometry3d& X_WC,
                                const Isometry3d& X_WH) {
  const Isometry3d X_HC = X_WH.inverse() * X_WC;
  // z_H = n_C·p_C + t_z ≤ 0  ⇔  n_C·p_C ≤ h = −t_z, with n_C the third row of R_HC.
  const Vector3d n_C = X_HC.linear().row(2).transpose();
  return cylinderInOwnFrame(radius, length, n_C, -X_HC.translation().z(), X_WC,
                            X_WH.linear().col(2));
}

ContactVolume boxHalfspace(const Vector3d& size, const Isometry3d& X_WB, const Isometry3d& X_WH) {
  // A box is a polyhedron: its exact clip is its closed form.
  static thread_local geometry::TriangleMesh mesh;
  static thread_local Vector3d meshSize = Vector3d::Zero();
  if (meshSize != size) {
    mesh = geometry::tessellateBox(size);
    meshSize = size;
  }
  ContactVolume cv = meshHalfspaceContact(mesh, X_WB, X_WH);
  cv.method = Method::kAnalytic;
  return cv;
}

bool analyticSupports(const geometry::Shape& a, const geometry::Shape& b) {
  return (isBoundedPrimitive(a) && std::holds_alternative<geometry::HalfSpace>(b)) ||
         (isBoundedPrimitive(b) && std::holds_alternative<geometry::HalfSpace>(a));
}

ContactVolume analyticContact(const geometry::Shape& a, const Isometry3d& X_WA,
                              const geometry::Shape& b, const Isometry3d& X_WB) {
  if (!analyticSupports(a, b)) {
    throw InputError("volume method analytic",
                     "the analytic method handles a sphere, cylinder or box against a "
                     "half-space; got " +
                         geometry::shapeKind(a) + " and " + geometry::shapeKind(b));
  }
  if (std::holds_alternative<geometry::HalfSpace>(b)) return primitiveHalfspace(a, X_WA, X_WB);
  return swapped(primitiveHalfspace(b, X_WB, X_WA));
}

}  // namespace vcontact::volume
