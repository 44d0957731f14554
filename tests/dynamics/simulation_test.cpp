// Whole-simulation physics checks against closed forms (MODEL.md §3, §5): restitution, energy,
// Coulomb and spin deceleration, bristle friction on a slope, invariance under rigid motion.
// Each runs with both integrators (Dormand–Prince and BDF) at the same tolerances.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "dynamics_fixtures.hpp"
#include "geometry/tessellate.hpp"
#include "support/test_support.hpp"

namespace vcontact::test {
namespace {

using dynamics::Integrator;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::Snapshot;

constexpr double kG = 9.81;  // m/s²

// Tight integration: the checks below compare with closed forms to ~1e-6, and the local
// error per step of 1e-11 (absolute, in m, m/s, rad) keeps the global error well below that.
void tight(Scenario& s, double duration, double output_rate, Integrator integrator) {
  s.settings.integrator = integrator;
  s.settings.duration = duration;
  s.settings.output_rate_hz = output_rate;
  s.settings.abs_tol = 1e-11;
  s.settings.rel_tol = 1e-10;
  s.settings.max_step = 1e-4;
}

// A softer plate for the friction tests: the static penetrations become ~µm instead of
// ~0.3 nm, so that the round-off-level rocking of a flat face does not lift its edges.
// The decelerations checked do not depend on kv.
constexpr double kSoftKv = 1e9;  // N/m³

class Simulation : public ::testing::TestWithParam<Integrator> {};

std::string integratorName(const ::testing::TestParamInfo<Integrator>& info) {
  return info.param == Integrator::kBdf ? "bdf" : "dopri5";
}

Model normalModel(double a) {
  Model m = Model::withEffects({"stiffness", "damping"});
  m.setParameter("damping.a", a);
  return m;
}

struct ImpactCase {
  const char* name;
  geometry::Shape shape;
  double half_height;  // m, from the body origin to its lowest point
};

std::vector<ImpactCase> impactCases() {
  return {{"sphere R=10mm", geometry::Sphere{0.01}, 0.01},
          {"punch R=5mm", geometry::Cylinder{0.005, 0.01}, 0.005}};
}

// Rebound speed of a body that hits the plate at v_in, without gravity.
double reboundSpeed(const ImpactCase& c, const Model& model, double v_in, Integrator integrator) {
  constexpr double kGap = 1e-6;  // m, start just above the plate
  dynamics::RigidBody body = freeBody("body", c.shape, at({0.0, 0.0, c.half_height + kGap}));
  body.v_WBcm0 = Eigen::Vector3d(0.0, 0.0, -v_in);
  Scenario s = onPlate(body, model);
  s.gravity_W.setZero();
  tight(s, 2e-3, 1e3, integrator);
  const auto out = run(s);
  EXPECT_EQ(out.back().pairs[0].cv.volume, 0.0) << c.name << ": still in contact";
  return out.back().bodies[1].v_WBcm.z();
}

// MODEL.md §5: α (1 + e) = ln((1 + α)/(1 − α e)), α = a v_in, for any shape and any kv.
TEST_P(Simulation, RestitutionRelation) {
  constexpr double kVin = 0.3;  // m/s
  for (const auto& c : impactCases()) {
    for (double alpha : {0.1, 0.6, 2.0}) {
      const double e = reboundSpeed(c, normalModel(alpha / kVin), kVin, GetParam()) / kVin;
      // The exact relation holds to the integration error (~1e-8 at these tolerances).
      EXPECT_NEAR(e, exactRestitution(alpha), 1e-6) << c.name << " alpha " << alpha;
    }
  }
}

// a = 0: the contact is conservative and the body leaves at the speed it came.
TEST_P(Simulation, ElasticReboundKeepsTheSpeed) {
  for (const auto& c : impactCases()) {
    const double v_out = reboundSpeed(c, normalModel(0.0), 0.3, GetParam());
    EXPECT_NEAR(v_out, 0.3, 0.3 * 1e-7) << c.name;  // integrator tolerance, ~1e-8 relative
  }
}

// Stiffness only: kinetic + potential + elastic energy stays constant through bounces.
TEST_P(Simulation, EnergyConservedWithoutDissipation) {
  constexpr double R = 0.01, kDrop = 1e-3;  // m
  const Model model = Model::withEffects({"stiffness"});
  const double kv = model.parameter("stiffness.kv");
  Scenario s = onPlate(freeBody("ball", geometry::Sphere{R}, at({0, 0, R + kDrop})), model);
  tight(s, 0.05, 2e4, GetParam());
  const double m = s.bodies[1].mass;
  const auto energy = [&](const Snapshot& snap) {
    const auto& b = snap.bodies[1];
    const double z = b.p_WBcm.z();
    return 0.5 * m * b.v_WBcm.squaredNorm() + m * kG * z + sphereElasticEnergy(kv, R, R - z);
  };
  const auto out = run(s);
  const double E0 = energy(out.front());
  double worst = 0.0;
  int in_contact = 0;
  for (const auto& snap : out) {
    worst = std::max(worst, std::abs(energy(snap) - E0) / E0);
    in_contact += snap.pairs[0].cv.volume > 0.0;
  }
  EXPECT_GT(in_contact, 0);  // the check covered contact phases
  EXPECT_LT(worst, 1e-7);    // local error 1e-10 relative per step over ~1e4 steps
}

// Box sliding on the plate: Coulomb friction decelerates it at μ g. The friction torque about
// the centre of mass tilts the box until the trailing edge's penetration falls by 3μ of the
// static one, whatever kv; μ = 0.1 keeps the whole face in contact through the rocking.
TEST_P(Simulation, CoulombBlockDecelerates) {
  constexpr double kMu = 0.1, kSide = 0.02, kV0 = 0.1;
  Model model = Model::withEffects({"stiffness", "damping", "coulomb"});
  model.setParameter("stiffness.kv", kSoftKv);
  model.setParameter("damping.a", 10.0);
  model.setParameter("coulomb.mu", kMu);
  dynamics::RigidBody box = freeBody("box", geometry::Box{Eigen::Vector3d::Constant(kSide)},
                                     Eigen::Isometry3d::Identity());
  // Start at the static penetration d = m g / (kv A), so the box does not bounce.
  const double d = box.mass * kG / (model.parameter("stiffness.kv") * kSide * kSide);
  box.X_WB0 = at({0.0, 0.0, kSide / 2 - d});
  box.v_WBcm0 = Eigen::Vector3d(kV0, 0.0, 0.0);
  Scenario s = onPlate(box, model);
  tight(s, 0.025, 1e3, GetParam());
  const auto out = run(s);
  const double v1 = out[5].bodies[1].v_WBcm.x(), v2 = out[25].bodies[1].v_WBcm.x();
  const double decel = (v1 - v2) / (out[25].t - out[5].t);
  // The rocking started by the friction torque averages out to well below 1e-4 of μ g.
  EXPECT_NEAR(decel, kMu * kG, 1e-4 * kMu * kG);
}

// Punch spinning face down: I_zz ω̇ = −μ r_gyr m g (MODEL.md §3 spin, Coulomb form). The punch
// is a 64-sided prism clipped exactly (method halfspace): the analytic cylinder backend slows
// to milliseconds per query at the round-off tilts a spinning body picks up. r_gyr is the
// prism's own, read from the contact volume.
TEST_P(Simulation, SpinningPunchDecelerates) {
  constexpr double kMu = 0.3, R = 0.01, L = 0.02, kW0 = 20.0;
  Model model = Model::withEffects({"stiffness", "damping", "coulomb", "spin"});
  model.setParameter("stiffness.kv", kSoftKv);
  model.setParameter("damping.a", 10.0);
  model.setParameter("coulomb.mu", kMu);
  const auto prism =
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateCylinder(R, L, 64));
  dynamics::RigidBody punch =
      freeBody("punch", geometry::Mesh{prism, "punch"}, Eigen::Isometry3d::Identity());
  const double face = 0.5 * 64 * R * R * std::sin(2.0 * std::numbers::pi / 64);  // m²
  const double d = punch.mass * kG / (model.parameter("stiffness.kv") * face);
  punch.X_WB0 = at({0.0, 0.0, L / 2 - d});
  punch.w_WB0 = Eigen::Vector3d(0.0, 0.0, kW0);
  Scenario s = onPlate(punch, model);
  s.pairs[0].method = volume::Method::kHalfspace;
  tight(s, 0.03, 1e3, GetParam());
  const auto out = run(s);
  const double w1 = out[5].bodies[1].w_WB.z(), w2 = out[30].bodies[1].w_WB.z();
  const double decel = (w1 - w2) / (out[30].t - out[5].t);
  const double r_gyr = out[5].pairs[0].cv.r_gyr;
  EXPECT_NEAR(r_gyr, R / std::sqrt(2.0), 2e-3 * R);  // 64-gon: r_gyr² = R²/2 (1 − 6e-4)
  const double expected = kMu * r_gyr * punch.mass * kG / punch.I_BBcm_B(2, 2);
  EXPECT_NEAR(decel, expected, 1e-4 * expected);  // as for the block
}

// A box released on a plate tilted by θ, with bristle friction (μ_C = 0.1, μ_S = 0.2: small,
// for the reason given at the Coulomb block).
std::vector<Snapshot> boxOnSlope(double tan_theta, double duration, Integrator integrator) {
  constexpr double kSide = 0.02;
  Model model = Model::withEffects({"stiffness", "damping", "coulomb", "stribeck", "bristle"});
  model.setParameter("stiffness.kv", kSoftKv);
  model.setParameter("damping.a", 10.0);
  model.setParameter("coulomb.mu", 0.1);
  model.setParameter("stribeck.mu_s", 0.2);
  // v_s = 10 mm/s: released on the slope, the overdamped bristle deflects at up to
  // tan θ/σ1 ≈ 0.5 mm/s, which must count as stuck for the static limit to be tested.
  model.setParameter("coulomb.v_s", 0.01);
  Eigen::Isometry3d X_WP = Eigen::Isometry3d::Identity();
  X_WP.linear() =
      Eigen::AngleAxisd(std::atan(tan_theta), Eigen::Vector3d::UnitX()).toRotationMatrix();
  dynamics::RigidBody box = freeBody("box", geometry::Box{Eigen::Vector3d::Constant(kSide)},
                                     Eigen::Isometry3d::Identity());
  const double cos_theta = 1.0 / std::sqrt(1.0 + tan_theta * tan_theta);
  const double d = box.mass * kG * cos_theta / (model.parameter("stiffness.kv") * kSide * kSide);
  box.X_WB0 = X_WP * at({0.0, 0.0, kSide / 2 - d});
  Scenario s = onPlate(box, model, X_WP);
  tight(s, duration, 100.0, integrator);
  s.settings.abs_tol = 1e-10;  // the bristle's stuck phase needs no tighter
  return run(s);
}

TEST_P(Simulation, BristleHoldsBelowTheStaticLimit) {
  constexpr double kTan = 0.15;  // μ_C < tan θ < μ_S: held by static friction only
  const auto out = boxOnSlope(kTan, 0.6, GetParam());
  const auto& start = out.front().bodies[1];
  const auto& end = out.back().bodies[1];
  // Presliding: the bristle deflects to z = tan θ / σ0 (33 µm for σ0 = 4500 1/m) and holds.
  EXPECT_LT((end.p_WBcm - start.p_WBcm).norm(), 1.5 * kTan / 4500.0);
  // At rest: the slowest bristle mode decays as exp(−σ0 t/σ1), 1e-4 of the ~1 mm/s peak.
  EXPECT_LT(end.v_WBcm.norm(), 1e-6);
}

TEST_P(Simulation, BristleSlidesAboveTheStaticLimit) {
  constexpr double kTan = 0.3;  // > μ_S = 0.2
  const auto out = boxOnSlope(kTan, 0.2, GetParam());
  const double theta = std::atan(kTan);
  const double expected = kG * (std::sin(theta) - 0.1 * std::cos(theta));
  // Sliding (v ≫ v_s, s = 0): σ0 z + σ1 ż = μ_C exactly, so a = g (sin θ − μ_C cos θ).
  const double a =
      (out[20].bodies[1].v_WBcm.norm() - out[10].bodies[1].v_WBcm.norm()) / (out[20].t - out[10].t);
  EXPECT_NEAR(a, expected, 1e-4 * expected);  // rocking averages out, as for the block
}

// Dwell (MODEL.md §3): at rest (s = 1) the stick state grows as s_dw = 1 − exp(−T/τ_dw), so
// the friction limit after a stop of length T is μ_S − (μ_S − μ_C) exp(−T/τ_dw).
TEST_P(Simulation, DwellStrengthensStaticFriction) {
  constexpr double kSide = 0.02, kTau = 0.05, kMuC = 0.2, kMuS = 0.35;  // τ_dw in s
  Model model =
      Model::withEffects({"stiffness", "damping", "coulomb", "stribeck", "bristle", "dwell"});
  model.setParameter("stiffness.kv", kSoftKv);
  model.setParameter("damping.a", 10.0);
  model.setParameter("coulomb.mu", kMuC);
  model.setParameter("stribeck.mu_s", kMuS);
  model.setParameter("dwell.tau_dw", kTau);
  dynamics::RigidBody box = freeBody("box", geometry::Box{Eigen::Vector3d::Constant(kSide)},
                                     Eigen::Isometry3d::Identity());
  const double d = box.mass * kG / (kSoftKv * kSide * kSide);
  box.X_WB0 = at({0.0, 0.0, kSide / 2 - d});
  Scenario s = onPlate(box, model);
  tight(s, 2.0 * kTau, 100.0, GetParam());
  // BDF2 has no local extrapolation: its global error is the sum of its local errors, ~2e-8 on
  // s_dw over this run at these tolerances. 100x tighter ones keep it below the
  // 1e-8 checked (the error falls as tol^(2/3) with order 2).
  if (GetParam() == Integrator::kBdf) {
    s.settings.abs_tol /= 100.0;
    s.settings.rel_tol /= 100.0;
  }
  const int s_dw = model.stateLayout().offsetOf("dwell");
  const auto out = run(s);
  for (const Snapshot& snap : out) {
    const double T = snap.t;
    // s = exp(−v²/v_s²) = 1 to ~1e-12 for the box at rest (|v| < 1e-9 m/s).
    EXPECT_NEAR(snap.pairs[0].state[s_dw], 1.0 - std::exp(-T / kTau), 1e-8) << T;
    EXPECT_NEAR(snap.pairs[0].result.mu_max, kMuS - (kMuS - kMuC) * std::exp(-T / kTau), 1e-8) << T;
  }
}

// Prescribed motion: the reported velocities are the time derivatives of the pose.
TEST(SimulationKinematics, PrescribedKinematicsAreConsistent) {
  dynamics::RigidBody b = plate(randomPose(5));
  b.motion = dynamics::BodyMotion::kPrescribed;
  b.p_BBcm = Eigen::Vector3d(0.01, -0.02, 0.03);
  b.prescribed = {Eigen::Vector3d(0.1, 0.2, -0.3), Eigen::Vector3d(1.0, -2.0, 0.5),
                  Eigen::Vector3d(0.001, 0.0, 0.002), 7.0, nullptr};  // no trajectory table
  constexpr double t = 0.123, h = 1e-6;  // s; central differences, error O(h²) ~ 1e-11
  const auto k = dynamics::scheduledKinematics(b, t);
  const auto k1 = dynamics::scheduledKinematics(b, t - h);
  const auto k2 = dynamics::scheduledKinematics(b, t + h);
  // 1e-8: the O(h²) truncation (~1e-11) plus the round-off of the quotient, ε·|p|/h ~ 1e-10.
  EXPECT_LT(((k2.p_WBcm - k1.p_WBcm) / (2 * h) - k.v_WBcm).norm(), 1e-8);
  const Eigen::Matrix3d R_dot = (k2.X_WB.linear() - k1.X_WB.linear()) / (2 * h);
  const Eigen::Matrix3d W = R_dot * k.X_WB.linear().transpose();  // [ω]×
  EXPECT_LT((Eigen::Vector3d(W(2, 1), W(0, 2), W(1, 0)) - k.w_WB).norm(), 1e-8);
}

// A plate lifted at 10 mm/s carries a ball resting on it.
TEST_P(Simulation, PrescribedPlateCarriesTheBall) {
  constexpr double R = 0.01, kLift = 0.01;  // m, m/s
  Model model = Model::withEffects({"stiffness", "damping"});
  model.setParameter("damping.a", 30.0);
  Scenario s = onPlate(freeBody("ball", geometry::Sphere{R}, at({0, 0, R - 1.42e-6})), model);
  s.bodies[0].motion = dynamics::BodyMotion::kPrescribed;
  s.bodies[0].prescribed.v_W = Eigen::Vector3d(0.0, 0.0, kLift);
  tight(s, 0.2, 10.0, GetParam());
  const auto out = run(s);
  // After the start-up transient the ball rides at the plate's speed, at its static depth.
  EXPECT_NEAR(out.back().bodies[1].v_WBcm.z(), kLift, 1e-6);
  EXPECT_NEAR(out.back().bodies[1].p_WBcm.z(), kLift * 0.2 + R - 1.42e-6, 0.1e-6);
}

// The same scenario seen from a moved and turned world frame gives the moved trajectory.
TEST_P(Simulation, InvariantUnderRigidMotion) {
  Model model = Model::withEffects({"stiffness", "damping", "coulomb", "stribeck", "bristle",
                                    "spin", "viscous", "rolling_resistance"});
  model.setParameter("damping.a", 10.0);
  model.setParameter("stribeck.mu_s", 0.3);
  model.setParameter("viscous.sigma2", 0.5);
  const auto scenarioIn = [&](const Eigen::Isometry3d& X) {
    // Start at the static penetration (m g = kv π R d², d ≈ 1.42 µm): no bounce.
    dynamics::RigidBody ball =
        freeBody("ball", geometry::Sphere{0.01}, X * at({0, 0, 0.01 - 1.42e-6}));
    ball.v_WBcm0 = X.linear() * Eigen::Vector3d(0.05, 0.02, 0.0);
    ball.w_WB0 = X.linear() * Eigen::Vector3d(1.0, -3.0, 8.0);
    Scenario s = onPlate(ball, model, X);
    s.gravity_W = X.linear() * Eigen::Vector3d(0.0, 0.0, -kG);
    tight(s, 0.02, 100.0, GetParam());
    return s;
  };
  const Eigen::Isometry3d X = randomPose(11);
  const auto a = run(scenarioIn(Eigen::Isometry3d::Identity()));
  const auto b = run(scenarioIn(X));
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(a.back().pairs[0].cv.volume, 0.0);  // it rolled and slid in contact
  const auto& ka = a.back().bodies[1];
  const auto& kb = b.back().bodies[1];
  // Step sequences differ (the error norm is not rotation invariant): differences are of the
  // order of the accumulated local error, ~1e-9 on positions and velocities of 1e-2.
  EXPECT_LT((X * ka.p_WBcm - kb.p_WBcm).norm(), 1e-9);
  EXPECT_LT((X.linear() * ka.v_WBcm - kb.v_WBcm).norm(), 1e-7);
  EXPECT_LT((X.linear() * ka.w_WB - kb.w_WB).norm(), 1e-5);
}

// --- Broad phase (PairContacts::screen) ---------------------------------------------------

constexpr double kBallR = 0.005;  // m

// A steel ball as a mesh (32 × 16 facets, symmetric under x → −x, y → −y and z → −z).
dynamics::RigidBody meshBall(const std::string& name, const Eigen::Vector3d& p) {
  static const auto mesh =
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(kBallR, 32, 16));
  return freeBody(name, geometry::Mesh{mesh, "ball"}, at(p));
}

