// Simulations with "friction": "distributed" (docs/DISTRIBUTED_FRICTION.md): a flat punch
// on the fixed 64-line column grid, against the closed forms of pointwise Coulomb friction
// (flatPunchFriction) and of the lumped Coulomb + spin + contensou model (lumpedPunchFriction)
// run on the same punch with the exact half-space clip.
//
// Why these numbers keep the comparison valid and the tests fast (~1 s each):
// - kv = 1e9 N/m³ instead of 5.17e12: Coulomb friction is proportional to the normal force
//   whatever kv, so the decelerations do not depend on it; the static penetration becomes
//   ~0.6 µm (not 0.1 nm) and the normal mode ~10× slower, so the explicit steps are ~10× longer.
// - 10 ms of motion: sliding at 0.1 m/s (μ g = 2 m/s²) and spinning at 2 rad/s (≤ 40 rad/s²),
//   ε = v/(ωR) stays within 4.5–5 over the window read, where the closed forms are evaluated
//   at the window's mean ε (M varies as ~1/ε, so the mean is exact to < 1e-3).
// - μ = 0.2 and a coin-like punch, R = 10 mm, 2 mm tall: the friction acts h = 1 mm below
//   the centre of mass, and its moment shifts the pressure centre by μh forward and (through
//   the small lateral force of the spin) sideways. Neither closed form has that shift; it
//   changes both laws' spin torque by ~4(μh/R)² = 1.6e-3 (2.6 % for the bundled 8 mm punch,
//   measured). The punch starts at the forward tilt that balances the moment (see
//   punchScenario), so it does not rock.
// - Dormand–Prince only: the BDF integrator forms Jacobians by 26 extra evaluations each, and
//   the integrators are compared with each other in simulation_test.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynamics/distributed_friction.hpp"
#include "dynamics_fixtures.hpp"
#include "geometry/tessellate.hpp"
#include "validation/punch_friction.hpp"

