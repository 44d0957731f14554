// The analytic backend against the closed forms of MODEL.md §5 and, for tilted cylinders,
// against an independent integration (columns along the cylinder axis instead of slices
// across it, with Boost's Gauss–Kronrod in long double).

#include "volume/analytic/primitive_on_plane.hpp"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "geometry/error.hpp"
#include "support/test_support.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using test::relativeDifference;
using LD = long double;

// The backend promises 1e-9 relative; the closed forms are evaluated in long double
// (64-bit mantissa) with series where they would cancel, so they are good to ~1e-15.
constexpr double kPromised = 1e-9;

// The worst relative error each case reached, printed when the suite ends, so that a log
// shows how far inside the promise the backend is (and a regression in accuracy shows up
// before it fails).
class AccuracyLog : public testing::Environment {
 public:
  static void record(const std::string& name, double error) {
    double& worst = table()[name];
    worst = std::max(worst, std::abs(error));
  }
  void TearDown() override {
    std::printf("analytic backend accuracy (worst relative error per case):\n");
    for (const auto& [name, worst] : table()) std::printf("  %-28s %.2e\n", name.c_str(), worst);
  }

 private:
  static std::map<std::string, double>& table() {
    static std::map<std::string, double> t;
    return t;
  }
};
const testing::Environment* const kAccuracyLog = testing::AddGlobalTestEnvironment(new AccuracyLog);

// x − sin x by its Taylor series: no cancellation for small x, exact coefficients.
LD xMinusSin(LD x) {
  LD term = x * x * x / 6.0L, sum = 0.0L;
  for (int j = 1; j < 60; ++j) {
    sum += (j % 2 == 1 ? term : -term);
    term *= x * x / ((2.0L * j + 2.0L) * (2.0L * j + 3.0L));
  }
  return sum;
}

Isometry3d translation(const Vector3d& t) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = t;
  return X;
}

// ---------------------------------------------------------------------------------------
// Sphere: V = πd²(3R − d)/3; centroid d(4R − d)/(4(3R − d)) below the plane;
// J_nn = πd³(20R² − 15Rd + 3d²)/30, J_tt = J_nn/2; a² = 2Rd − d² (πR² past the equator).

struct SphereExpected {
  double V, depthOfCentroid, Jnn, Suu, area;
};

SphereExpected sphereClosedForm(LD R, LD d) {
  const LD V = M_PIl * d * d * (3 * R - d) / 3;
  const LD uBar = d * (8 * R - 3 * d) / (4 * (3 * R - d));
  const LD Suu = M_PIl * d * d * d * d * (R / 2 - d / 5) - V * uBar * uBar;
  return {double(V), double(d * (4 * R - d) / (4 * (3 * R - d))),
          double(M_PIl * d * d * d * (20 * R * R - 15 * R * d + 3 * d * d) / 30), double(Suu),
          double(d <= R ? M_PIl * d * (2 * R - d) : M_PIl * R * R)};
}

TEST(AnalyticSphere, ClosedFormsFromShallowToFullySunk) {
  // R − d is exact in binary for these depths, so the pose carries the intended d exactly.
  const double R = 0.75;
  for (double d : {R * 0x1p-30, R * 0x1p-20, R * 0x1p-10, R * 0x1p-4, R / 2, R, 1.5 * R, 2 * R}) {
    SCOPED_TRACE(testing::Message() << "d/R = " << d / R);
    const auto e = sphereClosedForm(R, d);
    const ContactVolume cv =
        sphereHalfspace(R, translation({0.125, -0.25, R - d}), Isometry3d::Identity());
    EXPECT_NEAR(cv.volume / e.V, 1.0, kPromised);
    AccuracyLog::record("sphere V", cv.volume / e.V - 1.0);
    AccuracyLog::record("sphere centroid depth", cv.p_WC.z() / -e.depthOfCentroid - 1.0);
    AccuracyLog::record(
        "sphere J_s",
        relativeDifference(cv.J_s,
                           Vector3d(e.Jnn / 2, e.Jnn / 2, e.Jnn).asDiagonal().toDenseMatrix()));
    EXPECT_NEAR(cv.p_WC.z(), -e.depthOfCentroid, kPromised * e.depthOfCentroid);
    EXPECT_DOUBLE_EQ(cv.p_WC.x(), 0.125);
    EXPECT_DOUBLE_EQ(cv.p_WC.y(), -0.25);
    EXPECT_LT(relativeDifference(
                  cv.J_s, Vector3d(e.Jnn / 2, e.Jnn / 2, e.Jnn).asDiagonal().toDenseMatrix()),
              kPromised);
    const Matrix3d Jv = Vector3d(e.Jnn / 2 + e.Suu, e.Jnn / 2 + e.Suu, e.Jnn).asDiagonal();
    EXPECT_LT(relativeDifference(cv.J_v, Jv), kPromised);
    EXPECT_NEAR(cv.r_gyr * cv.r_gyr / (e.Jnn / e.V), 1.0, kPromised);
    EXPECT_NEAR(cv.area / e.area, 1.0, kPromised);
    EXPECT_EQ(cv.n_W, Vector3d::UnitZ());
  }
}