// Two balls bouncing on a plate 0.1 m apart. A pair declared between them is screened out by
// the broad phase at every right-hand side: it is never queried (two queries per right-hand
// side, not three) and the run is the run without it, to the last bit (Dormand–Prince: the
// pair's zero states add nothing to the error norm, so the steps are the same).
TEST(SimulationBroadPhase, PairApartIsNeverQueriedAndChangesNothing) {
  const auto scenario = [](bool ballBallPair) {
    Scenario s;
    s.bodies = {plate(), meshBall("left", {0.0, 0.0, kBallR + 1e-4}),
                meshBall("right", {0.1, 0.0, kBallR + 2e-4})};
    s.pairs.push_back({"left-plate", 1, 0, normalModel(5.0), std::nullopt});
    s.pairs.push_back({"right-plate", 2, 0, normalModel(5.0), std::nullopt});
    if (ballBallPair) s.pairs.push_back({"left-right", 1, 2, normalModel(5.0), std::nullopt});
    tight(s, 0.02, 1e3, Integrator::kDopri5);
    return s;
  };
  dynamics::SimulationSummary withSummary, withoutSummary;
  const auto with = run(scenario(true), &withSummary);
  const auto without = run(scenario(false), &withoutSummary);
  EXPECT_EQ(withSummary.contact_evaluations, 2 * withSummary.rhs_evaluations);
  EXPECT_EQ(withSummary.rhs_evaluations, withoutSummary.rhs_evaluations);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t k = 0; k < with.size(); ++k) {
    for (std::size_t b = 1; b < 3; ++b) {
      EXPECT_EQ(with[k].bodies[b].p_WBcm, without[k].bodies[b].p_WBcm) << k << " " << b;
      EXPECT_EQ(with[k].bodies[b].v_WBcm, without[k].bodies[b].v_WBcm) << k << " " << b;
    }
    EXPECT_EQ(with[k].pairs[2].cv.volume, 0.0);
  }
  // Both balls did bounce: the runs compared are not free falls.
  for (std::size_t b = 1; b < 3; ++b) {
    EXPECT_TRUE(std::any_of(with.begin(), with.end(), [b](const Snapshot& o) {
      return o.bodies[b].v_WBcm.z() > 0.0;
    })) << b;
  }
}

