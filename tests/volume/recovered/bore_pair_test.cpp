// A pin in a bore by slices (volume/recovered/pin_in_bore.hpp, volume/recovered/bore_pair.hpp): the
// slices against the closed form of a cylinder (the length times the disc less the lens) and an
// independent polar integration of its moments; a chamfered profile against Simpson's rule;
// the tessellated pin in the bundled block, recognised, against the same references, under
// rigid motions and with the bodies swapped; a pin in its clearance; and the cases that stay
// refined.

#include "volume/recovered/bore_pair.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>

#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "support/test_support.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/recovered/pin_in_bore.hpp"
#include "volume/recovered/pin_in_bore_slices.hpp"
#include "volume/recovered/refinement.hpp"
#include "volume/revolution_references.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::recogniseSurfaces;
using geometry::TriangleMesh;
using vcontact::test::chamferedPin;
using vcontact::test::chamferedPinInBore;
using vcontact::test::pinOutsideBore;

// The pin of the error table (r 5 mm, 30 mm, 0.5 mm 45° chamfers) and the bundled block's
// bore (5.1 mm, the block 20 mm thick between z = −20 mm and 0).
constexpr double kR = 0.005, kBore = 0.0051, kLength = 0.03, kChamfer = 0.0005, kBlock = 0.02;

// Hand-fed profiles against closed forms and Simpson's rule: the quadrature promises 1e-9
// relative (analytic/revolution_on_plane.hpp) and the references are good to 1e-12 (closed form)
// and 1e-9 (Simpson on 20,000 intervals of a smooth integrand).
constexpr double kProfile = 2e-9;