TEST(AnalyticSphere, SmallDepthRadiusOfGyrationTendsToContactRadius) {
  // r_gyr² → a²/3 as d → 0 (MODEL.md §5); at d = 2⁻³⁰R the correction is O(d/R).
  const double R = 0.75, d = R * 0x1p-30;
  const ContactVolume cv = sphereHalfspace(R, translation({0, 0, R - d}), Isometry3d::Identity());
  EXPECT_NEAR(cv.r_gyr * cv.r_gyr / ((2 * R * d) / 3), 1.0, 1e-8);
}

TEST(AnalyticSphere, ApartAndTouchingGiveNoContact) {
  const double R = 0.01;
  EXPECT_FALSE(sphereHalfspace(R, translation({0, 0, R}), Isometry3d::Identity()).inContact());
  EXPECT_FALSE(sphereHalfspace(R, translation({0, 0, 2 * R}), Isometry3d::Identity()).inContact());
}

// ---------------------------------------------------------------------------------------
// Cylinder on its side (axis along x_H), θ = acos(1 − d/R):
//   A = R²(θ − sin θ cos θ), V = L A; centroid 4R sin³θ/(3(2θ − sin 2θ)) − R cos θ below;
//   ∫x² dV = A L³/12 (along the axis); ∫y² dV = L R⁴ (12θ − 8 sin 2θ + sin 4θ)/48.

Isometry3d sideLying(double zCentre) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // cylinder z → world x, exactly
  X.translation() = Vector3d(0.0, 0.0, zCentre);
  return X;
}

TEST(AnalyticCylinder, SideLyingClosedForms) {
  const double R = 0.75, L = 1.3;
  for (double d : {R * 0x1p-30, R * 0x1p-20, R * 0x1p-10, R * 0x1p-4, R / 2, R, 1.75 * R}) {
    SCOPED_TRACE(testing::Message() << "d/R = " << d / R);
    const LD theta = 2 * std::asin(std::sqrt(LD(d) / (2 * LD(R))));
    const LD A = LD(R) * R * xMinusSin(2 * theta) / 2;
    // 12θ − 8 sin 2θ + sin 4θ = 8 (2θ − sin 2θ) − (4θ − sin 4θ)... which cancels at θ³;
    // its own series, Σ_{j≥2} (−1)^j [(4θ)^{2j+1} − 8 (2θ)^{2j+1}]/(2j+1)!, does not.
    LD yy = 0, t4 = 4 * theta, t2 = 2 * theta, f = 1;
    LD p4 = t4, p2 = t2;
    for (int j = 1; j < 60; ++j) {
      p4 *= t4 * t4;
      p2 *= t2 * t2;
      f *= (2.0L * j) * (2.0L * j + 1);
      if (j >= 2) yy += (j % 2 == 0 ? 1 : -1) * (p4 - 8 * p2) / f;
    }
    const LD Syy = LD(L) * std::pow(LD(R), 4) * yy / 48;
    const LD Sxx = A * std::pow(LD(L), 3) / 12;
    const LD depthC = 4 * LD(R) * std::pow(std::sin(theta), 3) / (3 * xMinusSin(2 * theta)) -
                      LD(R) * std::cos(theta);

    const ContactVolume cv = cylinderHalfspace(R, L, sideLying(R - d), Isometry3d::Identity());
    EXPECT_NEAR(double(cv.volume / (L * A)), 1.0, kPromised);
    AccuracyLog::record("side-lying cylinder V", double(cv.volume / (L * A)) - 1.0);
    AccuracyLog::record("side-lying centroid depth", cv.p_WC.z() / -double(depthC) - 1.0);
    AccuracyLog::record(
        "side-lying J_s",
        relativeDifference(
            cv.J_s,
            Vector3d(double(Syy), double(Sxx), double(Sxx + Syy)).asDiagonal().toDenseMatrix()));
    EXPECT_NEAR(cv.p_WC.z(), -double(depthC), kPromised * double(depthC));
    EXPECT_NEAR(cv.p_WC.x(), 0.0, kPromised * L);
    const Matrix3d Js = Vector3d(double(Syy), double(Sxx), double(Sxx + Syy)).asDiagonal();
    EXPECT_LT(relativeDifference(cv.J_s, Js), kPromised);
    const double chord = d <= R ? 2 * std::sqrt(d * (2 * R - d)) : 2 * R;
    EXPECT_NEAR(cv.area / (L * chord), 1.0, kPromised);
    EXPECT_LT(cv.relative_error, kPromised);
  }
}

