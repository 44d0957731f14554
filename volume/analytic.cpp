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
  return assembleContactVolume(V, X_WH * p_H, R_WH * Sigma_H * R_WH.transpose(), R_WH.col(2),
                               area, d, Method::kAnalytic);
}

// ---------------------------------------------------------------------------------------
// Cylinder. In the cylinder frame C the half-space is {p : n·p ≤ h}. Write n = s u + n_z e_z
// with u a unit vector in the xy plane and v = e_z × u. The slice at height ζ is the disc
// x² + y² ≤ R² cut by ξ ≤ w(ζ) = (h − n_z ζ)/s, where ξ = p·u: a circular segment of depth
// d(ζ) = R + w(ζ) from the disc's edge at ξ = −R. With ξ = −R cos φ (φ ∈ [0, θ],
// d = R(1 − cos θ)) the segment moments about the edge point ξ' = ξ + R = 0 are
//   A      = 2R² ∫ sin²φ,           S_ξ'  = 2R³ ∫ (1 − cos φ) sin²φ,
//   S_ξ'ξ' = 2R⁴ ∫ (1 − cos φ)² sin²φ,  S_ηη = (2/3)R⁴ ∫ sin⁴φ.
// The integrands are trigonometric polynomials, so 20-point Gauss–Legendre on [0, θ] is
// exact to rounding (error term below 1e-20 for θ ≤ π), and, with positive integrands and
// 1 − cos φ written 2 sin²(φ/2), no digits are lost to cancellation as θ → 0.
// The slices are then integrated over ζ adaptively, in θ where an end of the interval is
// a tangency (d = 0 or d = 2R: there the slice moments behave like d^{3/2} in ζ but are
// smooth in θ), otherwise in ζ itself.

