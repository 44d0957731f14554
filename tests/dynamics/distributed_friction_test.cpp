// Distributed (pointwise) Coulomb friction and the flat-punch closed form
// (dynamics/distributed_friction.hpp, DISTRIBUTED_FRICTION.md):
//   (a) the elliptic closed form against a direct quadrature of the pointwise traction;
//   (b) the integration over the columns δ map of a tessellated punch against the closed form;
//   (c) the lumped Coulomb + spin + contensou model against the distributed reference.

#include "dynamics/distributed_friction.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "dynamics/model.hpp"
#include "geometry/tessellate.hpp"
#include "support/test_support.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------
// (a) Direct quadrature of F = −p ∫ dir(v(s)) dS, M = −p ∫ s × dir(v(s)) dS over the unit disc
// (R = 1, ω = 1, v = ε along x, μ = 1, N = 1 so p = 1/π). The traction is evaluated pointwise
// from the velocity v + ω ẑ × s; only the placement of the nodes uses the instantaneous
// centre s₀ = (0, ε): polar coordinates (ρ, θ) about s₀, where the integrand is smooth in θ
// and polynomial (degree ≤ 2 after the Jacobian ρ) in ρ. No elliptic integral is involved.

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_n; Abramowitz & Stegun 25.4.29).
std::pair<std::vector<double>, std::vector<double>> gaussLegendre(int n) {
  std::vector<double> x(n), w(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
  return {x, w};
}

/// Adds the traction integrals of the ray from s₀ along `e` between ρ₁ and ρ₂, times `weight`.
void addRay(double eps, const Vector2d& s0, const Vector2d& e, double rho1, double rho2,
            double weight, PunchFriction& sum) {
  static const auto [x, w] = gaussLegendre(3);  // exact for degree ≤ 5 in ρ
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double rho = 0.5 * (rho1 + rho2) + 0.5 * (rho2 - rho1) * x[i];
    const double jac = 0.5 * (rho2 - rho1) * w[i] * rho * weight / kPi;  // p dS, p = 1/π
    const Vector2d s = s0 + rho * e;
    const Vector2d v(eps - s.y(), s.x());  // v + ω ẑ × s
    const Vector2d dir = v.normalized();
    sum.force += jac * dir.x();                          // |F| along −x
    sum.torque += jac * (s.x() * dir.y() - s.y() * dir.x());  // |M| along −z
  }
}

/// F/(μN), M/(μNR) by quadrature with `n` angular nodes.
PunchFriction discQuadrature(double eps, int n) {
  PunchFriction sum{0.0, 0.0};
  const Vector2d s0(0.0, eps);
  if (eps < 1.0) {
    // s₀ inside: every ray leaves the disc once, ρ_max(θ) smooth and periodic, so the
    // trapezoid rule in θ converges geometrically.
    for (int i = 0; i < n; ++i) {
      const double th = 2.0 * kPi * i / n;
      const Vector2d e(std::cos(th), std::sin(th));
      const double b = s0.dot(e);
      addRay(eps, s0, e, 0.0, -b + std::sqrt(b * b + 1.0 - eps * eps), 2.0 * kPi / n, sum);
    }
    return sum;
  }
  // s₀ outside: rays at angle ψ from the direction to the centre with |sin ψ| ≤ 1/ε cross the
  // disc between ε cos ψ ∓ h, h = √(1 − ε² sin²ψ). h has square-root ends; ψ = ψ_m sin φ makes
  // the integrand smooth in φ, integrated by Gauss–Legendre.
  const double psiM = std::asin(1.0 / eps);
  const auto [x, w] = gaussLegendre(n);
  for (int i = 0; i < n; ++i) {
    const double phi = 0.5 * kPi * x[i];
    const double psi = psiM * std::sin(phi);
    const double dpsi = psiM * std::cos(phi) * 0.5 * kPi * w[i];
    const Vector2d e(std::sin(psi), -std::cos(psi));
    const double h = std::sqrt(std::max(0.0, 1.0 - eps * eps * std::sin(psi) * std::sin(psi)));
    addRay(eps, s0, e, eps * std::cos(psi) - h, eps * std::cos(psi) + h, dpsi, sum);
  }
  return sum;
}

