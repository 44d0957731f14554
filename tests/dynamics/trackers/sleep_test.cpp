// Sleeping islands of the discrete stepper (dynamics/trackers/sleep.hpp, docs/SLEEP.md): a resting
// box falls asleep where the awake run keeps it, a dropped ball wakes it, a sliding block and a
// body under a load never sleep, and the hooks change nothing while nobody sleeps.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "dynamics/simulator.hpp"
#include "dynamics_fixtures.hpp"
#include "geometry/tessellate.hpp"

namespace vcontact::test {
namespace {

using dynamics::Integrator;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::SimulationSummary;
using dynamics::Snapshot;
using Eigen::Vector3d;

constexpr double kG = 9.81;
constexpr double kSide = 0.02;  // m, cube edge
constexpr double kH = 1e-3;     // s, the step

// The rigs' steel model softened to kv = 1e9 N/m³ (as discrete_simulation_test.cpp): the
// static sink of the 20 mm cube, 1.55 µm, is resolved and the cube rests without hopping.
Model steel(double mu = 0.2) {
  Model m = Model::withEffects(
      {"stiffness", "damping", "rolling_resistance", "coulomb", "stribeck", "bristle", "spin"});
  m.setParameter("stiffness.kv", 1e9);
  m.setParameter("damping.a", 20.0);
  m.setParameter("coulomb.mu", mu);
  m.setParameter("stribeck.mu_s", mu);
  return m;
}

double sinkOf(double mass, double g_n) { return mass * g_n / (1e9 * kSide * kSide); }

// A mesh cube (two cubes, or a cube and a sphere, meet only as meshes in this build).
dynamics::RigidBody cube(const std::string& name, const Vector3d& p) {
  auto mesh = std::make_shared<const geometry::TriangleMesh>(
      geometry::tessellateBox(Vector3d::Constant(kSide)));
  return freeBody(name, geometry::Mesh{mesh, name}, at(p));
}

// A cube resting at its static sink on the plate, the discrete stepper at 1 ms.
Scenario restingBox(double duration, bool sleep) {
  const dynamics::RigidBody probe = cube("box", Vector3d::Zero());
  Scenario s = onPlate(cube("box", {0.0, 0.0, kSide / 2 - sinkOf(probe.mass, kG)}), steel());
  s.settings.integrator = Integrator::kDiscrete;
  s.settings.impacts = dynamics::ImpactMode::kImplicit;
  s.settings.step = kH;
  s.settings.duration = duration;
  s.settings.output_rate_hz = 100.0;
  s.settings.sleep.enabled = sleep;
  return s;
}

// The resting box and a steel ball of 5 mm radius (a 224-triangle mesh) released `height` above its
// top face, off its centre by 5 mm so that the impact turns the box too.
Scenario ballOnBox(double height, bool sleep) {
  Scenario s = restingBox(0.4, sleep);
  constexpr double R = 0.005;
  auto ball = std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(R, 16, 8));
  s.bodies.push_back(
      freeBody("ball", geometry::Mesh{ball, "ball"}, at({0.005, 0.0, kSide + R + height})));
  s.pairs.push_back({"ball-plate", 2, 0, steel(), std::nullopt});
  s.pairs.push_back({"ball-box", 2, 1, steel(), std::nullopt});
  return s;
}

const dynamics::SleepEvent* firstEvent(const SimulationSummary& s, const std::string& body,
                                       bool asleep) {
  for (const dynamics::SleepEvent& e : s.sleep_events) {
    if (e.body == body && e.asleep == asleep) return &e;
  }
  return nullptr;
}

// Resting from t = 0, the box is quiet at once: it falls asleep after the quiet time T (50
// steps; a few more for the rounding of the summed steps), then stays put with zero velocity
// where the awake run keeps it (within 1 µm: the awake run's own drift at rest is below that,
// DiscreteSimulation.BoxRestsAtTheStaticSinkForTenSeconds), and its queries stop.
TEST(Sleep, RestingBoxFallsAsleepWhereTheAwakeRunKeepsIt) {
  SimulationSummary asleep, awake;
  const auto slept = run(restingBox(1.0, true), &asleep);
  const auto woke = run(restingBox(1.0, false), &awake);
  const double T = dynamics::SleepSettings{}.time;
  const dynamics::SleepEvent* e = firstEvent(asleep, "box", true);
  ASSERT_NE(e, nullptr);
  EXPECT_GE(e->t, T - 1e-12);
  EXPECT_LE(e->t, T + 3 * kH);
  EXPECT_EQ(asleep.sleep_events.size(), 1u);  // and never woke
  EXPECT_TRUE(awake.sleep_events.empty());
  ASSERT_EQ(slept.size(), woke.size());
  for (std::size_t i = 0; i < slept.size(); ++i) {
    EXPECT_LT((slept[i].bodies[1].p_WBcm - woke[i].bodies[1].p_WBcm).norm(), 1e-6) << slept[i].t;
    if (slept[i].t > e->t) {
      EXPECT_EQ(slept[i].bodies[1].v_WBcm.norm(), 0.0) << slept[i].t;
    }
  }
  // the pair with the plate is queried until the box sleeps (about T / h steps), then never
  EXPECT_LT(asleep.contact_evaluations, 0.1 * awake.contact_evaluations);
  EXPECT_GT(asleep.sleep_skipped_queries, 900);  // of the 1,000 steps, 950 asleep
  // the output still carries the contact (the kept one): the plate holds the box's weight
  // (to 1e-3: the damping of the last awake step's sub-µm/s motion is gone, nothing else)
  const double weight = restingBox(1.0, true).bodies[1].mass * kG;
  EXPECT_NEAR(slept.back().pairs[0].result.f_n, weight, 1e-3 * weight);
}

// The 20 mm steel cube on a plate at the steel stiffness kv = 5.17e12 N/m³, dropped from
// 0.2 mm: its static sink m g / (kv A), 0.3 nm, is far below a step's fall g h² (9.8 µm at
// 1 ms), so the plain step hops about the rest (docs/DISCRETE.md §5), at up to g h.
Scenario stiffDrop(dynamics::ImpactMode impacts) {
  Model m = steel();
  m.setParameter("stiffness.kv", 5.17e12);
  Scenario s = onPlate(cube("box", {0.0, 0.0, kSide / 2 + 2e-4}), m);
  s.settings.integrator = Integrator::kDiscrete;
  s.settings.impacts = impacts;
  s.settings.step = kH;
  s.settings.duration = 0.5;
  s.settings.output_rate_hz = 100.0;
  return s;
}

// With the default impacts (resolved), the steps whose linearised force missed the queried
// one (the cube fell into the plate from apart) are integrated by Dormand–Prince: the cube
// rests at its static sink m g / (kv A) with the contact holding its weight, then sleeps.
TEST(Sleep, DefaultImpactsRestAStiffPartOnItsWeight) {
  SimulationSummary summary;
  const Scenario s = stiffDrop(dynamics::ImpactMode::kResolve);
  const auto out = run(s, &summary);
  ASSERT_NE(firstEvent(summary, "box", true), nullptr);
  const double weight = s.bodies[1].mass * kG;
  const Snapshot& last = out.back();
  ASSERT_TRUE(last.pairs[0].cv.inContact());
  // 1e-3: the rest the Dormand–Prince intervals reach is within their tolerances' force
  // error (rel 1e-6 of states of 1e-10 m below 1e-3 of the 0.3 nm sink); the last awake
  // step's damping share is gone (as in RestingBoxFallsAsleepWhereTheAwakeRunKeepsIt)
  EXPECT_NEAR(last.pairs[0].result.f_n, weight, 1e-3 * weight);
  const double sink = weight / (5.17e12 * kSide * kSide);  // flat face: V = A d
  EXPECT_NEAR(last.pairs[0].cv.volume / last.pairs[0].cv.area, sink, 1e-3 * sink);
  std::printf("resolved %ld steps; rest f_n %.9g N (weight %.9g), sink %.6g m (closed form %.6g)\n",
              summary.resolved_steps, last.pairs[0].result.f_n, weight,
              last.pairs[0].cv.volume / last.pairs[0].cv.area, sink);
}

// The stiff cube let go 2.5 µm above the plate falls into it within one step at g h / √2
// = 7 mm/s, below the impact threshold 2 g h: the plain step ends 2.5 µm deep, four
// thousand times its static sink, and misses its linearisation. The default takes the step
// again about its end (Newton iterations of the implicit step, one query each) instead of by
// Dormand–Prince: no step is resolved, and the cube rests at its sink with the contact holding
// its weight, which the plain step alone ("implicit") does not: it hops about the rest.
TEST(Sleep, MissedLinearisationIsIteratedToTheRest) {
  const auto drop = [](dynamics::ImpactMode impacts) {
    Scenario s = stiffDrop(impacts);
    s.bodies[1].X_WB0.translation().z() = kSide / 2 + 2.5e-6;
    s.settings.sleep.enabled = false;
    s.settings.duration = 0.1;
    return s;
  };
  SimulationSummary summary, plain;
  const Scenario s = drop(dynamics::ImpactMode::kAuto);
  const auto out = run(s, &summary);
  const auto hops = run(drop(dynamics::ImpactMode::kImplicit), &plain);
  EXPECT_EQ(summary.resolved_steps, 0);
  EXPECT_GT(summary.newton_iterations, 0);
  EXPECT_EQ(plain.newton_iterations, 0);
  const double weight = s.bodies[1].mass * kG;
  const double sink = weight / (5.17e12 * kSide * kSide);  // flat face: V = A d
  // after 20 ms every output rests on the weight; the plain step's outputs do not
  double worst = 0.0, worst_plain = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].t < 0.02) continue;
    worst = std::max(worst, std::abs(out[i].pairs[0].result.f_n - weight));
    worst_plain = std::max(worst_plain, std::abs(hops[i].pairs[0].result.f_n - weight));
  }
  // 1e-3: the damping share of the last step's settling, as in the test above
  EXPECT_LT(worst, 1e-3 * weight);
  EXPECT_GT(worst_plain, weight);
  const dynamics::PairOutput& last = out.back().pairs[0];
  EXPECT_NEAR(last.cv.volume / last.cv.area, sink, 1e-3 * sink);
  std::printf(
      "%ld Newton iterations, %ld queries; rest f_n %.9g N (weight %.9g); plain step "
      "off by up to %.3g N\n",
      summary.newton_iterations, summary.contact_evaluations, last.result.f_n, weight, worst_plain);
}

