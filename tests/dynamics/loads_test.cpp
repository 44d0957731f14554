// Loads and springs in simulation (dynamics/loads.hpp) against closed forms: a constant force
// gives a parabola, a drive to a fixed target a damped oscillator, a saturated drive a constant
// force; two bodies on a spring keep their momentum and energy and swing with the period of
// their reduced mass. A prescribed body pressed into a fixed one reports the contact force.

#include "dynamics/loads.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynamics/dynamics_fixtures.hpp"
#include "dynamics/simulator.hpp"

namespace vcontact::dynamics {
namespace {

constexpr double kR = 0.01;  // m, sphere radius

Scenario freeFlight(std::size_t bodies) {
  Scenario s;
  s.gravity_W.setZero();
  for (std::size_t i = 0; i < bodies; ++i) {
    s.bodies.push_back(test::freeBody("ball" + std::to_string(i), geometry::Sphere{kR},
                                      Eigen::Isometry3d(Eigen::Translation3d(0.1 * i, 0, 0))));
  }
  s.settings.duration = 0.2;
  s.settings.output_rate_hz = 100.0;
  s.settings.abs_tol = 1e-12;
  s.settings.rel_tol = 1e-10;
  return s;
}

double sphereInertia(const RigidBody& b) { return b.I_BBcm_B(0, 0); }

// m ẍ = F: x = v0 t + F t²/(2m); a constant torque on a sphere: ω = τ t / I (no gyroscopic
// term, I is isotropic). Dormand–Prince integrates a quadratic exactly, so the bound is the
// round-off of ~1e3 steps on 1e-2 m.
TEST(Loads, ConstantForceGivesAParabola) {
  Scenario s = freeFlight(1);
  s.bodies[0].v_WBcm0 = Eigen::Vector3d(0.0, 0.1, 0.0);
  ExternalLoad load;
  load.constant.f_W = Eigen::Vector3d(0.02, 0.0, -0.01);
  load.constant.tau_W = Eigen::Vector3d(0.0, 0.0, 1e-6);
  s.loads.push_back(load);
  const double m = s.bodies[0].mass, I = sphereInertia(s.bodies[0]);
  for (const Snapshot& snap : test::run(s)) {
    const double t = snap.t;
    const Eigen::Vector3d x = s.bodies[0].v_WBcm0 * t + load.constant.f_W * (t * t / (2.0 * m));
    EXPECT_LT((snap.bodies[0].p_WBcm - x).norm(), 1e-12) << t;
    EXPECT_NEAR(snap.bodies[0].w_WB.z(), 1e-6 * t / I, 1e-9 * (1e-6 * t / I) + 1e-15) << t;
    ASSERT_EQ(snap.loads.size(), 1u);
    EXPECT_EQ(snap.loads[0].wrench.f_W, load.constant.f_W);
  }
}

// A force at a point off the centre of mass turns the body: its torque is r × f.
TEST(Loads, ForceAtAPointTurnsTheBody) {
  Scenario s = freeFlight(1);
  s.settings.duration = 1e-3;
  ExternalLoad load;
  load.p_BP = Eigen::Vector3d(0.0, kR, 0.0);
  load.constant.f_W = Eigen::Vector3d(0.01, 0.0, 0.0);
  s.loads.push_back(load);
  const std::vector<Snapshot> out = test::run(s);
  // r × f = (0, R, 0) × (F, 0, 0) = (0, 0, −R F); over 1 ms the turn is ~1e-4 rad, so the
  // lever arm changes by a part in 1e8 and the rate by as much.
  const double expected = -kR * 0.01 * 1e-3 / sphereInertia(s.bodies[0]);
  EXPECT_NEAR(out.back().bodies[0].w_WB.z(), expected, 1e-6 * std::abs(expected));
}

// A table's wrench is interpolated linearly between its rows and held after the last.
TEST(Loads, TableIsInterpolatedLinearly) {
  auto table = std::make_shared<WrenchTable>();
  table->t = {0.0, 0.1, 0.3};
  table->f_W = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 2), Eigen::Vector3d(3, 0, 0)};
  table->tau_W = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0)};
  EXPECT_LT((table->at(0.05).f_W - Eigen::Vector3d(0.5, 0, 1)).norm(), 1e-15);
  EXPECT_LT((table->at(0.2).f_W - Eigen::Vector3d(2, 0, 1)).norm(), 1e-15);
  EXPECT_LT((table->at(0.2).tau_W - Eigen::Vector3d(0, 0.5, 0)).norm(), 1e-15);
  EXPECT_EQ(table->at(1.0).f_W, Eigen::Vector3d(3, 0, 0));
}