TEST(FlatPunchFriction, ClosedFormMatchesDirectQuadratureOfThePointwiseTraction) {
  for (double eps : {0.01, 0.2, 0.45, 0.55, 0.8, 0.97, 1.04, 1.7, 2.2, 5.0, 40.0}) {
    const int n = 800;
    const PunchFriction coarse = discQuadrature(eps, n), fine = discQuadrature(eps, 2 * n);
    // The quadrature has converged: doubling the nodes changes it by round-off only.
    ASSERT_NEAR(coarse.force, fine.force, 1e-12) << eps;
    ASSERT_NEAR(coarse.torque, fine.torque, 1e-12) << eps;
    const PunchFriction exact = flatPunchFriction(eps);
    // Closed form in double (std::comp_ellint, or the series) vs a converged quadrature:
    // both to ~1e-14 (measured ≤ 9e-14); 1e-12 leaves room for other libms.
    EXPECT_NEAR(exact.force / fine.force, 1.0, 1e-12) << eps;
    EXPECT_NEAR(exact.torque / fine.torque, 1.0, 1e-12) << eps;
    std::printf("[measured] eps %-6g F rel err %.2e  M rel err %.2e\n", eps,
                std::abs(exact.force / fine.force - 1.0),
                std::abs(exact.torque / fine.torque - 1.0));
  }
}

TEST(FlatPunchFriction, LimitsOfPureSpinAndPureSliding) {
  // Pure spin: no net force, M = (2/3) μNR (uniform pressure, mean lever arm 2R/3).
  EXPECT_EQ(flatPunchFriction(0.0).force, 0.0);
  EXPECT_DOUBLE_EQ(flatPunchFriction(0.0).torque, 2.0 / 3.0);
  EXPECT_NEAR(flatPunchFriction(1e-9).torque, 2.0 / 3.0, 1e-15);
  // Small ε: F/μN = ε − ε³/8 + O(ε⁵) (series of the closed form, checked by (a)).
  for (double eps : {1e-6, 1e-3, 1e-2}) {
    EXPECT_NEAR(flatPunchFriction(eps).force / (eps - eps * eps * eps / 8.0), 1.0, eps * eps * eps)
        << eps;
  }
  // Pure sliding: F = μN, M = 0; approach M/μNR = 1/(4ε) + O(ε⁻³), 1 − F/μN = 1/(8ε²) + O(ε⁻⁴).
  EXPECT_EQ(flatPunchFriction(INFINITY).force, 1.0);
  EXPECT_EQ(flatPunchFriction(INFINITY).torque, 0.0);
  for (double eps : {1e2, 1e3, 1e6}) {
    const PunchFriction f = flatPunchFriction(eps);
    EXPECT_NEAR(4.0 * eps * f.torque, 1.0, 1.0 / (eps * eps)) << eps;
    EXPECT_NEAR(8.0 * eps * eps * (1.0 - f.force), 1.0, 2.0 / (eps * eps) + 1e-16 * eps * eps)
        << eps;
  }
}

TEST(FlatPunchFriction, BranchesAndSeriesJoinContinuously) {
  // ε = 1 joins the two elliptic branches; ε = 1/2 and 2 switch between series and elliptic
  // forms. F and M are continuous; the log term (ε − 1) ln|ε − 1| of the derivative bounds
  // the jump across 1 ± 1e-9 by ~1e-8.
  const PunchFriction at1 = flatPunchFriction(1.0);
  for (double e : {1.0 - 1e-9, 1.0 + 1e-9}) {
    EXPECT_NEAR(flatPunchFriction(e).force, at1.force, 1e-8);
    EXPECT_NEAR(flatPunchFriction(e).torque, at1.torque, 1e-8);
  }
  for (double e : {0.5, 2.0}) {
    const PunchFriction lo = flatPunchFriction(e * (1.0 - 1e-13));
    const PunchFriction hi = flatPunchFriction(e * (1.0 + 1e-13));
    EXPECT_NEAR(lo.force, hi.force, 1e-13) << e;  // slope ≤ 1, so a jump above 1e-13 is an error
    EXPECT_NEAR(lo.torque, hi.torque, 1e-13) << e;
  }
}