// ---------------------------------------------------------------------------------------
// Punch (flat end down). Aligned: V = πR²d, r_gyr² = R²/2, J_tt = πR⁴d/4.

TEST(AnalyticCylinder, AlignedPunch) {
  const double R = 0.75, L = 0.5;
  for (double d : {R * 0x1p-30, R * 0x1p-8, 0.25, L}) {
    SCOPED_TRACE(testing::Message() << "d = " << d);
    const ContactVolume cv =
        cylinderHalfspace(R, L, translation({0.5, 0.25, L / 2 - d}), Isometry3d::Identity());
    const double V = M_PI * R * R * d;
    EXPECT_NEAR(cv.volume / V, 1.0, kPromised);
    AccuracyLog::record("aligned punch V", cv.volume / V - 1.0);
    AccuracyLog::record("aligned punch J_s", cv.J_s(0, 0) / (M_PI * std::pow(R, 4) * d / 4) - 1.0);
    EXPECT_NEAR(cv.r_gyr * cv.r_gyr / (R * R / 2), 1.0, kPromised);
    EXPECT_NEAR(cv.J_s(0, 0) / (M_PI * std::pow(R, 4) * d / 4), 1.0, kPromised);
    EXPECT_NEAR(cv.p_WC.z(), -d / 2, kPromised * d);
    EXPECT_NEAR(cv.area / (M_PI * R * R), 1.0, kPromised);
  }
}

// Tilted punch, t = tan β, h₀ the distance along the axis from the face centre to the plane:
//   full contact (h₀ ≥ R t): V = πR²h₀; partial, cos α = −h₀/(R t):
//   V = R³ t (sin α − sin³α/3 − α cos α).
double tiltedPunchVolume(double R, double t, double h0) {
  if (h0 >= R * t) return M_PI * R * R * h0;
  const double alpha = std::acos(-h0 / (R * t));
  const double s = std::sin(alpha);
  return R * R * R * t * (s - s * s * s / 3 - alpha * std::cos(alpha));
}

// ---------------------------------------------------------------------------------------
// Independent integration: in the cylinder frame, with x along the in-plane part of the
// half-space normal, the region's extent along the axis at (x, y) is an interval
// [lo(x), hi(x)] that does not depend on y. Integrating the chord (y) and the axis (ζ) in
// closed form leaves a 1-D integral over x = −R cos φ, done by Boost's adaptive
// Gauss–Kronrod in long double, split where hi − lo has kinks. Moments about the region's
// deep corner q (x = −R, deep end of the axis) keep their digits for shallow contact.

struct Reference {
  double V;
  Vector3d centroid_C;
  Matrix3d Sigma_C;
};