// Moments of the part of the disc of radius r about the origin outside the disc of radius R
// about (e, 0), r + e > R > e, by Simpson's rule in the polar angle ψ about the origin: the
// ray at ψ leaves the bore at ρ_b = e cos ψ + √(R² − e² sin² ψ) and the region is ρ_b ≤ ρ ≤ r,
// for ψ between the crossings ψ_c and 2π − ψ_c (cos ψ_c = (r² + e² − R²)/(2er)); the radial
// integrals are closed. Area, ∫x, ∫x², ∫y².
struct Polar {
  double A = 0.0, Sx = 0.0, Sxx = 0.0, Syy = 0.0;
};
Polar polarCrescent(double r, double R, double e) {
  const double psiC = std::acos((r * r + e * e - R * R) / (2.0 * e * r));
  const int n = 200000;
  Polar m;
  for (int i = 0; i <= n; ++i) {
    const double psi = psiC + (2.0 * M_PI - 2.0 * psiC) * i / n;
    const double c = std::cos(psi), s = std::sin(psi);
    const double rb = e * c + std::sqrt(R * R - e * e * s * s);
    const double w =
        ((i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (2.0 * M_PI - 2.0 * psiC) / (3.0 * n);
    m.A += w * (r * r - rb * rb) / 2.0;
    m.Sx += w * (std::pow(r, 3) - std::pow(rb, 3)) / 3.0 * c;
    m.Sxx += w * (std::pow(r, 4) - std::pow(rb, 4)) / 4.0 * c * c;
    m.Syy += w * (std::pow(r, 4) - std::pow(rb, 4)) / 4.0 * s * s;
  }
  return m;
}

TEST(AnalyticBore, CylinderIsItsLengthTimesTheDiscLessTheLens) {
  const double L = 0.02;
  const RevolutionProfile pin = cylinderProfile(kR, L);
  for (double ratio : {1e-4, 1e-3, 1e-2, 0.5}) {
    const double d = ratio * kR, e = kBore - kR + d;
    BoreSection bore;
    bore.point_R = Vector3d(e, 0.0, 0.0);
    bore.radius = kBore;
    const BoreContact got = revolutionInBore(pin, Isometry3d::Identity(), bore);
    const double A = pinOutsideBore(kR, kBore, e);
    EXPECT_NEAR(got.cv.volume, L * A, kProfile * L * A) << ratio;
    // the slices are all alike: the moments are the slice's times L, the normal towards the
    // bore's axis (+x)
    const Polar p = polarCrescent(kR, kBore, e);
    const double xc = p.Sx / p.A;
    EXPECT_NEAR(p.A, A, 1e-9 * A) << "the polar reference itself";
    EXPECT_NEAR(got.cv.p_WC.x(), xc, 1e-9 * kR) << ratio;
    EXPECT_NEAR(got.cv.p_WC.y(), 0.0, 1e-12 * kR);
    EXPECT_NEAR(got.cv.p_WC.z(), 0.0, 1e-12 * kR);
    // J_v = tr(Σ) I − Σ, Σ = diag(L(Sxx − A x_c²), L Syy, A L³/12)
    const Vector3d sigma(L * (p.Sxx - p.A * xc * xc), L * p.Syy, p.A * L * L * L / 12.0);
    const Vector3d jv = Vector3d::Constant(sigma.sum()) - sigma;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got.cv.J_v(k, k), jv(k), 1e-7 * jv(k)) << ratio << ' ' << k;
    EXPECT_NEAR((got.cv.n_W - Vector3d::UnitX()).norm(), 0.0, 1e-12);
    // the shadow along n: the crossings' chord, or the pin's diameter once its segment passes
    // its axis
    const double hB = (kR - kBore + e) * (kR + kBore - e) / (2.0 * e);
    const double width = hB + d >= kR ? 2.0 * kR : 2.0 * std::sqrt(hB * (2.0 * kBore - hB));
    EXPECT_NEAR(got.cv.area, width * L, 1e-9 * width * L);
    EXPECT_NEAR(got.cv.depth, d, 1e-9 * d);
  }
}

TEST(AnalyticBore, BoreInsideTheDiscAndDiscOutsideTheBoreAreWholeDiscs) {
  const double L = 0.01, r = 0.004;
  const RevolutionProfile pin = cylinderProfile(r, L);
  BoreSection bore;
  bore.radius = 0.001;
  bore.point_R = Vector3d(0.0, 0.002, 0.0);  // inside: the annulus-like disc less a disc
  EXPECT_NEAR(revolutionInBore(pin, Isometry3d::Identity(), bore).cv.volume,
              L * M_PI * (r * r - 0.001 * 0.001), 1e-12 * L * r * r);
  bore.point_R = Vector3d(0.0, 0.006, 0.0);  // the bore misses the pin: all of it in B
  EXPECT_NEAR(revolutionInBore(pin, Isometry3d::Identity(), bore).cv.volume, L * M_PI * r * r,
              1e-12 * L * r * r);
}

// The pin's profile by hand: cone, cylinder, cone, ζ from 0 to kLength.
RevolutionProfile chamferedProfile() {
  return {{ProfilePiece::Kind::kLinear, 0.0, kChamfer, kR - kChamfer, kR},
          {ProfilePiece::Kind::kConstant, kChamfer, kLength - kChamfer, kR, kR},
          {ProfilePiece::Kind::kLinear, kLength - kChamfer, kLength, kR, kR - kChamfer}};
}

// The chamfered profile with its top chamfer cut by a plane of B half-way through the slices
// where the crescent lasts, and the bottom one outside B.
TEST(AnalyticBore, ChamferCutByAPlaneMatchesSimpson) {
  const RevolutionProfile pin = chamferedProfile();
  for (double ratio : {1e-4, 1e-3, 1e-2}) {
    const double d = ratio * kR, e = kBore - kR + d;
    for (double into : {0.5, 2.0}) {  // the plane within the crescent's slices, or beyond them
      BoreSection bore;
      bore.point_R = Vector3d(0.0, -e, 0.0);
      bore.radius = kBore;
      bore.zeta_hi = kLength - kChamfer + into * d;
      bore.zeta_lo = bore.zeta_hi - kBlock;
      const double expected =
          chamferedPinInBore(kR, kLength, kChamfer, kBore, e, bore.zeta_lo, bore.zeta_hi);
      const BoreContact got = revolutionInBore(pin, test::randomPose(7), bore);
      EXPECT_NEAR(got.cv.volume, expected, kProfile * expected) << ratio << ' ' << into;
      EXPECT_LT(got.cv.relative_error, 1e-9);
    }
  }
}

// The polar integration of a tilted bore, given a parallel one and the planes across it, is
// the closed form's solid by another route: V, centroid, J_v and n agree to the quadratures'
// accuracy (1e-9 asked of each). The areas differ in their definitions: |∫ n_A dS| against
// the shadow ∫ width dζ + |n_z| × the planes' parts, apart by the chamfer's slope times the
// cut chamfer's share (2e-6 here).
TEST(AnalyticBore, PolarSlicesOfAParallelBoreAreTheClosedForm) {
  const RevolutionProfile pin = chamferedProfile();
  // 1e-5: a crescent 0.06 rad wide, narrower than the rays sampled are apart
  for (double ratio : {1e-5, 1e-4, 1e-2}) {
    const double d = ratio * kR, e = kBore - kR + d;
    BoreSection bore;
    bore.point_R = Vector3d(0.6 * e, -0.8 * e, 0.0);
    bore.radius = kBore;
    bore.zeta_hi = kLength - kChamfer + 0.5 * d;
    bore.zeta_lo = bore.zeta_hi - kBlock;
    bore.polar_slices = true;  // the rays, not the ellipse's closed form (a circle here)
    const std::vector<BorePlane> planes = {{Vector3d::UnitZ(), Vector3d(0, 0, bore.zeta_hi)},
                                           {-Vector3d::UnitZ(), Vector3d(0, 0, bore.zeta_lo)}};
    const Isometry3d X_WR = test::randomPose(11);
    const ContactVolume closed = revolutionInBore(pin, X_WR, bore).cv;
    const ContactVolume polar = revolutionInTiltedBore(pin, X_WR, bore, planes).cv;
    EXPECT_NEAR(polar.volume, closed.volume, 1e-8 * closed.volume) << ratio;
    EXPECT_NEAR((polar.p_WC - closed.p_WC).norm(), 0.0, 1e-9 * kR) << ratio;
    EXPECT_NEAR((polar.J_v - closed.J_v).norm(), 0.0, 1e-7 * closed.J_v.norm()) << ratio;
    EXPECT_NEAR((polar.n_W - closed.n_W).norm(), 0.0, 1e-8) << ratio;
    EXPECT_NEAR(polar.area, closed.area, 1e-5 * closed.area) << ratio;
  }
}

// The disc of radius r less an ellipse (the section of the bore tilted by γ), by Simpson's
// rule in ψ about the disc's centre: the ray leaves the ellipse at ρ_E(ψ) (the larger root of
// |S⁻¹(ρ d − c)| = R) and the region is ρ_E ≤ ρ ≤ r between the two crossings, found by
// bisection between 4096 rays. The integrand is smooth there (the radial integrals are
// closed): 20,000 intervals leave ~1e-14 of it. In long double: in double, r − ρ_E carries
// ε R of rounding, 2e-11 of a crescent 1e-5 r deep.
struct Ellipse6 {
  double A = 0.0, Sx = 0.0, Sy = 0.0, Sxx = 0.0, Sxy = 0.0, Syy = 0.0;
  int crossings = 0;
};
Ellipse6 polarEllipse(double r, const detail::SliceEllipse& E) {
  using LD = long double;
  using V = Eigen::Matrix<LD, 2, 1>;
  const Eigen::Matrix<LD, 2, 2> Sinv = E.S.cast<LD>().inverse();
  const V cc = E.c.cast<LD>();
  const LD R = E.R;
  const auto exitAt = [&](LD psi) {
    const V d = Sinv * V(std::cos(psi), std::sin(psi)), s = Sinv * cc;
    const LD a = d.squaredNorm(), b = -2.0L * d.dot(s), c = s.squaredNorm() - R * R;
    return (-b + std::sqrt(b * b - 4.0L * a * c)) / (2.0L * a);
  };
  const LD psi0 = std::atan2(cc.y(), cc.x());  // the ellipse's far side: no region
  const auto g = [&](LD psi) { return exitAt(psi) - r; };
  std::vector<LD> roots;
  const int n = 4096;
  for (int i = 0; i < n; ++i) {
    LD a = psi0 + 2.0L * M_PI * i / n, b = psi0 + 2.0L * M_PI * (i + 1) / n;
    if ((g(a) > 0.0L) == (g(b) > 0.0L)) continue;
    const bool posA = g(a) > 0.0L;
    for (int k = 0; k < 70; ++k) ((g(0.5L * (a + b)) > 0.0L) == posA ? a : b) = 0.5L * (a + b);
    roots.push_back(0.5L * (a + b));
  }
  Ellipse6 m;
  m.crossings = static_cast<int>(roots.size());
  if (roots.size() != 2) return m;
  const int steps = 20000;
  const LD h = (roots[1] - roots[0]) / steps, rl = r;
  LD A = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0, Syy = 0;
  for (int i = 0; i <= steps; ++i) {
    const LD psi = roots[0] + h * i, c = std::cos(psi), s = std::sin(psi);
    const LD w = ((i == 0 || i == steps) ? 1.0L : (i % 2 ? 4.0L : 2.0L)) * h / 3.0L;
    const LD rho = std::min(rl, exitAt(psi)), dr = rl - rho;
    const LD a2 = dr * (rl + rho) / 2.0L, a3 = dr * (rl * rl + rl * rho + rho * rho) / 3.0L;
    const LD a4 = dr * (rl + rho) * (rl * rl + rho * rho) / 4.0L;
    A += w * a2;
    Sx += w * a3 * c;
    Sy += w * a3 * s;
    Sxx += w * a4 * c * c;
    Sxy += w * a4 * c * s;
    Syy += w * a4 * s * s;
  }
  m.A = A, m.Sx = Sx, m.Sy = Sy, m.Sxx = Sxx, m.Sxy = Sxy, m.Syy = Syy;
  return m;
}

// The closed form of the disc less the ellipse (volume/recovered/pin_in_bore_slices.hpp) against
// the polar rule above, at tilts 0.2 mrad to 0.1 rad and crescents d/r 1e-5 to 0.1 deep, the
// ellipse's long axis at 0.7 rad and its centre at −2 rad: within 1e-12 of A r^k and the
// rounding the crescent's depth amplifies (below).
TEST(AnalyticBore, DiscLessEllipseIsThePolarRule) {
  for (double gamma : {2e-4, 1e-3, 1e-2, 0.1})
    for (double ratio : {1e-5, 1e-3, 1e-1}) {
      const Vector3d axis(std::sin(gamma) * std::cos(0.7), std::sin(gamma) * std::sin(0.7),
                          std::cos(gamma));
      // the circle pokes out of the ellipse by ratio·r at least along −c
      const double e = kBore / std::cos(gamma) - kR + ratio * kR;
      const Vector3d point(e * std::cos(-2.0), e * std::sin(-2.0), 0.0);
      const detail::SliceEllipse E = detail::boreEllipse(point, axis, kBore, 0.0);
      EXPECT_NEAR(E.S.determinant(), 1.0 / std::cos(gamma), 1e-15);
      const Ellipse6 ref = polarEllipse(kR, E);
      ASSERT_EQ(ref.crossings, 2) << gamma << " " << ratio;
      detail::EllipseSlice got;
      ASSERT_TRUE(detail::discLessEllipse(kR, E, got)) << gamma << " " << ratio;
      // the crescent, d = ratio·r deep, moves by the ε R rounding of its inputs (c, R, the
      // crossings), a change of ε R/d of itself on either side: 8 ε R/d, and 1e-12 for the rule
      const double eps = std::numeric_limits<double>::epsilon();
      const double tol = (1e-12 + 8.0 * eps * kBore / (ratio * kR)) * ref.A;
      EXPECT_NEAR(got.A, ref.A, tol) << gamma << " " << ratio;
      EXPECT_NEAR(got.Sx, ref.Sx, tol * kR) << gamma << " " << ratio;
      EXPECT_NEAR(got.Sy, ref.Sy, tol * kR) << gamma << " " << ratio;
      EXPECT_NEAR(got.Sxx, ref.Sxx, tol * kR * kR) << gamma << " " << ratio;
      EXPECT_NEAR(got.Sxy, ref.Sxy, tol * kR * kR) << gamma << " " << ratio;
      EXPECT_NEAR(got.Syy, ref.Syy, tol * kR * kR) << gamma << " " << ratio;
      EXPECT_GT(got.depth, 0.0);
      EXPECT_LE(got.depth, kR);
    }
}

// Where the ellipse holds the disc the region is empty, and where the disc holds the ellipse
// (no crossing) the closed form declines and leaves the slice to the rays.
TEST(AnalyticBore, DiscLessEllipseEmptyOrDeclined) {
  const Vector3d axis(std::sin(1e-3), 0.0, std::cos(1e-3));
  detail::EllipseSlice got;
  got.A = -1.0;
  const detail::SliceEllipse around = detail::boreEllipse(Vector3d(5e-5, 0, 0), axis, kBore, 0.0);
  ASSERT_TRUE(detail::discLessEllipse(kR, around, got));
  EXPECT_EQ(got.A, 0.0);
  EXPECT_EQ(got.arcLength, 0.0);
  got.A = -1.0;
  const detail::SliceEllipse inside = detail::boreEllipse(Vector3d(5e-4, 0, 0), axis, 1e-3, 0.0);
  EXPECT_FALSE(detail::discLessEllipse(kR, inside, got));
  EXPECT_EQ(got.A, -1.0);  // left alone
}

// The chamfered pin in a bore tilted by 0.2 mrad to 10 mrad, between two faces across the
// bore's axis (so tilted from the slices: bands where their lines cross the disc, the region
// cut by them by Green's theorem): the closed-form slices against the polar ones, V,
// centroid, J_v, n and area within the outer quadrature's 1e-9 asked (1e-8 for V: the
// bands' 1e-4 of their share).
TEST(AnalyticBore, TiltedClosedFormSlicesAreThePolarSlices) {
  const RevolutionProfile pin = chamferedProfile();
  for (double gamma : {2e-4, 1e-3, 1e-2})
    for (double ratio : {1e-4, 1e-2}) {
      const double d = ratio * kR, e = kBore - kR + d;
      BoreSection bore;
      bore.axis_R = Vector3d(std::sin(gamma) * 0.6, std::sin(gamma) * 0.8, std::cos(gamma));
      bore.point_R = Vector3d(-0.6 * e, -0.8 * e, 0.5 * kLength);
      bore.radius = kBore;
      const Vector3d top = bore.point_R + 0.5 * kBlock * bore.axis_R;
      const Vector3d bottom = bore.point_R - 0.5 * kBlock * bore.axis_R;
      const std::vector<BorePlane> planes = {{bore.axis_R, top}, {-bore.axis_R, bottom}};
      const Isometry3d X_WR = test::randomPose(17);
      const BoreContact closed = revolutionInTiltedBore(pin, X_WR, bore, planes);
      bore.polar_slices = true;
      const BoreContact polar = revolutionInTiltedBore(pin, X_WR, bore, planes);
      const ContactVolume &c = closed.cv, &p = polar.cv;
      ASSERT_GT(p.volume, 0.0) << gamma << " " << ratio;
      EXPECT_NEAR(c.volume, p.volume, 1e-8 * p.volume) << gamma << " " << ratio;
      EXPECT_NEAR((c.p_WC - p.p_WC).norm(), 0.0, 1e-9 * kR) << gamma << " " << ratio;
      EXPECT_NEAR((c.J_v - p.J_v).norm(), 0.0, 1e-8 * p.J_v.norm()) << gamma << " " << ratio;
      EXPECT_NEAR((c.n_W - p.n_W).norm(), 0.0, 1e-8) << gamma << " " << ratio;
      EXPECT_NEAR(c.area, p.area, 1e-8 * p.area) << gamma << " " << ratio;
      // depth: the largest over the slices each quadrature sampled (not the same ones) and,
      // for the rays, over the rays sampled; the closed form's is the largest over its arcs
      EXPECT_NEAR(c.depth, p.depth, 1e-3 * p.depth) << gamma << " " << ratio;
      EXPECT_GE(c.depth, p.depth * (1.0 - 1e-9)) << gamma << " " << ratio;
    }
}

// ---------------------------------------------------------------------------------------
// Recognised meshes: the chamfered pin of 64 segments (512 triangles) and the bundled block
// (single-precision STL, bore radius recognised within 1e-10 m of 5.1 mm).

struct PinAndBlock {
  TriangleMesh pin = chamferedPin(kR, kLength, kChamfer, 64);
  TriangleMesh block =
      io::readMesh(std::string(VCONTACT_ASSETS_DIR) + "/scenarios/meshes/block_hole_d10.stl").mesh;
  geometry::SurfaceRecognition recPin = recogniseSurfaces(pin), recBlock = recogniseSurfaces(block);
  RecoveredBody a{pin, recPin}, b{block, recBlock};
};

const PinAndBlock& bodies() {
  static const PinAndBlock k;
  return k;
}

// The pin pressed sideways by d = ratio·r into the bore's wall, in the direction at 0.3 rad,
// its axis parallel to the bore's, `z` the height of its lower end in the block's frame.
Isometry3d pressed(double ratio, double z = -0.025) {
  const double e = kBore - kR + ratio * kR;
  Isometry3d X_BA = Isometry3d::Identity();
  X_BA.translation() = Vector3d(e * std::cos(0.3), e * std::sin(0.3), z);
  return X_BA;
}

// Against the references with the exact 5.1 mm: the recognised radius is off by the
// single-precision rounding of the block's vertices (a few 1e-11 m after the fit), which moves
// V by about 1.5·ΔR/d of itself: 1.5e-4 at d = 5e-7 m. The reported bound (area times the fit
// residual, ~1e-9 m) covers it, and the issue asks for 0.1 %.
TEST(RecoveredBore, PinInTheBundledBlockIsTheDiscOutsideTheBoreTimesTheBlock) {
  const PinAndBlock& k = bodies();
  for (double ratio : {1e-4, 1e-3, 1e-2}) {
    const double e = kBore - kR + ratio * kR, expected = kBlock * pinOutsideBore(kR, kBore, e);
    const RecoveredContact got =
        recoveredMeshMeshContact(k.a, pressed(ratio), k.b, Isometry3d::Identity());
    ASSERT_EQ(got.representation, Representation::kRevolutionInBore) << got.reason;
    EXPECT_NEAR(got.cv.volume, expected, got.volume_error_bound) << ratio;
    EXPECT_NEAR(got.cv.volume, expected, 1e-3 * expected) << ratio;
    EXPECT_LT(got.volume_error_bound, 5e-3 * expected);  // a bound that says something
    // the polyhedra are off by 0.1 % to 46 % here
    const geometry::MeshBvh ta(k.pin), tb(k.block);
    const ContactVolume poly =
        meshMeshContact(ta, geometry::MeshTopology(k.pin), pressed(ratio), tb,
                        geometry::MeshTopology(k.block), Isometry3d::Identity(), nullptr, false)
            .aggregate;
    EXPECT_GT(std::abs(poly.volume - expected), 10.0 * std::abs(got.cv.volume - expected));
    // n from the block into the pin: towards the bore's axis, against the pressing direction
    EXPECT_LT(got.cv.n_W.dot(Vector3d(std::cos(0.3), std::sin(0.3), 0.0)), -0.999999);
    std::cout << "d/r " << ratio << ": V " << expected << ", slices " << got.cv.volume << " (bound "
              << got.volume_error_bound << "), polyhedra " << poly.volume << '\n';
  }
}

TEST(RecoveredBore, ChamferCutByTheBlockFaceMatchesSimpson) {
  const PinAndBlock& k = bodies();
  const double ratio = 1e-2, d = ratio * kR, e = kBore - kR + d;
  // the pin's top chamfer begins d/2 below the block's top face (z = 0)
  const double z0 = -(kLength - kChamfer) - 0.5 * d;
  const double expected = chamferedPinInBore(kR, kLength, kChamfer, kBore, e, -kBlock - z0, -z0);
  const RecoveredContact got =
      recoveredMeshMeshContact(k.a, pressed(ratio, z0), k.b, Isometry3d::Identity());
  ASSERT_EQ(got.representation, Representation::kRevolutionInBore) << got.reason;
  // as above (1.5·ΔR/d), and the block's top plane recognised within its vertices' rounding
  EXPECT_NEAR(got.cv.volume, expected, got.volume_error_bound);
  EXPECT_NEAR(got.cv.volume, expected, 1e-4 * expected);
}

// A rigid motion of both bodies moves the contact with them; swapping them flips n only.
TEST(RecoveredBore, RigidMotionAndSwapChangeNothingButTheFrame) {
  const PinAndBlock& k = bodies();
  const Isometry3d X_BA = pressed(1e-3);
  const RecoveredContact first = recoveredMeshMeshContact(k.a, X_BA, k.b, Isometry3d::Identity());
  ASSERT_EQ(first.representation, Representation::kRevolutionInBore) << first.reason;
  for (unsigned seed : {3u, 17u, 29u}) {
    const Isometry3d X_WB = test::randomPose(seed);
    for (bool swap : {false, true}) {
      const RecoveredContact got = swap ? recoveredMeshMeshContact(k.b, X_WB, k.a, X_WB * X_BA)
                                        : recoveredMeshMeshContact(k.a, X_WB * X_BA, k.b, X_WB);
      ASSERT_EQ(got.representation, Representation::kRevolutionInBore) << got.reason;
      // the profile and the bore are read in the bodies' frames; the rigid motion changes the
      // rounding of the pose products only (1e-16 m on a 5 µm overlap: 1e-10 of V)
      EXPECT_NEAR(got.cv.volume, first.cv.volume, 1e-9 * first.cv.volume) << seed;
      EXPECT_NEAR((got.cv.p_WC - X_WB * first.cv.p_WC).norm(), 0.0, 1e-12) << seed;
      const Vector3d n = X_WB.linear() * first.cv.n_W * (swap ? -1.0 : 1.0);
      EXPECT_NEAR((got.cv.n_W - n).norm(), 0.0, 1e-9) << seed;
      const Eigen::Matrix3d J = X_WB.linear() * first.cv.J_v * X_WB.linear().transpose();
      EXPECT_NEAR((got.cv.J_v - J).norm(), 0.0, 1e-7 * J.norm()) << seed;
    }
  }
}

// The pin tilted by 1 mrad in the bore about its middle, pressed into the wall by 10 µm at
// the block's bottom face and 30 µm at its top (d/r 2e-3 to 6e-3): the bore's section is an
// ellipse and the block's faces cut the slices along lines; against the refinement of both
// meshes, whose own estimate is 0.1 % (RefinementOptions::tolerance): within the refinement's
// reported bound plus the slices' (and below 0.2 %, as recovered_refinement_test accepts).
TEST(RecoveredBore, TiltedPinMatchesTheRefinement) {
  const PinAndBlock& k = bodies();
  const double beta = 1e-3, e = kBore - kR + 2e-5;
  Isometry3d X_BA = Isometry3d::Identity();
  X_BA.linear() = Eigen::AngleAxisd(beta, Vector3d::UnitY()).toRotationMatrix();
  // the pin's middle (ζ = 15 mm) at the block's middle, e off the bore's axis along x
  X_BA.translation() = Vector3d(e, 0.0, -0.01) - X_BA.linear() * Vector3d(0, 0, 0.015);
  const RecoveredContact got = recoveredMeshMeshContact(k.a, X_BA, k.b, Isometry3d::Identity());
  ASSERT_EQ(got.representation, Representation::kRevolutionInBore) << got.reason;
  const RecoveredContact ref = refinedMeshMeshContact(k.a, X_BA, k.b, Isometry3d::Identity());
  ASSERT_EQ(ref.representation, Representation::kRefined);
  EXPECT_NEAR(got.cv.volume, ref.cv.volume, ref.volume_error_bound + got.volume_error_bound);
  EXPECT_NEAR(got.cv.volume, ref.cv.volume, 2e-3 * ref.cv.volume);
  EXPECT_NEAR((got.cv.p_WC - ref.cv.p_WC).norm(), 0.0, 1e-3 * kR);
  EXPECT_NEAR((got.cv.n_W - ref.cv.n_W).norm(), 0.0, 1e-3);
  std::cout << "tilted: slices " << got.cv.volume << " (bound " << got.volume_error_bound
            << "), refined " << ref.cv.volume << " (level " << ref.level << ", bound "
            << ref.volume_error_bound << ")\n";
  // under a rigid motion of both, and swapped
  const Isometry3d X_WB = test::randomPose(5);
  const RecoveredContact moved = recoveredMeshMeshContact(k.b, X_WB, k.a, X_WB * X_BA);
  ASSERT_EQ(moved.representation, Representation::kRevolutionInBore) << moved.reason;
  // the polar breakpoints are found by bisection to 1e-15 of their ranges, the quadratures
  // asked 1e-10: the moved query agrees to far below the refinement's 0.1 %
  EXPECT_NEAR(moved.cv.volume, got.cv.volume, 1e-8 * got.cv.volume);
  EXPECT_NEAR((moved.cv.p_WC - X_WB * got.cv.p_WC).norm(), 0.0, 1e-9 * kR);
  EXPECT_NEAR((moved.cv.n_W + X_WB.linear() * got.cv.n_W).norm(), 0.0, 1e-8);
}

TEST(RecoveredBore, PinInItsClearanceTouchesNothing) {
  const PinAndBlock& k = bodies();
  Isometry3d X_BA = Isometry3d::Identity();
  X_BA.translation() = Vector3d(0.00005, 0.0, -0.025);  // 50 µm off the axis, 100 µm clearance
  const RecoveredContact got = recoveredMeshMeshContact(k.a, X_BA, k.b, Isometry3d::Identity());
  EXPECT_EQ(got.representation, Representation::kRevolutionInBore) << got.reason;
  EXPECT_EQ(got.cv.volume, 0.0);
  EXPECT_FALSE(got.cv.inContact());
}

// What the slices do not take stays refined (a low level cap keeps the tests quick; the
// representation and the reason are what is checked).
TEST(RecoveredBore, OtherPairsStayRefined) {
  const PinAndBlock& k = bodies();
  RefinementOptions quick;
  quick.max_level = 3;
  const auto expectRefined = [&](const RecoveredBody& a, const Isometry3d& X_WA,
                                 const RecoveredBody& b, const std::string& why) {
    const RecoveredContact got =
        recoveredMeshMeshContact(a, X_WA, b, Isometry3d::Identity(), quick);
    EXPECT_EQ(got.representation, Representation::kRefined) << why;
    EXPECT_NE(got.reason.find(why), std::string::npos) << got.reason;
  };
  // a sphere is not a solid of revolution here (its closed form is the sphere's own)
  const TriangleMesh ball = geometry::tessellateSphere(0.0049, 32, 17);
  const geometry::SurfaceRecognition recBall = recogniseSurfaces(ball);
  const RecoveredBody sphere(ball, recBall);
  Isometry3d X_BS = Isometry3d::Identity();
  X_BS.translation() = Vector3d(-0.0003, 0.0, -0.01);
  expectRefined(sphere, X_BS, k.b, "the pin is not one solid of revolution");
  // the pin on its side on a box: the box's faces within reach are planes, no bore
  const TriangleMesh box = geometry::tessellateBox(Vector3d(0.04, 0.04, 0.02));
  const geometry::SurfaceRecognition recBox = recogniseSurfaces(box);
  const RecoveredBody plate(box, recBox);
  Isometry3d side = Isometry3d::Identity();
  side.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
  side.translation() = Vector3d(-0.015, 0.0, 0.01 + kR - 1e-5);
  expectRefined(k.a, side, plate, "no concave cylinder");
}

}  // namespace
}  // namespace vcontact::volume