// A drive to a fixed target, along z only: m z̈ = −k z − c ż, z(0) = z0, ż(0) = 0:
// z = z0 e^{−ζωt} (cos ω_d t + ζ/√(1−ζ²) sin ω_d t), ω = √(k/m), ω_d = ω √(1−ζ²).
TEST(Loads, DriveToAFixedTargetIsADampedOscillator) {
  Scenario s = freeFlight(1);
  const double m = s.bodies[0].mass, k = 50.0, zeta = 0.1;
  const double w = std::sqrt(k / m), c = 2.0 * zeta * std::sqrt(k * m);
  const double z0 = 0.002;
  s.bodies[0].X_WB0.translation() = Eigen::Vector3d(0, 0, z0);
  ExternalLoad load;
  load.kind = LoadKind::kDrive;
  load.drive.stiffness = Eigen::Vector3d::Constant(k);
  load.drive.damping = Eigen::Vector3d::Constant(c);
  s.loads.push_back(load);
  s.settings.duration = 5.0 * 2.0 * std::numbers::pi / w;
  s.settings.output_rate_hz = 20.0 * w;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  for (const Snapshot& snap : test::run(s)) {
    const double t = snap.t;
    const double z = z0 * std::exp(-zeta * w * t) *
                     (std::cos(wd * t) + zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t));
    // tolerances 1e-10 relative per step over ~1e3 steps: 1e-6 of z0 is a wide margin
    EXPECT_NEAR(snap.bodies[0].p_WBcm.z(), z, 1e-6 * z0) << t;
    EXPECT_NEAR(snap.loads[0].wrench.f_W.z(),
                -k * snap.bodies[0].p_WBcm.z() - c * snap.bodies[0].v_WBcm.z(), 1e-12 * k * z0)
        << t;
  }
}

// With the target far away the drive saturates at f_max: a constant force along the line to
// the target, hence a parabola, until the body comes within f_max / k of it.
TEST(Loads, ForceLimitSaturates) {
  Scenario s = freeFlight(1);
  const double m = s.bodies[0].mass, f_max = 0.05;
  ExternalLoad load;
  load.kind = LoadKind::kDrive;
  load.drive.X_WT0.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);  // 1 m away
  load.drive.stiffness = Eigen::Vector3d::Constant(1e4);            // 1e4 N unlimited
  load.drive.damping = Eigen::Vector3d::Constant(10.0);
  load.drive.max_force = f_max;
  s.loads.push_back(load);
  for (const Snapshot& snap : test::run(s)) {
    const double x = f_max * snap.t * snap.t / (2.0 * m);
    ASSERT_LT(x, 0.5);  // still far: saturated throughout
    EXPECT_NEAR(snap.loads[0].wrench.f_W.norm(), f_max, 1e-12 * f_max) << snap.t;
    EXPECT_NEAR(snap.bodies[0].p_WBcm.x(), x, 1e-12) << snap.t;
  }
}