// Head-on collision of two equal balls in free space, elastic contact (stiffness only): the
// pair is screened while the balls are 1 mm apart and queried once their boxes meet, and the
// velocities are exchanged (equal masses; the mirror-symmetric facets keep the normal along
// x). Momentum is conserved to rounding: the pair's forces are equal and opposite, and the
// integrator keeps linear invariants.
TEST(SimulationBroadPhase, PairIsQueriedOnceTheBoxesMeet) {
  constexpr double v = 0.1;  // m/s
  Scenario s;
  s.bodies = {meshBall("moving", {0.0, 0.0, 0.0}), meshBall("resting", {2 * kBallR + 1e-3, 0, 0})};
  s.bodies[0].v_WBcm0 = Eigen::Vector3d(v, 0.0, 0.0);
  Model elastic = Model::withEffects({"stiffness"});
  elastic.setParameter("stiffness.kv", 1e11);
  s.pairs.push_back({"moving-resting", 0, 1, elastic, std::nullopt});
  s.gravity_W.setZero();
  tight(s, 0.02, 1e3, Integrator::kDopri5);
  dynamics::SimulationSummary summary;
  const auto out = run(s, &summary);
  EXPECT_EQ(out.back().pairs[0].cv.volume, 0.0) << "still in contact";
  const Eigen::Vector3d vA = out.back().bodies[0].v_WBcm, vB = out.back().bodies[1].v_WBcm;
  std::printf(
      "[measured] after the collision: moving %.3e m/s, resting %.9f m/s; %ld of %ld "
      "right-hand sides queried\n",
      vA.x(), vB.x(), summary.contact_evaluations, summary.rhs_evaluations);
  // An elastic impact of equal masses swaps the velocities; 1e-6 v bounds the integration
  // error over the impact at these tight tolerances (the line above prints the actual one).
  EXPECT_NEAR(vA.x(), 0.0, 1e-6 * v);
  EXPECT_NEAR(vB.x(), v, 1e-6 * v);
  // Momentum: the pair's forces are equal and opposite, so only round-off changes the sum.
  EXPECT_LT((vA + vB - Eigen::Vector3d(v, 0, 0)).norm(), 1e-12 * v);
  EXPECT_GT(summary.contact_evaluations, 0);
  EXPECT_LT(summary.contact_evaluations, summary.rhs_evaluations / 2);
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, Simulation,
                         ::testing::Values(Integrator::kDopri5, Integrator::kBdf), integratorName);

}  // namespace
}  // namespace vcontact::test
