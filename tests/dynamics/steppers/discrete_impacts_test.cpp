// Impacts in the discrete stepper (docs/DISCRETE.md §5–6): the steps that hold an impact
// shorter than h are integrated by Dormand–Prince ("impacts": "resolve"), so ball_drop's
// restitution at h = 1 ms and 0.5 ms is that of the exact relation (MODEL.md §5); and the
// impact records of the summary (dynamics/trackers/impact_tracker.hpp) balance the momentum. An
// impact is looked for per patch and resolved up to 250 steps per impact (issue 18's rest pose).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynamics/simulator.hpp"
#include "dynamics_fixtures.hpp"
#include "patch_meshes.hpp"

namespace vcontact::test {
namespace {

using dynamics::ImpactMode;
using dynamics::ImpactRecord;
using dynamics::Integrator;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::SimulationSummary;
using dynamics::Snapshot;
using Eigen::Vector3d;

constexpr double kG = 9.81;
constexpr double kR = 0.01;      // m, ball_drop's ball
constexpr double kDrop = 0.005;  // m, its fall to the plate

Model ballModel(double damping) {
  Model m = Model::withEffects(damping > 0.0 ? std::vector<std::string>{"stiffness", "damping"}
                                             : std::vector<std::string>{"stiffness"});
  m.setParameter("stiffness.kv", 5.17e12);  // ball_drop's steel on aluminium
  if (damping > 0.0) m.setParameter("damping.a", damping);
  return m;
}

Scenario ballDrop(const Model& m, Integrator integrator, double h, ImpactMode mode,
                  double duration) {
  Scenario s = onPlate(freeBody("ball", geometry::Sphere{kR}, at({0.0, 0.0, kR + kDrop})), m);
  s.settings.integrator = integrator;
  s.settings.step = h;
  s.settings.impacts = mode;
  s.settings.duration = duration;
  s.settings.output_rate_hz = 1.0 / h;
  return s;
}

double ballMass() { return kSteelDensity * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR; }

// The first impact: it hits at sqrt(2 g drop) = 0.313 m/s. The free flight of every
// integrator here is exact under gravity (a discrete step moves a body in flight by the
// trapezoid rule). A plain step's onset is placed inside its step by the mean depth V/A, half
// a sphere cap's depth, so the speed is carried too far by at most g h / 2 (1.6 % at 1 ms);
// it is 0.2 % for this drop, hence 0.5 %.
ImpactRecord firstImpact(const Scenario& s, std::vector<Snapshot>* out = nullptr) {
  SimulationSummary summary;
  const auto snapshots = run(s, &summary);
  if (out) *out = snapshots;
  EXPECT_FALSE(summary.impacts.empty());
  if (summary.impacts.empty()) return {};
  const ImpactRecord& r = summary.impacts.front();
  EXPECT_NEAR(r.approach_speed, std::sqrt(2.0 * kG * kDrop), 0.005 * std::sqrt(2.0 * kG * kDrop));
  return r;
}

// Restitution at h = 1 ms and 0.5 ms, resolved, against the exact relation: e = 1 for
// stiffness alone, e(a v_in) for a = 1 s/m (0.8268 at the run's own v_in, 0.313 m/s).
// The 2 % is the target; the
// resolved interval is Dormand–Prince at the scenario's tolerances, whose own run is within
// 0.2 % (docs/DISCRETE.md §5). The plain step at the same h does not rebound (e < 0.05).
TEST(DiscreteImpacts, ResolvedDropRestitutionIsTheExactRelation) {
  for (const double a : {0.0, 1.0}) {
    for (const double h : {1e-3, 5e-4}) {
      const ImpactRecord r =
          firstImpact(ballDrop(ballModel(a), Integrator::kDiscrete, h, ImpactMode::kResolve, 0.05));
      const double exact = a > 0.0 ? exactRestitution(a * r.approach_speed) : 1.0;
      EXPECT_EQ(r.outcome, "separated") << "a = " << a << ", h = " << h;
      EXPECT_NEAR(r.restitution, exact, 0.02 * exact) << "a = " << a << ", h = " << h;
      const ImpactRecord plain = firstImpact(
          ballDrop(ballModel(a), Integrator::kDiscrete, h, ImpactMode::kImplicit, 0.05));
      EXPECT_LT(plain.restitution, 0.05) << "a = " << a << ", h = " << h;
    }
  }
}

// Stiffness alone at h = 1 ms, resolved: out of contact the energy m g z + ½ m v² never
// exceeds the drop's. Slack: the resolved intervals' local errors (abs 1e-9 m, m/s per step)
// over their few hundred steps move the energy by m g · 1e-7 m ≈ 3e-8 J, 2e-5 of the drop's
// 1.6e-3 J; 1e-4 of it is the bound. The fixed steps in free flight lose energy (their
// positions lag by g h t / 2).
TEST(DiscreteImpacts, ResolvedElasticBounceNeverGainsEnergy) {
  std::vector<Snapshot> out;
  SimulationSummary summary;
  const Scenario s =
      ballDrop(ballModel(0.0), Integrator::kDiscrete, 1e-3, ImpactMode::kResolve, 0.2);
  out = run(s, &summary);
  const double m = ballMass();
  auto energy = [&](const Snapshot& x) {
    return m * kG * (x.bodies[1].p_WBcm.z() - kR) + 0.5 * m * x.bodies[1].v_WBcm.squaredNorm();
  };
  const double e0 = energy(out.front());
  for (const Snapshot& x : out) {
    if (!x.pairs[0].cv.inContact()) {
      EXPECT_LE(energy(x), e0 * (1.0 + 1e-4)) << "t = " << x.t;
    }
  }
  // it bounces on: every impact of the run separated, at restitution ≈ 1
  ASSERT_GE(summary.impacts.size(), 3u);
  for (const ImpactRecord& r : summary.impacts) {
    EXPECT_EQ(r.outcome, "separated");
    EXPECT_LE(r.restitution, 1.0 + 1e-3);
  }
  EXPECT_GT(summary.resolved_steps, 0);
  EXPECT_LT(summary.resolved_steps, summary.steps / 5);  // impacts are short: the cost stays low
}

// The impulse of an impact is the momentum it turned: m (v_in + v_out) plus the weight carried
// over its duration. Dormand–Prince: the trapezoid rule over its µs steps, within 0.5 % (the
// speeds are exact free flight; the rule's error over ~30 steps of a smooth pulse is far
// below). The plain discrete step: h times its implicit normal force, exact by construction
// (the solved velocities are those of that impulse) up to the speed at which the impact is
// counted as settled: below 2 g h (19.6 mm/s, 6 % of v_in) for 5 ms.
TEST(DiscreteImpacts, ImpulseBalancesTheMomentum) {
  const double m = ballMass();
  const ImpactRecord ref =
      firstImpact(ballDrop(ballModel(1.0), Integrator::kDopri5, 1e-3, ImpactMode::kResolve, 0.05));
  EXPECT_EQ(ref.outcome, "separated");
  // About 0.28 ms: the sphere's cap V = π R δ² (δ ≪ R) stores kv π R δ³/3, so the impact at
  // 0.313 m/s reaches δ = 31 µm, and a contact of this force law lasts about 2.9 δ / v_in.
  EXPECT_GT(ref.duration, 2e-4);
  EXPECT_LT(ref.duration, 4e-4);
  const ImpactRecord resolved = firstImpact(
      ballDrop(ballModel(1.0), Integrator::kDiscrete, 1e-3, ImpactMode::kResolve, 0.05));
  // the same impact, resolved inside a fixed step: duration and impulse as the reference's
  // within 3 % (the onset and separation are placed between accepted steps, above)
  EXPECT_NEAR(resolved.duration, ref.duration, 0.03 * ref.duration);
  EXPECT_NEAR(resolved.impulse, ref.impulse, 0.01 * ref.impulse);
  const double turned = m * (ref.approach_speed + ref.separation_speed) + m * kG * ref.duration;
  EXPECT_NEAR(ref.impulse, turned, 5e-3 * turned);
  const ImpactRecord plain = firstImpact(
      ballDrop(ballModel(1.0), Integrator::kDiscrete, 1e-3, ImpactMode::kImplicit, 0.05));
  EXPECT_EQ(plain.outcome, "settled");
  EXPECT_NEAR(plain.impulse, m * plain.approach_speed + m * kG * plain.duration,
              2.0 * m * kG * 1e-3);
}

// At h = 5 µs the ball's first impact (0.28 ms) lasts 56 steps. The plain step's restitution at
// that h is 0.749 against the exact 0.8268 (docs/DISCRETE.md §5, 9 % low); with impacts resolved
// up to 250 steps per impact it is Dormand–Prince's, within the 2 % of the test above. (Up to 25
// steps, as before, this impact stayed on the plain step at any h below 11 µs.)
TEST(DiscreteImpacts, ImpactOfFiftyStepsIsResolved) {
  const double h = 5e-6;
  const ImpactRecord r =
      firstImpact(ballDrop(ballModel(1.0), Integrator::kDiscrete, h, ImpactMode::kResolve, 0.04));
  const double exact = exactRestitution(r.approach_speed);
  EXPECT_EQ(r.outcome, "separated");
  EXPECT_NEAR(r.restitution, exact, 0.02 * exact);
  const ImpactRecord plain =
      firstImpact(ballDrop(ballModel(1.0), Integrator::kDiscrete, h, ImpactMode::kImplicit, 0.04));
  EXPECT_LT(plain.restitution, 0.95 * exact) << "the plain step would pass too: no test";
}

// "impacts": "auto" (the default) on ball_drop with a = 1 s/m over 0.6 s at the default
// restitution threshold, 0.05 m/s: the ball bounces at e ≈ 0.83–0.96 until its predicted
// rebound e v_in falls below the threshold; the plain step then dissipates that impact, and
// the ball settles. Every impact is labelled by what the stepper did: the resolved ones
// rebounding as the exact relation says (2 %, as above) and, where a fast region decided it (a
// predicted rebound above 0), predicted at or above the threshold; the plain ones below it.
// The prediction is e(a v) v at the step's start, carried by at most g h into the step for a
// touch inside it: within [e v_in, e (v_in + g h)] of the tracker's approach speed v_in. (At
// 0.02 m/s the impacts that slow at h = 1 ms are below the impact speed 2 g h of the
// simulator's impact check already; their hops are resolved by the linearisation check, with
// no fast region.)
TEST(DiscreteImpacts, AutoResolvesTheImpactsWorthResolving) {
  const double a = 1.0, h = 1e-3;
  const Scenario s = ballDrop(ballModel(a), Integrator::kDiscrete, h, ImpactMode::kAuto, 0.6);
  const double threshold = s.settings.restitution_threshold;
  EXPECT_EQ(threshold, 0.05);
  SimulationSummary summary;
  run(s, &summary);
  std::size_t resolved = 0, plain = 0;
  for (const ImpactRecord& r : summary.impacts) {
    const double exact = exactRestitution(a * r.approach_speed);
    if (r.resolution == "resolved") {
      EXPECT_EQ(plain, 0u) << "at " << r.start << ": the rebounds only fall";
      ++resolved;
      EXPECT_EQ(r.outcome, "separated") << "at " << r.start;
      EXPECT_NEAR(r.restitution, exact, 0.02 * exact) << "at " << r.start;
      EXPECT_GT(r.resolved_steps, 0);
      EXPECT_EQ(r.plain_steps, 0);
      if (r.predicted_rebound == 0.0) continue;
      EXPECT_GE(r.predicted_rebound, threshold) << "at " << r.start;
      EXPECT_GE(r.predicted_rebound, exact * r.approach_speed * (1.0 - 1e-3)) << "at " << r.start;
      EXPECT_LE(r.predicted_rebound, exact * (r.approach_speed + kG * h) * (1.0 + 1e-3))
          << "at " << r.start;
    } else {
      EXPECT_EQ(r.resolution, "plain") << "at " << r.start;
      ++plain;
      EXPECT_LT(r.predicted_rebound, threshold) << "at " << r.start;
      EXPECT_GT(r.plain_steps, 0);
      EXPECT_EQ(r.resolved_steps, 0);
    }
  }
  EXPECT_GE(resolved, 10u);
  EXPECT_GE(plain, 1u);
  ASSERT_FALSE(summary.impacts.empty());
  EXPECT_EQ(summary.impacts.back().outcome, "settled");
}

// The threshold decides: above the first rebound (0.26 m/s) the first impact is the plain
// step's (e < 0.05, as "implicit"); at 0 every fast impact is resolved, as "resolve".
TEST(DiscreteImpacts, RestitutionThresholdDecides) {
  Scenario high = ballDrop(ballModel(1.0), Integrator::kDiscrete, 1e-3, ImpactMode::kAuto, 0.05);
  high.settings.restitution_threshold = 0.3;
  const ImpactRecord skipped = firstImpact(high);
  EXPECT_EQ(skipped.resolution, "plain");
  EXPECT_LT(skipped.restitution, 0.05);
  Scenario zero = ballDrop(ballModel(1.0), Integrator::kDiscrete, 1e-3, ImpactMode::kAuto, 0.3);
  zero.settings.restitution_threshold = 0.0;
  SimulationSummary auto_zero, every;
  run(zero, &auto_zero);
  zero.settings.impacts = ImpactMode::kResolve;
  run(zero, &every);
  ASSERT_EQ(auto_zero.impacts.size(), every.impacts.size());
  for (std::size_t i = 0; i < every.impacts.size(); ++i) {
    EXPECT_EQ(auto_zero.impacts[i].resolution, every.impacts[i].resolution);
    EXPECT_EQ(auto_zero.impacts[i].restitution, every.impacts[i].restitution);
  }
  EXPECT_EQ(auto_zero.resolved_steps, every.resolved_steps);
}

// A part on two 10 mm steel feet 40 mm apart, released tilted by 2° about y on the outer edge of
// its left foot, sliding at 50 mm/s across and turning at 1 rad/s about z (kv = 1e11 N/m³, the
// model of cad_tray_drop). It pivots on that edge, and at 17.3 ms its right foot lands flat at
// about 0.2 m/s while the left foot is still in contact: a second patch of a pair in contact,
// whose aggregate centroid (near the left foot, where the volume is) barely moves along n.
// Returns the part's snapshot at 19 ms, after the impact, in flight.
dynamics::BodyKinematics afterSecondFoot(Integrator integrator, double h) {
  constexpr double kFoot = 0.01, kHalfSpan = 0.02, kTilt = 2.0 * std::numbers::pi / 180.0;
  const geometry::TriangleMesh foot = geometry::tessellateBox(Vector3d::Constant(kFoot));
  const auto part = meshShape(
      merged({{foot, placed({-kHalfSpan, 0, 0})}, {foot, placed({kHalfSpan, 0, 0})}}), "two feet");
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-kTilt, Vector3d::UnitY()).toRotationMatrix();
  const double z = (kHalfSpan + kFoot / 2) * std::sin(kTilt) + kFoot / 2 * std::cos(kTilt);
  dynamics::RigidBody body = freeBody("part", part, placed({0, 0, z}, R));
  body.v_WBcm0 = Vector3d(0, 0.05, 0);  // the feet are symmetric: the origin is the centre of mass
  body.w_WB0 = Vector3d(0, 0, 1.0);
  Model m = Model::withEffects({"stiffness", "damping", "coulomb", "rolling_resistance", "spin"});
  m.setParameter("stiffness.kv", 1e11);
  m.setParameter("damping.a", 20.0);
  Scenario s = onPlate(std::move(body), m);
  s.pairs[0].method = volume::Method::kHalfspace;
  s.settings.integrator = integrator;
  s.settings.impacts = ImpactMode::kResolve;
  s.settings.step = h;
  s.settings.abs_tol = 1e-10;  // the reference: 10x tighter moves these numbers by ~1e-6
  s.settings.rel_tol = 1e-7;
  s.settings.max_step = 2e-4;
  s.settings.duration = 0.019;
  s.settings.output_rate_hz = 1000.0;
  return run(s).back().bodies[1];
}

// The second foot's impact is resolved although its pair was in contact: the rocking rebound
// about y within 2 % of Dormand–Prince's (measured 0.1–0.3 % at 1 and 0.25 ms; taken by the
// plain step, as when only the aggregate was looked at, it was 68–86 % low), and the turn about
// x that the friction of the sliding foot gives it within 20 % (measured 14–15 %; the plain
// step: none). The 20 % is the plain steps' first-order error before the impact: the part
// rocks on the corners of its left foot, and its ω_x there is 0.1–0.3 rad/s off at 0.25 ms.
TEST(DiscreteImpacts, SecondPatchOfAPairInContactIsResolved) {
  const dynamics::BodyKinematics ref = afterSecondFoot(Integrator::kDopri5, 1e-3);
  ASSERT_LT(ref.w_WB.y(), -0.5) << "the part rocks back after the impact";
  ASSERT_LT(ref.w_WB.x(), -0.5);
  for (const double h : {1e-3, 2.5e-4}) {
    const dynamics::BodyKinematics k = afterSecondFoot(Integrator::kDiscrete, h);
    EXPECT_NEAR(k.w_WB.y(), ref.w_WB.y(), 0.02 * std::abs(ref.w_WB.y())) << "h = " << h;
    EXPECT_NEAR(k.w_WB.x(), ref.w_WB.x(), 0.2 * std::abs(ref.w_WB.x())) << "h = " << h;
  }
}

}  // namespace
}  // namespace vcontact::test