// A torsional drive turns the body towards the target's attitude: at small angles
// I θ̈ = −k_rot θ, θ = θ0 cos(ω t), ω = √(k_rot / I).
TEST(Loads, TorsionalDriveOscillates) {
  Scenario s = freeFlight(1);
  const double I = sphereInertia(s.bodies[0]), k_rot = 1e-3, theta0 = 1e-3;
  s.bodies[0].X_WB0.linear() = Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitY()).matrix();
  ExternalLoad load;
  load.kind = LoadKind::kDrive;
  load.drive.torsional_stiffness = Eigen::Vector3d::Constant(k_rot);
  s.loads.push_back(load);
  const double w = std::sqrt(k_rot / I);
  s.settings.duration = 2.0 * 2.0 * std::numbers::pi / w;
  s.settings.output_rate_hz = 20.0 * w;
  for (const Snapshot& snap : test::run(s)) {
    const Eigen::AngleAxisd turn(snap.bodies[0].X_WB.linear());
    const double theta = turn.angle() * turn.axis().y();
    // linear about one axis, exact: the bound is the integration error
    EXPECT_NEAR(theta, theta0 * std::cos(w * snap.t), 1e-6 * theta0) << snap.t;
  }
}

// Two balls joined by an undamped spring along x, stretched by 1 mm and drifting together
// along y: momentum stays that of the drift, the energy is conserved, and they swing along x
// with ω = √(k/μ), μ = m1 m2 / (m1 + m2).
TEST(Springs, TwoBodiesConserveMomentumAndEnergy) {
  Scenario s = freeFlight(2);
  s.bodies[0].X_WB0.translation().x() = -0.05;  // small coordinates: small rel_tol · |x|
  s.bodies[1].X_WB0.translation().x() = 0.05;
  s.bodies[1].mass *= 2.0;  // unequal masses (only the mass enters a central spring)
  s.bodies[1].I_BBcm_B *= 2.0;
  BodySpring spring;
  spring.a = 0;
  spring.b = 1;
  spring.p_AP = Eigen::Vector3d(kR, 0, 0);
  spring.p_BQ = Eigen::Vector3d(-kR, 0, 0);
  const double A = 1e-3;  // m, the initial stretch
  spring.rest_length = 0.1 - 2 * kR - A;
  spring.stiffness = 200.0;
  s.springs.push_back(spring);
  for (RigidBody& b : s.bodies) b.v_WBcm0 = Eigen::Vector3d(0, 0.01, 0);
  const double m1 = s.bodies[0].mass, m2 = s.bodies[1].mass, mu = m1 * m2 / (m1 + m2);
  const double period = 2.0 * std::numbers::pi * std::sqrt(mu / spring.stiffness);
  s.settings.duration = 10.0 * period;
  s.settings.output_rate_hz = 200.0 / period;
  SimulationSummary summary;
  const std::vector<Snapshot> out = test::run(s, &summary);
  const Eigen::Vector3d p0 = (m1 + m2) * s.bodies[0].v_WBcm0;
  const auto energy = [&](const Snapshot& snap) {  // oscillation and drift
    const auto& a = snap.bodies[0];
    const auto& b = snap.bodies[1];
    return 0.5 * m1 * a.v_WBcm.squaredNorm() + 0.5 * m2 * b.v_WBcm.squaredNorm() +
           springEnergy(spring, a, b);
  };
  const double e0 = energy(out.front()), e_osc = 0.5 * spring.stiffness * A * A;
  // Each step may move a coordinate by its tolerance ε = abs + rel·|x| (|x| ≤ 0.06 m), which
  // changes the oscillation energy by up to 2ε/A of itself, in position and velocity alike;
  // summed over the steps, that is the integrator's bound on the drift.
  const double eps = s.settings.abs_tol + s.settings.rel_tol * 0.06;
  const double bound = 4.0 * double(summary.steps) * eps / A * e_osc;
  std::vector<double> crossings;  // upward zero crossings of the stretch
  double previous = 0.0;
  for (const Snapshot& snap : out) {
    const Eigen::Vector3d p = m1 * snap.bodies[0].v_WBcm + m2 * snap.bodies[1].v_WBcm;
    // the wrenches are equal and opposite to the bit; the integration error is ~1e-10 rel.
    EXPECT_LT((p - p0).norm(), 1e-9 * p0.norm()) << snap.t;
    EXPECT_NEAR(energy(snap), e0, bound) << snap.t;
    const double stretch =
        (snap.bodies[1].p_WBcm - snap.bodies[0].p_WBcm).x() - 2 * kR - spring.rest_length;
    if (previous < 0.0 && stretch >= 0.0) {
      const double dt = 1.0 / s.settings.output_rate_hz;
      crossings.push_back(snap.t - stretch / (stretch - previous) * dt);
    }
    previous = stretch;
  }
  EXPECT_LT(bound, 1e-4 * e_osc);  // the bound itself is tight enough to mean something
  ASSERT_GE(crossings.size(), 8u);
  // the linear interpolation of a sine at 200 samples a period errs by ~(2π/200)³/6 ≈ 5e-6
  // of a period at its zero
  const double measured = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  EXPECT_NEAR(measured, period, 1e-3 * period);
}