// A ball dropped 80 mm onto the box lands at 0.13 s, after the box fell asleep (0.05 s): the
// ball's box overlapping the cube's wakes the cube before the impact, and the impact moves it.
TEST(Sleep, RestingBoxWakesWhenADroppedBallHitsIt) {
  SimulationSummary summary;
  const auto out = run(ballOnBox(0.08, true), &summary);
  const dynamics::SleepEvent* slept = firstEvent(summary, "box", true);
  const dynamics::SleepEvent* woke = firstEvent(summary, "box", false);
  ASSERT_NE(slept, nullptr);
  ASSERT_NE(woke, nullptr);
  EXPECT_LT(slept->t, woke->t);
  double landing = -1.0, moved = 0.0;
  for (const Snapshot& s : out) {
    if (landing < 0.0 && s.pairs[2].cv.inContact()) landing = s.t;
    if (landing >= 0.0)
      moved = std::max(moved, s.bodies[1].v_WBcm.norm() + s.bodies[1].w_WB.norm());
  }
  ASSERT_GT(landing, 0.0) << "the ball never reached the box";
  EXPECT_LT(woke->t, landing);  // awake before the contact (the boxes overlap first)
  // The impact of 1.25 m/s of a ball of 4 g on a cube of 63 g: the cube is pushed into the
  // plate and tilted; 1 mm/s is a thousandth of the ball's momentum share, far above rest.
  EXPECT_GT(moved, 1e-3);
  std::printf("box asleep at %g s, woke at %g s, ball landed at %g s, box's speed bound %g\n",
              slept->t, woke->t, landing, moved);
}

