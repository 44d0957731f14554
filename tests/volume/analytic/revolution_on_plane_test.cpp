// Solids of revolution on a half-space by closed-form slices
// (volume/analytic/revolution_on_plane.hpp): the curved pieces' path against the cylinder's and the
// sphere's (a cylinder written as a cone of zero slope, a sphere as one arc), a frustum standing on
// its small end and a capsule on its side and on its end against the closed forms of MODEL.md §5, a
// chamfered pin on its side against an independent integration, a dumbbell whose two balls touch
// as two patches against the sphere's closed form, each also under a random rigid motion.

#include "volume/analytic/revolution_on_plane.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_support.hpp"
#include "volume/analytic/circular_segment.hpp"
#include "volume/analytic/primitive_on_plane.hpp"
#include "volume/revolution_references.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using test::randomPose;
using test::relativeDifference;
using vcontact::test::pinOnItsSide;
using vcontact::test::segment;
using vcontact::test::sphereCap;
using Kind = ProfilePiece::Kind;

// The backend promises 1e-9 relative (quadrature to 1e-11 against ∫|f|); the closed forms
// below are evaluated in double, each within a few 1e-16 of the truth at these depths.
constexpr double kPromised = 1e-9;

ProfilePiece linear(double z0, double z1, double r0, double r1) {
  ProfilePiece p;
  p.kind = Kind::kLinear;
  p.z0 = z0;
  p.z1 = z1;
  p.r0 = r0;
  p.r1 = r1;
  return p;
}

ProfilePiece constant(double z0, double z1, double r) {
  ProfilePiece p = linear(z0, z1, r, r);
  p.kind = Kind::kConstant;
  return p;
}

ProfilePiece arc(double z0, double z1, double rho, double zc, double a) {
  ProfilePiece p;
  p.kind = Kind::kArc;
  p.z0 = z0;
  p.z1 = z1;
  p.rho_c = rho;
  p.z_c = zc;
  p.a = a;
  return p;
}

void expectSameContact(const ContactVolume& a, const ContactVolume& b, double tol) {
  ASSERT_GT(b.volume, 0.0);
  EXPECT_NEAR(a.volume, b.volume, tol * b.volume);
  const double scale = std::cbrt(b.volume);  // centroids compared against the region's size
  EXPECT_LT((a.p_WC - b.p_WC).norm() / scale, tol * 10.0);
  EXPECT_LT(relativeDifference(a.J_v, b.J_v), tol * 10.0);
  EXPECT_NEAR(a.area, b.area, tol * 10.0 * b.area);
  EXPECT_NEAR(a.depth, b.depth, 1e-15);  // a few ulps of the poses' 0.37 m translations
}

// A pose of the solid's frame with its axis tilted by `tilt` from the plane's normal and its
// deepest point (of a body of largest radius R, profile from z0 to z1) at depth d.
Isometry3d tilted(double tilt, double d, double R, double z0, double z1) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(tilt, Vector3d::UnitY()).toRotationMatrix();
  const double s = std::sin(tilt), c = std::cos(tilt);
  const double lowest = std::min(-s * R + c * z0, -s * R + c * z1);  // of the rims
  X.translation().z() = -lowest - d;
  return X;
}

TEST(AnalyticRevolution, ZeroSlopeConeAndSplitCylinderAreTheCylinder) {
  const double R = 0.01, L = 0.03;
  const RevolutionProfile cone = {linear(-0.5 * L, 0.5 * L, R, R)};
  const RevolutionProfile split = {constant(-0.5 * L, 0.001, R), constant(0.001, 0.5 * L, R)};
  for (unsigned seed = 1; seed <= 40; ++seed) {
    const double tilt = seed % 4 == 0 ? M_PI / 2 : 1.5 * (seed % 7) / 7.0 + 0.01;
    const double d = R * std::pow(10.0, -4.0 + 4.0 * (seed % 5) / 5.0);
    const Isometry3d X = tilted(tilt, d, R, -0.5 * L, 0.5 * L);
    const Isometry3d M = randomPose(seed);
    const ContactVolume ref = cylinderHalfspace(R, L, M * X, M);
    SCOPED_TRACE(seed);
    expectSameContact(revolutionHalfspace(cone, M * X, M), ref, kPromised);
    expectSameContact(revolutionHalfspace(split, M * X, M), ref, kPromised);
  }
}