// A torsional spring between two balls: equal and opposite torques, so the total angular
// momentum stays zero, and the relative angle swings with ω = √(k_rot / I_μ).
TEST(Springs, TorsionalSpringSwingsAtTheReducedInertia) {
  Scenario s = freeFlight(2);
  const double I = sphereInertia(s.bodies[0]), k_rot = 1e-3, theta0 = 2e-3;
  BodySpring spring;
  spring.a = 0;
  spring.b = 1;
  spring.torsional_stiffness = k_rot;
  s.springs.push_back(spring);  // rest: the initial relative rotation, identity
  s.bodies[1].w_WB0 = Eigen::Vector3d(0, 0, theta0 * std::sqrt(k_rot / (I / 2.0)));
  const double w = std::sqrt(k_rot / (I / 2.0));
  s.settings.duration = 2.0 * 2.0 * std::numbers::pi / w;
  s.settings.output_rate_hz = 20.0 * w;
  const double L0 = I * s.bodies[1].w_WB0.z();
  for (const Snapshot& snap : test::run(s)) {
    const double L = I * (snap.bodies[0].w_WB.z() + snap.bodies[1].w_WB.z());
    EXPECT_NEAR(L, L0, 1e-9 * L0) << snap.t;
    const double rel =
        Eigen::AngleAxisd(snap.bodies[0].X_WB.linear().transpose() * snap.bodies[1].X_WB.linear())
            .angle();
    // relative angle θ0 |sin ω t|... from rest angle 0 with rate θ0 ω: θ = θ0 sin ω t
    EXPECT_NEAR(rel, std::abs(theta0 * std::sin(w * snap.t)), 1e-6 * theta0) << snap.t;
  }
}

// A prescribed sphere held d into a fixed half-space: the contact force on it is kv V, the
// reading of a force sensor, and a listed or default pair of the two gives it.
TEST(Loads, PrescribedBodyAgainstAFixedOneReportsTheContactForce) {
  Model model = Model::withEffects({"stiffness"});
  model.setParameter("stiffness.kv", 1e11);
  RigidBody ball;
  ball.name = "ball";
  ball.shape = geometry::Sphere{kR};
  ball.motion = BodyMotion::kPrescribed;
  const double d = 1e-4;
  ball.X_WB0.translation() = Eigen::Vector3d(0, 0, kR - d);
  Scenario s = test::onPlate(ball, model);
  s.settings.duration = 1e-3;
  const std::vector<Snapshot> out = test::run(s);
  const double V = std::numbers::pi * d * d * (3 * kR - d) / 3.0;
  EXPECT_NEAR(out.back().pairs[0].result.wrench.f_W.z(), 1e11 * V, 1e-9 * 1e11 * V);
}

}  // namespace
}  // namespace vcontact::dynamics
