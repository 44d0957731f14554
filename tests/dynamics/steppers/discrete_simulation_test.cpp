// The discrete stepper in whole runs (Integrator::kDiscrete, docs/DISCRETE.md §4): a box at
// rest on a plate, a block on a 10° incline that sticks or slides, a frictionless elastic
// bounce, the restitution of a damped drop, and the stops of a run.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynamics/simulator.hpp"
#include "dynamics_fixtures.hpp"
#include "geometry/error.hpp"

namespace vcontact::test {
namespace {

using dynamics::Integrator;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::Snapshot;
using Eigen::Vector3d;

constexpr double kG = 9.81;
constexpr double kSide = 0.02;  // m, cube edge

// The plain step unless `mode` says otherwise: these tests are of the linearly implicit step
// itself (discrete_impacts_test.cpp has those of the resolved impacts).
Scenario discrete(Scenario s, double h, double duration, double rate = 1000.0,
                  dynamics::ImpactMode mode = dynamics::ImpactMode::kImplicit) {
  s.settings.integrator = Integrator::kDiscrete;
  s.settings.impacts = mode;
  s.settings.step = h;
  s.settings.duration = duration;
  s.settings.output_rate_hz = rate;
  return s;
}

// The steel model of the rigs (MODEL.md §4) with its bristles, softened to kv = 1e9 N/m³ so
// that the static sink of a 20 mm steel cube (m g / (kv A) = 1.55 µm) is resolved by 1 µm.
Model steel(double kv = 1e9, double mu = 0.2) {
  Model m = Model::withEffects(
      {"stiffness", "damping", "rolling_resistance", "coulomb", "stribeck", "bristle", "spin"});
  m.setParameter("stiffness.kv", kv);
  m.setParameter("damping.a", 20.0);
  m.setParameter("coulomb.mu", mu);
  m.setParameter("stribeck.mu_s", mu);
  return m;
}

dynamics::RigidBody cube(double depth) {
  return freeBody("box", geometry::Box{Vector3d::Constant(kSide)},
                  at({0.0, 0.0, kSide / 2 - depth}));
}

double staticSink(const dynamics::RigidBody& body, const Model& m, double g_n) {
  return body.mass * g_n / (m.parameter("stiffness.kv") * kSide * kSide);  // V = m g / kv
}

// Placed at the static sink, the box stays there for 10 s at h = 1 ms: no drift, no chatter.
TEST(DiscreteSimulation, BoxRestsAtTheStaticSinkForTenSeconds) {
  const Model m = steel();
  const double d = staticSink(cube(0.0), m, kG);
  const auto out = run(discrete(onPlate(cube(d), m), 1e-3, 10.0, 100.0));
  ASSERT_EQ(out.size(), 1001u);
  double worst = 0.0, lateral = 0.0;
  for (const Snapshot& s : out) {
    worst = std::max(worst, std::abs(s.bodies[1].p_WBcm.z() - (kSide / 2 - d)));
    lateral = std::max(lateral, s.bodies[1].p_WBcm.head<2>().norm());
  }
  EXPECT_LT(worst, 1e-6);  // the brief's bound
  EXPECT_LT(lateral, 1e-9);
  // the fixed point of the step is the static equilibrium itself
  EXPECT_NEAR(out.back().bodies[1].p_WBcm.z(), kSide / 2 - d, 1e-3 * d);
}

// Released 0.1 mm above the plate at the rigs' stiffness (static sink 0.3 nm), the box does
// not come to rest: a step out of contact lets it fall g h² (9.8 µm at 1 ms) into the plate,
// and the next step, backward Euler on a contact mode of 37 kHz, pushes it back to the
// surface with the velocity that removes that depth in one step. It hops on the surface
// with an amplitude of about g h² (docs/DISCRETE.md §5): bounded, never growing.
TEST(DiscreteSimulation, DroppedBoxAtRigStiffnessHopsWithinGravityStep) {
  const Model m = steel(5.17e12);
  for (const double h : {1e-3, 5e-4}) {
    const double d = staticSink(cube(0.0), m, kG);
    const auto out = run(discrete(onPlate(cube(-1e-4), m), h, 1.0, 1.0 / h));
    for (std::size_t i = out.size() / 2; i < out.size(); ++i) {
      // a 10 % margin on g h² for the damping's share of the push-back
      EXPECT_LT(std::abs(out[i].bodies[1].p_WBcm.z() - (kSide / 2 - d)), 1.1 * kG * h * h)
          << "h = " << h << ", t = " << out[i].t;
      EXPECT_LT(out[i].bodies[1].p_WBcm.head<2>().norm(), 1e-9);
    }
  }
}

// Gravity tilted by 10° about y: the plate is an incline. Returns the snapshots.
std::vector<Snapshot> onIncline(const Model& m, double h, double duration) {
  constexpr double kTheta = 10.0 * std::numbers::pi / 180.0;
  const double d = staticSink(cube(0.0), m, kG * std::cos(kTheta));
  Scenario s = discrete(onPlate(cube(d), m), h, duration, 100.0);
  s.gravity_W = kG * Vector3d(std::sin(kTheta), 0.0, -std::cos(kTheta));
  return run(s);
}

// μ = 0.3 > tan 10° = 0.176: the bristles hold the block; it creeps below 1 µm/s.
TEST(DiscreteSimulation, BlockSticksOnTenDegreeInclineWithMuPointThree) {
  for (const double h : {1e-3, 5e-4}) {
    const auto out = onIncline(steel(1e9, 0.3), h, 2.0);
    const double drift = (out.back().bodies[1].p_WBcm.x() - out[100].bodies[1].p_WBcm.x()) /
                         (out.back().t - out[100].t);
    EXPECT_LT(std::abs(drift), 1e-6) << "h = " << h;
    EXPECT_LT(std::abs(out.back().bodies[1].v_WBcm.x()), 1e-6) << "h = " << h;
  }
}

// μ = 0.1: the block slides at g (sin θ − μ cos θ) = 0.738 m/s², within 1 %.
TEST(DiscreteSimulation, BlockSlidesOnTenDegreeInclineWithMuPointOne) {
  constexpr double kTheta = 10.0 * std::numbers::pi / 180.0;
  const double expected = kG * (std::sin(kTheta) - 0.1 * std::cos(kTheta));
  for (const auto& effects : {std::vector<std::string>{"stiffness", "damping", "coulomb"},
                              {"stiffness", "damping", "coulomb", "bristle"}}) {
    Model m = Model::withEffects(effects);
    m.setParameter("stiffness.kv", 1e9);
    m.setParameter("damping.a", 20.0);
    m.setParameter("coulomb.mu", 0.1);
    const auto out = onIncline(m, 1e-3, 1.0);
    const double a =
        (out[100].bodies[1].v_WBcm.x() - out[50].bodies[1].v_WBcm.x()) / (out[100].t - out[50].t);
    EXPECT_NEAR(a, expected, 0.01 * expected) << effects.size() << " effects";
  }
}

constexpr double kBallRadius = 0.01;

// A steel ball dropped 5 mm (ball_drop): the first impact's restitution (rebound speed over
// impact speed, from the outputs before and after the contact) and whether the energy
// m g z + ½ m v² of any output out of contact exceeded the drop's by more than `slack`.
struct Drop {
  double restitution = 0.0;  // 0 when the ball never leaves the plate again
  double impact_speed = 0.0;
  double worst_gain = 0.0;  // J, the largest excess over the drop's energy out of contact
};

Drop drop(const Model& m, double h, double duration) {
  constexpr double R = kBallRadius;
  dynamics::RigidBody ball = freeBody("ball", geometry::Sphere{R}, at({0.0, 0.0, R + 0.005}));
  const double mass = ball.mass;
  const auto out = run(discrete(onPlate(ball, m), h, duration, 1.0 / h));
  auto energy = [&](const Snapshot& s) {
    return mass * kG * (s.bodies[1].p_WBcm.z() - R) + 0.5 * mass * s.bodies[1].v_WBcm.squaredNorm();
  };
  Drop d;
  const double e0 = energy(out.front());
  bool landed = false;
  for (const Snapshot& s : out) {
    const bool contact = s.pairs[0].cv.inContact();
    if (!contact) d.worst_gain = std::max(d.worst_gain, energy(s) - e0);
    if (!landed && !contact) d.impact_speed = -s.bodies[1].v_WBcm.z();
    if (landed && !contact && d.restitution == 0.0)
      d.restitution = s.bodies[1].v_WBcm.z() / d.impact_speed;
    landed = landed || contact;
  }
  return d;
}

// Stiffness alone (no dissipation in the model): out of contact the energy never exceeds the
// drop's (beyond the ½ m g² h² of one step's position error), and backward Euler's numerical
// dissipation shrinks with h: the restitution grows towards 1 as h falls, never above it.
TEST(DiscreteSimulation, FrictionlessElasticBounceNeverGainsEnergy) {
  Model m = Model::withEffects({"stiffness"});
  m.setParameter("stiffness.kv", 5.17e12);
  double previous = -1.0;
  for (const double h : {1e-3, 1e-4, 1e-5, 1e-6}) {
    const Drop d = drop(m, h, 0.1);
    const double mass = kSteelDensity * 4.0 / 3.0 * std::numbers::pi * std::pow(kBallRadius, 3);
    EXPECT_LE(d.worst_gain, 0.5 * mass * kG * kG * h * h + 1e-12) << "h = " << h;
    EXPECT_LT(d.restitution, 1.0) << "h = " << h;
    EXPECT_GT(d.restitution, previous) << "h = " << h;
    previous = d.restitution;
  }
}

// Stiffness and damping (a = 1 s/m, ball_drop's model without friction): backward Euler
// converges to the exact restitution of MODEL.md §5 at first order in h. At h = 1 µs (a
// 280th of the impact's 0.28 ms) it is 2 % low; the Richardson extrapolation 2 e(h) − e(2h)
// is within 1 % (docs/DISCRETE.md §5 tabulates e(h)).
TEST(DiscreteSimulation, DampedDropRestitutionConvergesToTheExactRelation) {
  Model m = Model::withEffects({"stiffness", "damping"});
  m.setParameter("stiffness.kv", 5.17e12);
  m.setParameter("damping.a", 1.0);
  const Drop fine = drop(m, 1e-6, 0.04), coarse = drop(m, 2e-6, 0.04);
  const double exact = exactRestitution(1.0 * fine.impact_speed);
  EXPECT_NEAR(fine.restitution, exact, 0.025 * exact);
  EXPECT_LT(fine.restitution, exact);  // backward Euler dissipates
  EXPECT_NEAR(2.0 * fine.restitution - coarse.restitution, exact, 0.01 * exact);
}

// The stops of a run keep working: a contact far too soft for a steel ball lets it sink
// through (penetration_beyond_bound), and a step outside its range is refused up front.
TEST(DiscreteSimulation, PenetrationStopsAndStepRangeIsChecked) {
  Model m = Model::withEffects({"stiffness", "damping"});
  m.setParameter("stiffness.kv", 1e3);
  dynamics::RigidBody ball =
      freeBody("ball", geometry::Sphere{kBallRadius}, at({0.0, 0.0, kBallRadius}));
  const Scenario s = discrete(onPlate(ball, m), 1e-3, 1.0);
  try {
    run(s);
    FAIL() << "the ball should have sunk through the plate";
  } catch (const dynamics::SimulationError& e) {
    EXPECT_EQ(e.cause(), dynamics::StopCause::kPenetration);
    EXPECT_LT(e.time(), 1.0);
  }
  Scenario bad = s;
  bad.settings.step = 0.05;
  EXPECT_THROW(dynamics::Simulator{bad}, InputError);
}

// Drives and springs enter the step implicitly: a 10 mm steel cube (I = 1.3e-9 kg m²) held by
// a torsional drive of 1e-4 N m s/rad and 1e-3 N m/rad (h c / I = 76, h² k / I = 0.8 at 1 ms)
// and tied to a second cube by a spring of 1e4 N/m (h² k / m = 1.3): explicit terms would
// grow ×75 per step. Both come to rest at the drive's target, without gravity or contact.
TEST(DiscreteSimulation, StiffDriveAndSpringAreStable) {
  Scenario s;
  const double a = 0.01;
  s.bodies = {freeBody("held", geometry::Box{Vector3d::Constant(a)}, at({0.0, 0.0, 0.0})),
              freeBody("tied", geometry::Box{Vector3d::Constant(a)}, at({0.03, 0.0, 0.0}))};
  s.bodies[0].w_WB0 = Vector3d(3.0, -2.0, 10.0);
  s.bodies[1].v_WBcm0 = Vector3d(0.1, 0.0, 0.0);  // along the spring
  dynamics::ExternalLoad drive;
  drive.name = "drive";
  drive.kind = dynamics::LoadKind::kDrive;
  drive.drive.stiffness = Vector3d::Constant(1e3);
  drive.drive.damping = Vector3d::Constant(10.0);
  drive.drive.torsional_stiffness = Vector3d::Constant(1e-3);
  drive.drive.torsional_damping = Vector3d::Constant(1e-4);
  s.loads.push_back(drive);
  dynamics::BodySpring spring;
  spring.name = "tie";
  spring.a = 0;
  spring.b = 1;
  spring.rest_length = 0.03;
  spring.stiffness = 1e4;
  spring.damping = 1.0;
  s.springs.push_back(spring);
  s.gravity_W.setZero();
  const auto out = run(discrete(s, 1e-3, 2.0, 10.0));
  for (const auto& body : out.back().bodies) {
    EXPECT_LT(body.w_WB.norm(), 1e-6);    // from 10 rad/s; decay e^{-k t / c} = e^{-20} at 2 s
    EXPECT_LT(body.v_WBcm.norm(), 1e-6);  // from 0.1 m/s
  }
  EXPECT_LT(out.back().bodies[0].p_WBcm.norm(), 1e-6);  // at the drive's target
  EXPECT_NEAR((out.back().bodies[1].p_WBcm - out.back().bodies[0].p_WBcm).norm(), 0.03, 1e-6);
}

}  // namespace
}  // namespace vcontact::test