struct GaussLegendre20 {
  std::array<double, 20> x{}, w{};  // on [−1, 1]
  GaussLegendre20() {
    constexpr int n = 20;
    for (int i = 0; i < n / 2; ++i) {
      double z = std::cos(M_PI * (i + 0.75) / (n + 0.5));
      double dp = 0.0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1.0, p1 = 0.0;
        for (int k = 1; k <= n; ++k) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
        }
        dp = n * (z * p0 - p1) / (z * z - 1.0);
        const double dz = p0 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = -z;
      x[n - 1 - i] = z;
      w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre20& gaussLegendre20() {
  static const GaussLegendre20 rule;
  return rule;
}

struct Segment {
  double A, S1, S11, S22;  // area, ∫ξ', ∫ξ'², ∫η² (about the edge point)
};

Segment segmentMoments(double R, double theta) {
  const auto& gl = gaussLegendre20();
  const double half = 0.5 * theta;
  double i20 = 0.0, i21 = 0.0, i22 = 0.0, i40 = 0.0;
  for (int k = 0; k < 20; ++k) {
    const double phi = half * (gl.x[k] + 1.0);
    const double s = std::sin(phi), s2 = s * s;
    const double sh = std::sin(0.5 * phi), omc = 2.0 * sh * sh;  // 1 − cos φ
    i20 += gl.w[k] * s2;
    i21 += gl.w[k] * omc * s2;
    i22 += gl.w[k] * omc * omc * s2;
    i40 += gl.w[k] * s2 * s2;
  }
  const double R2 = R * R;
  return {2.0 * R2 * half * i20, 2.0 * R2 * R * half * i21, 2.0 * R2 * R2 * half * i22,
          (2.0 / 3.0) * R2 * R2 * half * i40};
}

/// θ with d = R(1 − cos θ), accurate for small d; d is clamped to [0, 2R].
double segmentAngle(double R, double d) {
  const double r = std::clamp(d / (2.0 * R), 0.0, 1.0);
  return 2.0 * std::asin(std::sqrt(r));
}

// Integrated quantities, per unit ζ, about o = −R u + ζ_deep e_z:
//   0 A, 1 S_ξ', 2 S_ξ'ξ', 3 S_ηη, 4 A z', 5 S_ξ' z', 6 A z'², 7 side shadow, 8 cut-face
// where z' = ζ − ζ_deep; 7 is ∫|n_s·n| over the slice's wetted arc, 8 the chord / s.
using Slice = Eigen::Matrix<double, 9, 1>;

Slice sliceIntegrand(double R, double s, double theta, double zp) {
  const Segment g = segmentMoments(R, theta);
  const double sinT = std::sin(theta);
  Slice f;
  f << g.A, g.S1, g.S11, g.S22, g.A * zp, g.S1 * zp, g.A * zp * zp,
      s * R * 2.0 * (theta <= 0.5 * M_PI ? sinT : 2.0 - sinT), 2.0 * R * sinT / s;
  return f;
}

struct CylinderSetup {
  double R, L, s, nz, h;
  Vector3d u, v;
  double zetaDeep;
  double depth(double zeta) const { return R + (h - nz * zeta) / s; }  // segment depth d(ζ)
};

ContactVolume cylinderInOwnFrame(double R, double L, const Vector3d& n_C, double h,
                                 const Isometry3d& X_WC, const Vector3d& n_W) {
  CylinderSetup c{R, L, std::hypot(n_C.x(), n_C.y()), n_C.z(), h, {}, {}, 0.0};
  c.zetaDeep = c.nz > 0.0 ? -0.5 * L : 0.5 * L;
  const double depth = h + c.s * R + std::abs(c.nz) * 0.5 * L;  // max of h − n·p
  if (!(depth > 0.0)) return ContactVolume{.method = Method::kAnalytic};

  Slice total = Slice::Zero();
  double relErr = 0.0;
  double capArea = 0.0;  // |n_z| × wetted cap area, both caps

  if (c.s == 0.0) {
    // Axis along the normal: every slice is a full disc or empty. Wetted length ℓ.
    const double ell = std::min(depth / std::abs(c.nz), L);
    const double A = M_PI * R * R;
    total(0) = A * ell;
    total(1) = A * R * ell;
    total(2) = 1.25 * M_PI * R * R * R * R * ell;
    total(3) = 0.25 * M_PI * R * R * R * R * ell;
    total(4) = A * ell * ell / 2.0;
    total(5) = A * R * ell * ell / 2.0;
    total(6) = A * ell * ell * ell / 3.0;
    c.u = Vector3d::UnitX();
    c.v = Vector3d::UnitY();
    // Seen along n: the deep cap, plus the cut face while the plane crosses the body, or
    // the far cap once the cylinder is wholly sunk.
    capArea = ell < L ? A : 2.0 * A;
    total(8) = ell < L ? A : 0.0;
  } else {
    c.u = Vector3d(n_C.x() / c.s, n_C.y() / c.s, 0.0);
    c.v = Vector3d::UnitZ().cross(c.u);
    std::vector<double> cuts = {-0.5 * L, 0.5 * L};
    std::vector<double> tangency;
    if (c.nz != 0.0) {
      for (double zeta : {(h + c.s * R) / c.nz, (h - c.s * R) / c.nz}) {
        if (zeta > -0.5 * L && zeta < 0.5 * L) {
          cuts.push_back(zeta);
          tangency.push_back(zeta);
        }
      }
    }
    std::sort(cuts.begin(), cuts.end());
    auto isTangency = [&](double z) {
      return std::find(tangency.begin(), tangency.end(), z) != tangency.end();
    };
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double a = cuts[i], b = cuts[i + 1];
      if (!(b > a)) continue;
      const double dMid = c.depth(0.5 * (a + b));
      const double za = a - c.zetaDeep, zb = b - c.zetaDeep;
      if (dMid <= 0.0) continue;
      if (dMid >= 2.0 * R) {
        // Full discs: polynomial in z'.
        const double A = M_PI * R * R, len = b - a;
        const double p1 = (zb * zb - za * za) / 2.0, p2 = (zb * zb * zb - za * za * za) / 3.0;
        Slice f;
        f << A * len, A * R * len, 1.25 * A * R * R * len, 0.25 * A * R * R * len,
            A * p1, A * R * p1, A * p2, 4.0 * c.s * R * len, 0.0;
        total += f;
        continue;
      }
      if (isTangency(a) || isTangency(b)) {
        // θ as the variable: ζ(θ) = (h + sR cos θ)/n_z, |dζ/dθ| = sR sin θ / |n_z|.
        const double ta = isTangency(a) ? (c.depth(a) < R ? 0.0 : M_PI) : segmentAngle(R, c.depth(a));
        const double tb = isTangency(b) ? (c.depth(b) < R ? 0.0 : M_PI) : segmentAngle(R, c.depth(b));
        const double lo = std::min(ta, tb), hi = std::max(ta, tb);
        auto f = [&](double theta) -> Slice {
          const double zeta = (h + c.s * R * std::cos(theta)) / c.nz;
          return sliceIntegrand(R, c.s, theta, zeta - c.zetaDeep) *
                 (c.s * R * std::sin(theta) / std::abs(c.nz));
        };
        const auto r = integrateAdaptive<9>(f, lo, hi, kQuadratureTolerance);
        total += r.value;
        relErr = std::max(relErr, r.relative_error);
      } else {
        auto f = [&](double zeta) -> Slice {
          return sliceIntegrand(R, c.s, segmentAngle(R, c.depth(zeta)), zeta - c.zetaDeep);
        };
        const auto r = integrateAdaptive<9>(f, a, b, kQuadratureTolerance);
        total += r.value;
        relErr = std::max(relErr, r.relative_error);
      }
    }
    for (double zeta : {-0.5 * L, 0.5 * L}) {
      capArea += std::abs(c.nz) * segmentMoments(R, segmentAngle(R, c.depth(zeta))).A;
    }
  }

  const double V = total(0);
  if (!(V > 0.0)) return ContactVolume{.method = Method::kAnalytic};
  // Moments about o in C: m1 = S_ξ' u + (∫A z') e_z, m2 assembled from the slice terms.
  const Vector3d& u = c.u;
  const Vector3d& v = c.v;
  const Vector3d e = Vector3d::UnitZ();
  const Vector3d m1 = total(1) * u + total(4) * e;
  const Matrix3d m2 = total(2) * u * u.transpose() + total(3) * v * v.transpose() +
                      total(5) * (u * e.transpose() + e * u.transpose()) +
                      total(6) * e * e.transpose();
  const Vector3d cOff = m1 / V;
  const Matrix3d Sigma_C = m2 - V * cOff * cOff.transpose();
  const Vector3d o = -R * u + c.zetaDeep * e;
  // Projected area of a convex region: half of ∫|n_s·n| over its boundary.
  const double area = 0.5 * (total(7) + total(8) + capArea);
  const Matrix3d R_WC = X_WC.linear();
  // o and the offset are mapped separately: o + cOff would round the offset (~d) against
  // the radius, losing digits for shallow contact.
  ContactVolume cv = assembleContactVolume(V, X_WC * o + R_WC * cOff,
                                           R_WC * Sigma_C * R_WC.transpose(), n_W, area, depth,
                                           Method::kAnalytic);
  cv.relative_error = relErr;
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
      Overloaded{
          [&](const geometry::Sphere& s) { return sphereHalfspace(s.radius, X_WB, X_WH); },
          [&](const geometry::Cylinder& c) {
            return cylinderHalfspace(c.radius, c.length, X_WB, X_WH);
          },
          [&](const geometry::Box& b) { return boxHalfspace(b.size, X_WB, X_WH); },
          [&](const auto&) -> ContactVolume {
            throw InputError("--method analytic", "not a bounded primitive");
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
    throw InputError("--method analytic",
                     "the analytic method handles a sphere, cylinder or box against a "
                     "half-space; got " + geometry::shapeKind(a) + " and " +
                         geometry::shapeKind(b));
  }
  if (std::holds_alternative<geometry::HalfSpace>(b)) return primitiveHalfspace(a, X_WA, X_WB);
  return swapped(primitiveHalfspace(b, X_WB, X_WA));
}

}  // namespace vcontact::volume