// g (sin θ − μ cos θ) = 0.74 m/s² down a 10° incline at μ = 0.1: the block moves 0.9 mm in the
// quiet time's 50 ms, twenty times the quiet distance (1 mm/s × 50 ms); it never sleeps and
// slides at the same acceleration as without sleep.
TEST(Sleep, SlidingBlockNeverSleeps) {
  constexpr double kTheta = 10.0 * std::numbers::pi / 180.0;
  const dynamics::RigidBody probe = cube("box", Vector3d::Zero());
  Scenario s = restingBox(0.5, true);
  s.bodies[1] = cube("box", {0.0, 0.0, kSide / 2 - sinkOf(probe.mass, kG * std::cos(kTheta))});
  s.pairs[0].model = steel(0.1);
  s.gravity_W = kG * Vector3d(std::sin(kTheta), 0.0, -std::cos(kTheta));
  SimulationSummary summary;
  const auto out = run(s, &summary);
  EXPECT_TRUE(summary.sleep_events.empty());
  const double expected = kG * (std::sin(kTheta) - 0.1 * std::cos(kTheta));
  const double a =
      (out.back().bodies[1].v_WBcm.x() - out[25].bodies[1].v_WBcm.x()) / (out.back().t - out[25].t);
  EXPECT_NEAR(a, expected, 0.01 * expected);  // DiscreteSimulation's slide bound
}