namespace vcontact::test {
namespace {

using dynamics::FrictionMode;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::Snapshot;

constexpr double kG = 9.81;  // m/s²
constexpr double kMu = 0.2;
constexpr double kRadius = 0.01;      // m
constexpr double kHeight = 0.002;     // m, a coin: see the header
constexpr int kSegments = 64;         // the prism of the bundled punch
constexpr double kSoftKv = 1e9;       // N/m³, see above
constexpr double kV0 = 0.1;           // m/s
constexpr int kFirst = 2, kLast = 8;  // the output samples (ms) the decelerations are read over

/// The radius of the disc with the 64-gon's area, R √(N sin(2π/N)/(2π)) (1 − 8e-4 R): the
/// closed forms are for a disc.
double equalAreaRadius() {
  const double N = kSegments;
  return kRadius * std::sqrt(N * std::sin(2.0 * std::numbers::pi / N) / (2.0 * std::numbers::pi));
}

Model frictionModel() {
  Model m = Model::withEffects({"stiffness", "damping", "coulomb", "spin", "contensou"});
  m.setParameter("stiffness.kv", kSoftKv);
  m.setParameter("damping.a", 10.0);
  m.setParameter("coulomb.mu", kMu);
  return m;
}

/// The punch face down at its static penetration, sliding along x at kV0 and spinning at w0.
Scenario punchScenario(double w0, FrictionMode friction) {
  const Model model = frictionModel();
  const auto prism = std::make_shared<const geometry::TriangleMesh>(
      geometry::tessellateCylinder(kRadius, kHeight, kSegments));
  dynamics::RigidBody punch =
      freeBody("punch", geometry::Mesh{prism, "punch"}, Eigen::Isometry3d::Identity());
  const double R = equalAreaRadius();
  const double face = std::numbers::pi * R * R;  // m²
  const double d = punch.mass * kG / (kSoftKv * face);
  // Start at the tilt that balances the sliding friction's moment about the centre of mass,
  // μ m g h (h = L/2): kv φ ∫x² dS = kv φ πR⁴/4, face tipped forward (about +y). Started flat,
  // the punch rocks at ~570 Hz, a mode the pressure law does not damp (damping acts on the
  // centroid's δ̇ only), and the spin deceleration read over a few ms swings by ±30 % (measured
  // with an 8 mm punch).
  const double tilt = kMu * punch.mass * kG * (kHeight / 2) / (kSoftKv * face * R * R / 4);
  punch.X_WB0 = at({0.0, 0.0, kHeight / 2 * std::cos(tilt) - d});
  punch.X_WB0.linear() = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  punch.v_WBcm0 = Eigen::Vector3d(kV0, 0.0, 0.0);
  punch.w_WB0 = Eigen::Vector3d(0.0, 0.0, w0);
  Scenario s = onPlate(punch, model);
  s.pairs[0].friction = friction;
  s.pairs[0].method = friction == FrictionMode::kDistributed ? volume::Method::kColumns
                                                             : volume::Method::kHalfspace;
  s.settings.duration = kLast * 1e-3;
  s.settings.output_rate_hz = 1e3;
  return s;
}

struct Decelerations {
  double linear;   ///< −dv_x/dt, m/s²
  double angular;  ///< −dω_z/dt, rad/s²
  double eps;      ///< mean v/(ωR) over the window
  double inertia;  ///< I_zz, kg·m²
  double mass;     ///< kg
};

Decelerations decelerations(const Scenario& s) {
  const auto out = run(s);
  const auto& a = out[kFirst].bodies[1];
  const auto& b = out[kLast].bodies[1];
  const double dt = out[kLast].t - out[kFirst].t;
  const double v = 0.5 * (a.v_WBcm.x() + b.v_WBcm.x()), w = 0.5 * (a.w_WB.z() + b.w_WB.z());
  return {(a.v_WBcm.x() - b.v_WBcm.x()) / dt, (a.w_WB.z() - b.w_WB.z()) / dt,
          w > 0.0 ? v / (w * equalAreaRadius()) : INFINITY, s.bodies[1].I_BBcm_B(2, 2),
          s.bodies[1].mass};
}

// Sliding without spin: every column slides the same way, so distributed friction is μ f_n
// exactly and the punch decelerates at μ g, as with the lumped law.
TEST(DistributedSimulation, SlidingPunchDeceleratesAtMuG) {
  const Decelerations dist = decelerations(punchScenario(0.0, FrictionMode::kDistributed));
  const Decelerations lumped = decelerations(punchScenario(0.0, FrictionMode::kLumped));
  std::printf("[measured] sliding: distributed %.6f, lumped %.6f, mu g %.6f m/s^2\n", dist.linear,
              lumped.linear, kMu * kG);
  // The mean normal force over the window is m g up to the change of the vertical momentum
  // (the rocking started by the friction moment, ~1e-5 of m g here): 1e-4 leaves a margin.
  EXPECT_NEAR(dist.linear, kMu * kG, 1e-4 * kMu * kG);
  EXPECT_NEAR(lumped.linear, kMu * kG, 1e-4 * kMu * kG);
  EXPECT_NEAR(dist.linear, lumped.linear, 1e-4 * kMu * kG);
  // No spin appears: Σ p ρ = 0 about the field's own centroid.
  EXPECT_LT(std::abs(dist.angular), 1e-3);  // rad/s², vs ~20 with ω = 2 rad/s below
}

// Sliding and spinning, sliding dominating (ε ≈ 4.7): the spin decelerates at the closed-form
// pointwise torque M = μ N R m(ε), while the lumped model's torque is μ N R g²/√(ε² + g²),
// about twice as high (docs/DISTRIBUTED_FRICTION.md, "Where the lumped model fails").
TEST(DistributedSimulation, SpinDecelerationFollowsThePointwiseTorqueNotTheLumpedOne) {
  constexpr double kW0 = 2.0;  // rad/s: ε = 0.1/(2 × 0.01) = 5 at the start
  const Decelerations dist = decelerations(punchScenario(kW0, FrictionMode::kDistributed));
  const Decelerations lumped = decelerations(punchScenario(kW0, FrictionMode::kLumped));
  const double R = equalAreaRadius();
  const auto torqueDecel = [&](const Decelerations& d, double m) {
    return kMu * d.mass * kG * R * m / d.inertia;  // I ω̇ = −μ N R m(ε), N = m g
  };
  const double exact = torqueDecel(dist, validation::flatPunchFriction(dist.eps).torque);
  // g = r_gyr/R = 1/√2 for a disc (the 64-gon's differs by 3e-4).
  const double lumpedExpected =
      torqueDecel(lumped, validation::lumpedPunchFriction(lumped.eps, 1.0 / std::sqrt(2.0)).torque);
  std::printf(
      "[measured] eps %.3f: spin deceleration distributed %.4f (closed form %.4f), "
      "lumped %.4f (closed form %.4f), lumped/distributed %.4f\n",
      dist.eps, dist.angular, exact, lumped.angular, lumpedExpected, lumped.angular / dist.angular);
  // Distributed: the 64-line grid's torque error (≤ 3.5e-3, distributed_friction_test,
  // FixedColumnGrid) plus the pressure shift (1.6e-3). Lumped (exact clip): the shift alone.
  EXPECT_NEAR(dist.angular / exact, 1.0, 5e-3);
  EXPECT_NEAR(lumped.angular / lumpedExpected, 1.0, 2e-3);
  // The direction the issue states: the lumped spin torque is too high when sliding
  // dominates, by the closed forms' ratio in the same state (→ 2 as ε → ∞; 1.97 at ε = 4.76),
  // far beyond both tolerances above. The two runs' decelerations differ by less (1.88):
  // the lumped run's spin falls faster, so its ε grows and its torque falls.
  const double ratio = validation::lumpedPunchFriction(dist.eps, 1.0 / std::sqrt(2.0)).torque /
                       validation::flatPunchFriction(dist.eps).torque;
  std::printf("[measured] closed forms' torque ratio at eps %.3f: %.4f\n", dist.eps, ratio);
  EXPECT_GT(lumped.angular / dist.angular, 1.8);
  // The force hardly differs at this ε (closed forms: 0.9951 vs 0.9955 of μ N).
  const double forceExact = kMu * kG * validation::flatPunchFriction(dist.eps).force;
  EXPECT_NEAR(dist.linear / forceExact, 1.0, 2e-3);
}

}  // namespace
}  // namespace vcontact::test