TEST(AnalyticRevolution, OneArcIsTheSphere) {
  const double R = 0.01;
  const RevolutionProfile ball = {arc(-R, R, 0.0, 0.0, R)};
  for (unsigned seed = 1; seed <= 30; ++seed) {
    const double d = R * std::pow(10.0, -4.0 + 4.3 * (seed % 6) / 5.0);  // up to 2R
    Isometry3d X = Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(0.3 * seed, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    X.translation() = Vector3d(0.002, -0.001, R - std::min(d, 1.9 * R));
    const Isometry3d M = randomPose(seed);
    SCOPED_TRACE(seed);
    expectSameContact(revolutionHalfspace(ball, M * X, M), sphereHalfspace(R, M * X, M), kPromised);
  }
}

TEST(AnalyticRevolution, FrustumOnItsSmallEndIsTheConeFrustum) {
  // Radii 4 mm at the bottom, 6 mm at the top, 10 mm high: pressed d, the wetted frustum has
  // radii r0 and r0 + d·k, V = πd(r0² + r0 r_d + r_d²)/3, its centroid on the axis.
  const double r0 = 0.004, r1 = 0.006, H = 0.01, k = (r1 - r0) / H;
  const RevolutionProfile frustum = {linear(0.0, H, r0, r1)};
  for (double d : {1e-6, 1e-5, 1e-4, 1e-3, 5e-3}) {
    const double rd = r0 + k * d;
    const double V = M_PI * d * (r0 * r0 + r0 * rd + rd * rd) / 3.0;
    const double zBar =
        d * (r0 * r0 + 2 * r0 * rd + 3 * rd * rd) / (4.0 * (r0 * r0 + r0 * rd + rd * rd));
    for (unsigned seed : {0u, 3u, 11u}) {
      const Isometry3d M = seed == 0 ? Isometry3d::Identity() : randomPose(seed);
      Isometry3d X = Isometry3d::Identity();
      X.translation().z() = -d;
      const ContactVolume cv = revolutionHalfspace(frustum, M * X, M);
      SCOPED_TRACE(d);
      EXPECT_NEAR(cv.volume, V, kPromised * V);
      EXPECT_LT((M.inverse() * cv.p_WC - Vector3d(0, 0, zBar - d)).norm(), kPromised * H);
      EXPECT_NEAR(cv.area, M_PI * rd * rd, kPromised * cv.area);  // the cut disc
      EXPECT_NEAR(cv.depth, d, 1e-15);
    }
  }
}

// A capsule of radius R, straight length L along z from 0: hemispheres centred at 0 and L.
RevolutionProfile capsule(double R, double L) {
  ProfilePiece top = arc(L, L + R, 0.0, L, R);
  return {arc(-R, 0.0, 0.0, 0.0, R), constant(0.0, L, R), top};
}

TEST(AnalyticRevolution, CapsuleOnItsSideIsSegmentTimesLengthPlusSphereCap) {
  // The two hemispheres lying on their side make one sphere's cap.
  const double R = 0.005, L = 0.02;
  for (double ratio : {1e-4, 1e-3, 1e-2, 0.5, 1.5}) {
    const double d = ratio * R;
    const double V = L * segment(R, d) + sphereCap(R, d);
    for (unsigned seed : {0u, 5u, 9u}) {
      const Isometry3d M = seed == 0 ? Isometry3d::Identity() : randomPose(seed);
      Isometry3d X = Isometry3d::Identity();
      X.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
      X.translation() = Vector3d(0.0, 0.0, R - d);
      const ContactVolume cv = revolutionHalfspace(capsule(R, L), M * X, M);
      SCOPED_TRACE(ratio);
      EXPECT_NEAR(cv.volume, V, kPromised * V);
      // The centroid lies under the axis' middle, by symmetry.
      const Vector3d c = M.inverse() * cv.p_WC;
      EXPECT_NEAR(c.x(), 0.5 * L, kPromised * L);
      EXPECT_NEAR(c.y(), 0.0, kPromised * L);
    }
  }
}

TEST(AnalyticRevolution, CapsuleOnItsEndIsTheSphereCap) {
  const double R = 0.005, L = 0.02;
  for (double ratio : {1e-4, 1e-2, 0.7}) {
    const double d = ratio * R;
    for (double tilt : {0.0, 1e-9}) {  // exactly along the normal, and the tilted path
      Isometry3d X = Isometry3d::Identity();
      X.linear() = Eigen::AngleAxisd(tilt, Vector3d::UnitX()).toRotationMatrix();
      X.translation().z() = R - d;
      const ContactVolume cv = revolutionHalfspace(capsule(R, L), X, Isometry3d::Identity());
      const ContactVolume ref = sphereHalfspace(R, X, Isometry3d::Identity());
      SCOPED_TRACE(tilt);
      // At a tilt of 1e-9 the capsule's sphere is the same to 1e-9·R in its lowest point.
      expectSameContact(cv, ref, tilt == 0.0 ? kPromised : 2e-8 / ratio);
    }
  }
}

TEST(AnalyticRevolution, ChamferedPinOnItsSideAgainstSimpson) {
  const double r = 0.005, Lp = 0.03, c = 0.0005;
  const RevolutionProfile pin = {linear(0.0, c, r - c, r), constant(c, Lp - c, r),
                                 linear(Lp - c, Lp, r, r - c)};
  for (double ratio : {1e-4, 1e-3, 1e-2, 0.09}) {
    const double d = ratio * r;
    const double V = pinOnItsSide(r, Lp, c, d);
    for (unsigned seed : {0u, 2u, 7u}) {
      const Isometry3d M = seed == 0 ? Isometry3d::Identity() : randomPose(seed);
      Isometry3d X = Isometry3d::Identity();
      X.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
      X.translation() = Vector3d(0.0, 0.0, r - d);
      const ContactVolume cv = revolutionHalfspace(pin, M * X, M);
      SCOPED_TRACE(ratio);
      EXPECT_NEAR(cv.volume, V, kPromised * V);
      EXPECT_NEAR((M.inverse() * cv.p_WC).x(), 0.5 * Lp, kPromised * Lp);  // symmetric
    }
  }
}

// A pin of radius R with a fillet of radius f at its lower end (a torus' outer half: centre
// ρ_c = R − f, z_c = f), standing on its end pressed d < f: every slice is a whole disc, and
// V = ∫₀^d π r(z)² dz with r = ρ_c + √(f² − (z − f)²), in closed form:
// π[ρ_c² t + 2ρ_c F(t) + f² t − t³/3] between t = −f and d − f, F(t) = (t√(f² − t²) + f²
// asin(t/f))/2.
TEST(AnalyticRevolution, FilletedPinOnItsEndIsItsDiscsIntegrated) {
  const double R = 0.005, f = 0.001, L = 0.02, rho = R - f;
  ProfilePiece fillet = arc(0.0, f, rho, f, f);
  const RevolutionProfile pin = {fillet, constant(f, L, R)};
  const auto G = [&](double t) {
    const double F = 0.5 * (t * std::sqrt(f * f - t * t) + f * f * std::asin(t / f));
    return M_PI * (rho * rho * t + 2.0 * rho * F + f * f * t - t * t * t / 3.0);
  };
  for (double d : {1e-7, 1e-5, 5e-4}) {
    const double expected = G(d - f) - G(-f);
    for (unsigned seed : {0u, 19u, 23u}) {
      const Isometry3d M = seed == 0 ? Isometry3d::Identity() : randomPose(seed);
      Isometry3d X = Isometry3d::Identity();
      X.translation().z() = -d;
      const ContactVolume cv = revolutionHalfspace(pin, M * X, M);
      SCOPED_TRACE(d);
      // G's terms cancel to the volume's size: ~1e-16 of π ρ_c² f over V, 4e-9 at d = 1e-7
      EXPECT_NEAR(cv.volume, expected, 1e-8 * expected + 1e-15 * M_PI * rho * rho * f);
      EXPECT_LT((M.inverse() * cv.p_WC).head<2>().norm(), 1e-9 * R);  // on the axis
    }
  }
}

// A dumbbell (two balls of radius R, their centres Lc apart, joined by a bar of radius rb)
// lying on the plane, tilted by ε so that the balls sink to different depths while the bar
// stays dry: two regions, each the closed-form cap of its ball (its slices, a sphere arc cut
// where the bar joins it, are the whole cap because the cap's slices end before the joint,
// √(R² − (R − d)²) < √(R² − rb²)). The aggregate is the one region of all the slices, with the
// summed volume. Tilted the other way, the far ball lifts off: one patch, the aggregate.
TEST(AnalyticRevolution, DumbbellOnThePlaneIsTwoPatchesOneCapPerBall) {
  const double R = 0.005, rb = 0.002, Lc = 0.03, zj = std::sqrt(R * R - rb * rb);
  const RevolutionProfile dumbbell = {arc(-R, zj, 0.0, 0.0, R), constant(zj, Lc - zj, rb),
                                      arc(Lc - zj, Lc + R, 0.0, Lc, R)};
  for (double d : {1e-6, 1e-5, 2e-4}) {
    for (unsigned seed : {0u, 5u, 11u}) {
      const Isometry3d M = seed == 0 ? Isometry3d::Identity() : randomPose(seed);
      const double eps = 1e-3;  // the far ball 30 µm deeper
      Isometry3d X = Isometry3d::Identity();
      X.linear() = Eigen::AngleAxisd(M_PI / 2 + eps, Vector3d::UnitY()).toRotationMatrix();
      X.translation() = Vector3d(0.0, 0.0, R - d);
      const Isometry3d near = M * X, far = M * X * Eigen::Translation3d(0.0, 0.0, Lc);
      const ContactPatches c = revolutionHalfspacePatches(dumbbell, near, M);
      SCOPED_TRACE(testing::Message() << "d " << d << " seed " << seed);
      ASSERT_EQ(c.patches.size(), 2u);
      // sortPatches: the deeper (far) ball's cap first
      expectSameContact(c.patches[0], sphereHalfspace(R, far, M), kPromised);
      expectSameContact(c.patches[1], sphereHalfspace(R, near, M), kPromised);
      EXPECT_NEAR(c.aggregate.volume, c.patches[0].volume + c.patches[1].volume,
                  1e-14 * c.aggregate.volume);
      const ContactVolume whole = revolutionHalfspace(dumbbell, near, M);
      EXPECT_EQ(whole.volume, c.aggregate.volume);  // the same numbers, to the bit
      EXPECT_EQ(whole.p_WC, c.aggregate.p_WC);
      // tilted the other way by 10 d / Lc about the near ball's centre, the far ball lifts off
      Isometry3d Y = X;
      Y.linear() =
          Eigen::AngleAxisd(M_PI / 2 - 10.0 * d / Lc, Vector3d::UnitY()).toRotationMatrix();
      const ContactPatches one = revolutionHalfspacePatches(dumbbell, M * Y, M);
      ASSERT_EQ(one.patches.size(), 1u);
      EXPECT_EQ(one.patches[0].volume, one.aggregate.volume);
    }
  }
}

// The curved pieces' shorter series (Horner, as many terms as θ needs) against the cylinder's
// full one: both are sums of the same exact coefficients, so they agree to rounding; 1e-14
// leaves room for a few ulps of the thinnest segments' cancellation-free sums.
TEST(AnalyticRevolution, ShallowSegmentSeriesAgreesWithTheFullOne) {
  double worst = 0.0;
  for (int i = 1; i <= 3000; ++i) {
    const double theta = 0.7499 * i / 3000.0 * (i % 3 == 0 ? 1e-4 : 1.0);
    const detail::Segment a = detail::segmentMoments(0.3, theta);
    const detail::Segment b = detail::shallowSegmentMoments(0.3, theta);
    for (const auto& [x, y] : {std::pair{a.A, b.A}, {a.S1, b.S1}, {a.S11, b.S11}, {a.S22, b.S22}})
      worst = std::max(worst, std::abs(x - y) / std::abs(x));
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(AnalyticRevolution, RejectsAProfileWithAGap) {
  const RevolutionProfile gap = {constant(0.0, 1.0, 0.5), constant(1.5, 2.0, 0.5)};
  EXPECT_NE(test::inputErrorMessage([&] {
              revolutionHalfspace(gap, Isometry3d::Identity(), Isometry3d::Identity());
            }).find("piece 1"),
            std::string::npos);
  EXPECT_FALSE(test::inputErrorMessage([&] {
                 revolutionHalfspace({}, Isometry3d::Identity(), Isometry3d::Identity());
               }).empty());
}

}  // namespace
}  // namespace vcontact::volume