// A load on the lower of two stacked resting cubes keeps both awake (one island); with a zero
// force the stack rests exactly as a sleeping one would, so only the rule holds it awake.
TEST(Sleep, BodyWithALoadAndItsIslandNeverSleep) {
  Scenario s = restingBox(0.3, true);
  const double m = s.bodies[1].mass;
  s.bodies.push_back(cube("top", {0.0, 0.0, 1.5 * kSide - sinkOf(2 * m, kG) - sinkOf(m, kG)}));
  s.pairs.push_back({"top-box", 2, 1, steel(), std::nullopt});
  dynamics::ExternalLoad load;
  load.name = "nothing";
  load.body = 1;
  s.loads.push_back(load);
  SimulationSummary summary;
  run(s, &summary);
  EXPECT_TRUE(summary.sleep_events.empty());
  // without the load, the same stack falls asleep whole
  s.loads.clear();
  run(s, &summary);
  EXPECT_NE(firstEvent(summary, "box", true), nullptr);
  EXPECT_NE(firstEvent(summary, "top", true), nullptr);
}

// Until a body falls asleep the hooks change nothing: a quiet time longer than the run gives
// the same numbers, to the bit, as "sleep": false (bundled outputs and `vcontact simulate`
// with "sleep": false are compared against the build before sleep in docs/SLEEP.md).
TEST(Sleep, NoSleepingBodyLeavesTheRunUnchanged) {
  Scenario never = ballOnBox(0.08, true);
  never.settings.sleep.time = 10.0;
  SimulationSummary a, b;
  const auto with = run(never, &a);
  const auto without = run(ballOnBox(0.08, false), &b);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    for (std::size_t j = 0; j < with[i].bodies.size(); ++j) {
      EXPECT_EQ(with[i].bodies[j].p_WBcm, without[i].bodies[j].p_WBcm);
      EXPECT_EQ(with[i].bodies[j].v_WBcm, without[i].bodies[j].v_WBcm);
      EXPECT_EQ(with[i].bodies[j].w_WB, without[i].bodies[j].w_WB);
    }
    for (std::size_t k = 0; k < with[i].pairs.size(); ++k) {
      EXPECT_EQ(with[i].pairs[k].result.wrench.f_W, without[i].pairs[k].result.wrench.f_W);
    }
  }
  EXPECT_EQ(a.contact_evaluations, b.contact_evaluations);
  EXPECT_TRUE(a.sleep_events.empty());
}

// dopri5 and bdf never sleep, whatever the settings say.
TEST(Sleep, ErrorControlledIntegratorsIgnoreIt) {
  for (const Integrator i : {Integrator::kDopri5, Integrator::kBdf}) {
    Scenario s = restingBox(0.1, true);
    s.settings.integrator = i;
    SimulationSummary summary;
    run(s, &summary);
    EXPECT_TRUE(summary.sleep_events.empty());
    EXPECT_EQ(summary.sleep_skipped_queries, 0);
  }
}

}  // namespace
}  // namespace vcontact::test