TEST(FlatPunchFriction, RejectsNegativeOrNanRatio) {
  EXPECT_THROW(flatPunchFriction(-1.0), std::invalid_argument);
  EXPECT_THROW(flatPunchFriction(NAN), std::invalid_argument);
  EXPECT_THROW(lumpedPunchFriction(1.0, 0.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// (b), (c): a tessellated steel punch on a plate, both under a random rigid motion.

constexpr double kRadius = 0.0123;   // m, not a binary fraction
constexpr double kDepth = 1.37e-6;   // m
constexpr int kSegments = 512;       // polygon of the cylinder
constexpr double kKv = 5.17e12;      // N/m³ (MODEL.md §4)
constexpr double kMu = 0.2;
constexpr double kVEps = 1e-5;       // m/s, ModelSettings default

/// The equal-area radius of the inscribed 512-gon: R √(N sin(2π/N)/(2π)) (1 − 2.5e-5 R); the
/// closed form is compared for the disc of the same area, leaving an O(1/N²) shape difference.
double equalAreaRadius() {
  return kRadius * std::sqrt(kSegments * std::sin(2.0 * kPi / kSegments) / (2.0 * kPi));
}

struct PunchContact {
  volume::ContactVolume cv;
  volume::ColumnField field;
  Eigen::Isometry3d X_WH;  ///< plate frame: its z is n
};

const PunchContact& punchContact() {
  static const PunchContact c = [] {
    PunchContact pc;
    pc.X_WH = test::randomPose(7);
    const geometry::Mesh punch{std::make_shared<geometry::TriangleMesh>(
                                   geometry::tessellateCylinder(kRadius, 0.02, kSegments)),
                               "punch"};
    Eigen::Isometry3d X_WP = pc.X_WH;
    X_WP.translation() = pc.X_WH * Vector3d(0.0, 0.0, 0.01 - kDepth);
    pc.cv = volume::columnsContact(punch, X_WP, geometry::HalfSpace{}, pc.X_WH, &pc.field);
    return pc;
  }();
  return c;
}

/// Motion at p_c for ε = v/(ωR) with ω = 3 rad/s about n (ε = ∞: ω = 0, v = 0.05 m/s),
/// plus a rolling rate and an approach speed that must not change the friction direction.
RelativeMotion punchMotion(const PunchContact& c, double eps, double approach = 0.0) {
  const Vector3d t = c.X_WH.linear() * Vector3d(0.6, 0.8, 0.0);
  const Vector3d n = c.cv.normal;
  const double w = std::isinf(eps) ? 0.0 : 3.0;
  const double v = std::isinf(eps) ? 0.05 : eps * w * equalAreaRadius();
  return {v * t - approach * n, w * n + 0.7 * c.X_WH.linear().col(0)};
}

TEST(DistributedFriction, PressureIntegratesToTheLumpedNormalForce) {
  const PunchContact& c = punchContact();
  ASSERT_TRUE(c.cv.inContact());
  const double a = 3e4, approach = 2e-5;  // s/m, m/s: 1 + a δ̇ = 1.6
  const DistributedFriction d =
      distributedFriction(c.cv, c.field, {kKv, a}, punchMotion(c, 0.5, approach), kMu, kVEps);
  // Σ kv δ (1 + a δ̇) dS = kv V (1 + a δ̇): the same sum as V, to round-off.
  EXPECT_NEAR(d.f_n / (kKv * c.cv.volume * (1.0 + a * approach)), 1.0, 1e-12);
  EXPECT_NEAR(d.cells * d.cell_area / c.cv.area, 1.0, 1e-12);
}

TEST(DistributedFriction, PureSlidingGivesMuFnAndNoTorque) {
  const PunchContact& c = punchContact();
  const DistributedFriction d =
      distributedFriction(c.cv, c.field, {kKv, 0.0}, punchMotion(c, INFINITY), kMu, kVEps);
  const Vector3d dir = c.X_WH.linear() * Vector3d(0.6, 0.8, 0.0);
  // Every cell slides the same way: f = −μ f_n dir exactly, up to round-off of the sum.
  EXPECT_LT((d.wrench.f_W + kMu * d.f_n * dir).norm(), 1e-12 * kMu * d.f_n);
  // p_c is the δ-weighted centroid of the columns, so Σ p ρ = 0 and the torque vanishes.
  EXPECT_LT(d.wrench.tau_W.norm(), 1e-10 * kMu * d.f_n * kRadius);
}

TEST(DistributedFriction, ColumnsPunchMatchesTheClosedFormWithinTheGridError) {
  const PunchContact& c = punchContact();
  const double R = equalAreaRadius();
  const Vector3d n = c.cv.normal, t = c.X_WH.linear() * Vector3d(0.6, 0.8, 0.0);
  // The midpoint rule's error sits in the rim cells, as does the level-to-level change of V
  // that the backend reports; normalising by f_n of the same cells removes its first-order
  // part, so the reported error bounds what is left. The 512-gon adds < 1e-5 (see above).
  const double tolerance = c.cv.relative_error + 1e-5;
  std::printf("[measured] columns relative_error %.2e, cells %zu\n", c.cv.relative_error,
              c.field.depth.size());
  double worst = 0.0;
  for (double eps : {0.0, 0.1, 0.5, 0.9, 1.0, 1.3, 3.0, 10.0}) {
    const DistributedFriction d =
        distributedFriction(c.cv, c.field, {kKv, 0.0}, punchMotion(c, eps), kMu, kVEps);
    const PunchFriction exact = flatPunchFriction(eps);
    const double F = d.wrench.f_W.norm() / (kMu * d.f_n);
    const double M = -d.wrench.tau_W.dot(n) / (kMu * d.f_n * R);
    // Frames: the force opposes the slip of the centre, the torque opposes ω_n (header).
    const double directionError = eps > 0.0 ? (d.wrench.f_W.normalized() + t).norm() : 0.0;
    EXPECT_LT(directionError, 2.0 * tolerance) << eps;
    EXPECT_LT(d.wrench.tau_W.cross(n).norm(), 1e-9 * kMu * d.f_n * R) << eps;
    EXPECT_NEAR(F, exact.force, tolerance * std::max(exact.force, 0.01)) << eps;
    EXPECT_NEAR(M / exact.torque, 1.0, tolerance) << eps;
    worst = std::max({worst, std::abs(M / exact.torque - 1.0),
                      eps > 0.0 ? std::abs(F / exact.force - 1.0) : 0.0});
    std::printf("[measured] eps %-5g F %.6f (exact %.6f)  M %.6f (exact %.6f)\n", eps, F,
                exact.force, M, exact.torque);
  }
  std::printf("[measured] worst relative difference %.2e vs tolerance %.2e\n", worst, tolerance);
}

TEST(DistributedFriction, RejectsAFieldOfAnotherContactAndBadParameters) {
  const PunchContact& c = punchContact();
  volume::ColumnField other = c.field;
  other.depth.back() *= 2.0;
  const RelativeMotion m = punchMotion(c, 1.0);
  EXPECT_THROW(distributedFriction(c.cv, other, {kKv, 0.0}, m, kMu, kVEps),
               std::invalid_argument);
  EXPECT_THROW(distributedFriction(c.cv, c.field, {kKv, 0.0}, m, NAN, kVEps),
               std::invalid_argument);
  EXPECT_THROW(distributedFriction(c.cv, c.field, {-kKv, 0.0}, m, kMu, kVEps),
               std::invalid_argument);
  EXPECT_THROW(distributedFriction(c.cv, c.field, {kKv, 0.0}, {Vector3d(NAN, 0, 0), {}}, kMu,
                                   kVEps),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// (c) The lumped model (MODEL.md §3: Coulomb + spin + contensou, C_v = |v_t|/v_avg,
// C_ω = r_gyr|ω_n|/v_avg) against the distributed reference on the same contact.

struct Compared {
  double forceRatio, torqueRatio;  ///< lumped / distributed
};

Compared lumpedOverDistributed(double eps) {
  const PunchContact& c = punchContact();
  Model lumped = Model::withEffects({"stiffness", "coulomb", "spin", "contensou"});
  lumped.setParameter("stiffness.kv", kKv);
  lumped.setParameter("coulomb.mu", kMu);
  const RelativeMotion m = punchMotion(c, eps);
  const ContactResult r = lumped.evaluate(c.cv, m, PairState{});
  const DistributedFriction d = distributedFriction(c.cv, c.field, {kKv, 0.0}, m, kMu, kVEps);
  const Vector3d friction = r.wrench.f_W - r.f_n * c.cv.normal;  // stiffness share is along n
  return {friction.norm() / d.wrench.f_W.norm(),
          r.wrench.tau_W.dot(c.cv.normal) / d.wrench.tau_W.dot(c.cv.normal)};
}

TEST(LumpedVsDistributed, RatiosFollowTheClosedFormsOfBoth) {
  const PunchContact& c = punchContact();
  // r_gyr of the columns punch is R/√2 to the grid error (MODEL.md §5).
  const double g = c.cv.r_gyr / equalAreaRadius();
  EXPECT_NEAR(g * std::sqrt(2.0), 1.0, c.cv.relative_error);
  const double tolerance = 2.0 * c.cv.relative_error + 1e-5;  // two grid-level quantities
  for (double eps : {0.01, 0.3, 1.0, 3.0, 30.0}) {
    const Compared got = lumpedOverDistributed(eps);
    const PunchFriction l = lumpedPunchFriction(eps, 1.0 / std::sqrt(2.0));
    const PunchFriction e = flatPunchFriction(eps);
    EXPECT_NEAR(got.forceRatio / (l.force / e.force), 1.0, tolerance) << eps;
    EXPECT_NEAR(got.torqueRatio / (l.torque / e.torque), 1.0, tolerance) << eps;
    std::printf("[measured] eps %-5g lumped/distributed F %.5f M %.5f (closed forms %.5f %.5f)\n",
                eps, got.forceRatio, got.torqueRatio, l.force / e.force, l.torque / e.torque);
  }
}

TEST(LumpedVsDistributed, SpinTorqueIsTwiceTheExactOneWhenSlidingDominates) {
  // Lumped M/μNR = g²/√(ε² + g²) → 1/(2ε) (g² = 1/2); exact → 1/(4ε): the ratio → 2, with
  // corrections O(1/ε²) (closed forms: 2 (1 − 1/(8ε²))/(1 + …)). At ε = 100 that is < 1e-3.
  const PunchContact& c = punchContact();
  const Compared got = lumpedOverDistributed(100.0);
  EXPECT_NEAR(got.torqueRatio, 2.0, 2.0 * (2.0 * c.cv.relative_error + 1e-3));
  EXPECT_NEAR(lumpedPunchFriction(1e4, 1.0 / std::sqrt(2.0)).torque /
                  flatPunchFriction(1e4).torque,
              2.0, 1e-7);
  // The force agrees in that limit, and its deficit 1 − F/μN is twice the exact one too
  // (lumped 1/(4ε²), exact 1/(8ε²)).
  EXPECT_NEAR(got.forceRatio, 1.0, 1e-4);
  const double eps = 1e3;
  EXPECT_NEAR((1.0 - lumpedPunchFriction(eps, 1.0 / std::sqrt(2.0)).force) /
                  (1.0 - flatPunchFriction(eps).force),
              2.0, 1e-5);
}

TEST(LumpedVsDistributed, PureSpinTorqueIsHighByThreeOverTwoRootTwo) {
  // Pure spin: lumped μN r_gyr = μNR/√2, exact (2/3) μNR: ratio 3/(2√2) = 1.0607. They do not
  // agree; they would for r_gyr replaced by the friction radius 2R/3 of uniform pressure.
  const PunchContact& c = punchContact();
  const Compared got = lumpedOverDistributed(0.0);
  EXPECT_NEAR(got.torqueRatio, 3.0 / (2.0 * std::sqrt(2.0)), 3.0 * c.cv.relative_error);
  // Spin-dominated, the lumped force is √2 too high: √2 ε vs ε.
  const Compared small = lumpedOverDistributed(1e-3);
  EXPECT_NEAR(small.forceRatio, std::sqrt(2.0), 2.0 * (2.0 * c.cv.relative_error + 1e-5));
}

}  // namespace
}  // namespace vcontact::dynamics