Reference integrateCylinderRegion(double R, double L, const Vector3d& n_C, double h) {
  const LD s = std::hypot(LD(n_C.x()), LD(n_C.y())), nz = n_C.z();
  const Vector3d u =
      s > 0 ? Vector3d(n_C.x() / double(s), n_C.y() / double(s), 0) : Vector3d::UnitX();
  const Vector3d v = Vector3d::UnitZ().cross(u);
  const LD zDeep = nz > 0 ? -L / 2.0L : L / 2.0L;
  auto interval = [&](LD x, LD& lo, LD& hi) {  // ζ with n_z ζ ≤ h − s x, within ±L/2
    lo = -L / 2.0L;
    hi = L / 2.0L;
    const LD rhs = h - s * x;
    if (nz > 0)
      hi = std::min(hi, rhs / nz);
    else if (nz < 0)
      lo = std::max(lo, rhs / nz);
    else if (rhs < 0)
      hi = lo;
    if (hi < lo) hi = lo;
  };
  // Quantities in (x' = x + R, ζ' = ζ − ζ_deep): 0 ∫1, 1 ∫x', 2 ∫ζ', 3 ∫x'², 4 ∫y², 5 ∫ζ'²,
  // 6 ∫x'ζ'.
  auto moment = [&](int k) {
    return [&, k](LD phi) -> LD {
      const LD x = -R * std::cos(phi), c = R * std::sin(phi), xp = x + R;
      LD lo, hi;
      interval(x, lo, hi);
      const LD a = lo - zDeep, b = hi - zDeep;
      const LD len = b - a, z1 = (b * b - a * a) / 2, z2 = (b * b * b - a * a * a) / 3;
      const LD jac = R * std::sin(phi);  // dx/dφ
      const LD chord = 2 * c;
      const LD values[7] = {chord * len,           xp * chord * len,        chord * z1,
                            xp * xp * chord * len, 2 * c * c * c / 3 * len, chord * z2,
                            xp * chord * z1};
      return values[k] * jac;
    };
  };
  std::vector<LD> cuts = {0.0L, M_PIl};
  auto addCut = [&](LD x) {
    if (x > -R && x < R) cuts.push_back(std::acos(-x / R));
  };
  if (s > 0) {
    if (nz != 0) {
      addCut((h - nz * L / 2.0L) / s);
      addCut((h + nz * L / 2.0L) / s);
    } else {
      addCut(h / s);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  LD m[7] = {};
  for (int k = 0; k < 7; ++k) {
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      m[k] += boost::math::quadrature::gauss_kronrod<LD, 61>::integrate(moment(k), cuts[i],
                                                                        cuts[i + 1], 12, 1e-14L);
    }
  }
  Reference ref;
  ref.V = double(m[0]);
  const LD cx = m[1] / m[0], cz = m[2] / m[0];
  const LD Sxx = m[3] - m[0] * cx * cx, Szz = m[5] - m[0] * cz * cz, Sxz = m[6] - m[0] * cx * cz;
  const Vector3d q = -R * u + double(zDeep) * Vector3d::UnitZ();
  ref.centroid_C = q + double(cx) * u + double(cz) * Vector3d::UnitZ();
  const Vector3d e = Vector3d::UnitZ();
  ref.Sigma_C = double(Sxx) * u * u.transpose() + double(m[4]) * v * v.transpose() +
                double(Szz) * e * e.transpose() +
                double(Sxz) * (u * e.transpose() + e * u.transpose());
  return ref;
}

struct TiltCase {
  const char* name;
  double tiltDeg;   // angle of the axis from the plane normal
  double depthRel;  // deepest penetration / R
};

class AnalyticCylinderTilted : public testing::TestWithParam<TiltCase> {};

TEST_P(AnalyticCylinderTilted, MatchesIndependentIntegrationUnderARigidMotion) {
  const TiltCase tc = GetParam();
  const double R = 0.0123, L = 0.0371;
  const double beta = tc.tiltDeg * M_PI / 180;
  // Pose in H: axis tilted by β about y, lowest point (the rim, or a whole face edge) at
  // depth d; then both bodies moved by the same random rigid motion.
  Isometry3d X_HC = Isometry3d::Identity();
  X_HC.linear() = Eigen::AngleAxisd(beta, Vector3d::UnitY()).toRotationMatrix();
  const Vector3d n_C0 = X_HC.linear().row(2).transpose();
  const double reach = R * std::hypot(n_C0.x(), n_C0.y()) + std::abs(n_C0.z()) * L / 2;
  X_HC.translation() = Vector3d(0.002, -0.001, reach - tc.depthRel * R);
  const Isometry3d X_WH = test::randomPose(7);
  const Isometry3d X_WC = X_WH * X_HC;

  const ContactVolume cv = cylinderHalfspace(R, L, X_WC, X_WH);

  const Isometry3d X_HC_used = X_WH.inverse() * X_WC;  // the pose as the backend sees it
  const Vector3d n_C = X_HC_used.linear().row(2).transpose();
  const Reference ref = integrateCylinderRegion(R, L, n_C, -X_HC_used.translation().z());
  const Matrix3d R_WC = X_WC.linear();

  // Pose rounding moves the surface by ~1e-16·|t| ≈ 1e-17 m against depths ≥ 1e-6 R here,
  // and both sides integrate that same pose; the backend promises 1e-9.
  EXPECT_NEAR(cv.volume / ref.V, 1.0, kPromised);
  const double size = std::cbrt(ref.V);
  AccuracyLog::record("tilted cylinder V", cv.volume / ref.V - 1.0);
  AccuracyLog::record("tilted cylinder centroid/V^1/3",
                      (cv.p_WC - X_WC * ref.centroid_C).norm() / size);
  AccuracyLog::record(
      "tilted cylinder J_v",
      relativeDifference(
          cv.J_v,
          R_WC * ((ref.Sigma_C.trace() * Matrix3d::Identity() - ref.Sigma_C)) * R_WC.transpose()));
  EXPECT_LT((cv.p_WC - X_WC * ref.centroid_C).norm(), kPromised * size);
  EXPECT_LT(relativeDifference(cv.J_v,
                               R_WC * ((ref.Sigma_C.trace() * Matrix3d::Identity() - ref.Sigma_C)) *
                                   R_WC.transpose()),
            kPromised);
  EXPECT_NEAR(cv.n_W.dot(X_WH.linear().col(2)), 1.0, 1e-15);  // n is z_H: a dot product's ulps
}

TEST(AnalyticCylinder, TiltedPunchMatchesMODELClosedForm) {
  const double R = 0.02, L = 0.05, beta = 0.1;  // t = tan β
  const double t = std::tan(beta);
  for (double h0 : {-0.5 * R * t, 0.0, 0.5 * R * t, 2.0 * R * t}) {
    SCOPED_TRACE(testing::Message() << "h0/(R t) = " << h0 / (R * t));
    // Face centre at distance h₀ below the plane along the axis.
    Isometry3d X_HC = Isometry3d::Identity();
    X_HC.linear() = Eigen::AngleAxisd(beta, Vector3d::UnitY()).toRotationMatrix();
    const Vector3d axis = X_HC.linear().col(2);
    X_HC.translation() = -h0 * axis + (L / 2) * axis;  // face centre = centre − (L/2) axis
    const ContactVolume cv = cylinderHalfspace(R, L, X_HC, Isometry3d::Identity());
    EXPECT_NEAR(cv.volume / tiltedPunchVolume(R, t, h0), 1.0, kPromised);
    AccuracyLog::record("tilted punch V (MODEL form)",
                        cv.volume / tiltedPunchVolume(R, t, h0) - 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, AnalyticCylinderTilted,
                         testing::Values(TiltCase{"punch_rim_shallow", 3.0, 1e-6},
                                         TiltCase{"punch_rim", 7.0, 0.05},
                                         TiltCase{"punch_face_wet", 2.0, 0.3},
                                         TiltCase{"side_tilted_shallow", 87.0, 1e-5},
                                         TiltCase{"side_tilted_deep", 84.0, 0.6},
                                         TiltCase{"oblique", 45.0, 0.2},
                                         TiltCase{"almost_aligned", 1e-7, 1e-3},
                                         TiltCase{"almost_side", 89.99999, 1e-3}),
                         [](const auto& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------------
// Box. Face down: V = a b d, r_gyr² = (a² + b²)/12. Corner down along the body diagonal
// (d ≤ s/√3): V = (√3/2) d³, centroid d/4 below the plane.

TEST(AnalyticBox, FaceDown) {
  const Vector3d size(0.03, 0.05, 0.07);
  for (double d : {0.07 * 0x1p-30, 0.001, 0.07}) {
    const ContactVolume cv =
        boxHalfspace(size, translation({0.1, 0.2, 0.035 - d}), Isometry3d::Identity());
    const double dUsed = 0.035 - (0.035 - d);  // the depth the pose represents
    EXPECT_NEAR(cv.volume / (0.03 * 0.05 * dUsed), 1.0, 1e-12);
    AccuracyLog::record("box face-down V", cv.volume / (0.03 * 0.05 * dUsed) - 1.0);
    EXPECT_NEAR(cv.r_gyr * cv.r_gyr / ((0.03 * 0.03 + 0.05 * 0.05) / 12), 1.0, 1e-12);
    EXPECT_NEAR(cv.p_WC.z(), -dUsed / 2, 1e-12 * dUsed);  // as V: an exact clip's rounding
  }
}

TEST(AnalyticBox, CornerDown) {
  const double s = 0.04;
  Isometry3d X_HB = Isometry3d::Identity();
  X_HB.linear() = test::rotationZTo(Vector3d(1, 1, 1).normalized()).transpose();  // (1,1,1) → z
  for (double d : {1e-9 * s, 1e-4 * s, 0.5 * s}) {
    SCOPED_TRACE(testing::Message() << "d/s = " << d / s);
    const Vector3d corner = X_HB.linear() * Vector3d(-s / 2, -s / 2, -s / 2);
    X_HB.translation() = Vector3d(0, 0, -d - corner.z());
    // The depth the rounded pose represents: the lowest vertex as the backend computes it.
    const double dUsed = -(X_HB * Vector3d(-s / 2, -s / 2, -s / 2)).z();
    const ContactVolume cv = boxHalfspace(Vector3d::Constant(s), X_HB, Isometry3d::Identity());
    EXPECT_NEAR(cv.volume / (std::sqrt(3.0) / 2 * dUsed * dUsed * dUsed), 1.0, 1e-9);
    AccuracyLog::record("box corner-down V",
                        cv.volume / (std::sqrt(3.0) / 2 * dUsed * dUsed * dUsed) - 1.0);
    EXPECT_NEAR(cv.p_WC.z(), -dUsed / 4, 1e-9 * dUsed);  // as V above: the turned pose
  }
}

// ---------------------------------------------------------------------------------------
// Invariance: moving both bodies by one rigid motion moves the result with them.

TEST(AnalyticContact, InvariantUnderRigidMotionOfBothBodies) {
  const geometry::Shape shapes[] = {geometry::Sphere{0.0111}, geometry::Cylinder{0.0123, 0.0371},
                                    geometry::Box{Vector3d(0.021, 0.033, 0.017)}};
  const Isometry3d X_HB = test::randomPose(3, 0.0) * translation({0, 0, 0});
  for (const auto& shape : shapes) {
    SCOPED_TRACE(geometry::describe(shape));
    Isometry3d X_HA = test::randomPose(11, 0.0);
    X_HA.translation() = Vector3d(0.001, 0.002, 0.008);
    const ContactVolume base = analyticContact(shape, X_HA, geometry::HalfSpace{}, X_HB);
    ASSERT_TRUE(base.inContact());
    for (unsigned seed : {21u, 22u, 23u}) {
      const Isometry3d X = test::randomPose(seed);
      const ContactVolume moved = analyticContact(shape, X * X_HA, geometry::HalfSpace{}, X * X_HB);
      const Matrix3d R = X.linear();
      // Rounding of the composed poses: ~1e-16 × |t| / depth, far below 1e-9.
      EXPECT_NEAR(moved.volume / base.volume, 1.0, kPromised);
      EXPECT_LT((moved.p_WC - X * base.p_WC).norm(), kPromised * 0.01);
      EXPECT_LT((moved.n_W - R * base.n_W).norm(), 1e-14);
      EXPECT_LT(relativeDifference(moved.J_s, R * base.J_s * R.transpose()), kPromised);
      EXPECT_LT(relativeDifference(moved.J_v, R * base.J_v * R.transpose()), kPromised);
    }
  }
}

TEST(AnalyticContact, SwappingTheBodiesFlipsOnlyTheNormal) {
  const geometry::Shape ball = geometry::Sphere{0.01};
  const Isometry3d X_WS = translation({0, 0, 0.0095});
  const ContactVolume ab =
      analyticContact(ball, X_WS, geometry::HalfSpace{}, Isometry3d::Identity());
  const ContactVolume ba =
      analyticContact(geometry::HalfSpace{}, Isometry3d::Identity(), ball, X_WS);
  EXPECT_EQ(ab.volume, ba.volume);
  EXPECT_EQ(ab.n_W, -ba.n_W);
  EXPECT_EQ(ab.J_s, ba.J_s);
}

TEST(AnalyticContact, RejectsPairsItDoesNotHandle) {
  EXPECT_THROW(analyticContact(geometry::Sphere{1}, Isometry3d::Identity(), geometry::Sphere{1},
                               Isometry3d::Identity()),
               InputError);
}

}  // namespace
}  // namespace vcontact::volume
