// The force model as named parameters in, wrench out: parameters, composition of the effects
// of MODEL.md §3 and their closed forms on given contact volumes and motions.

#include "dynamics/model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/effects/registry.hpp"
#include "geometry/error.hpp"
#include "support/test_support.hpp"
#include "volume/analytic.hpp"

namespace vcontact::dynamics {
namespace {

// Closed forms evaluated once in double precision: a few ulps of the largest term.
constexpr double kRoundOff = 1e-12;

// A sphere of radius 10 mm pressed 20 µm into a plate whose normal is not a coordinate axis.
volume::ContactVolume sphereContact() {
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = test::rotationZTo(Eigen::Vector3d(0.3, -0.2, 0.9).normalized());
  Eigen::Isometry3d X_WS = X_WH;
  X_WS.translation() = X_WH * Eigen::Vector3d(0.0, 0.0, 0.01 - 20e-6);
  return volume::sphereHalfspace(0.01, X_WS, X_WH);
}

Eigen::Vector3d tangent(const Eigen::Vector3d& n) { return n.unitOrthogonal(); }

TEST(Model, ParameterNamesFollowEffectStageOrderAndRoundTrip) {
  Model m = Model::withEffects({"coulomb", "stiffness", "damping", "bristle"});
  const std::vector<std::string> expected = {"stiffness.kv",   "damping.a",  "bristle.sigma0",
                                             "bristle.sigma1", "coulomb.mu", "coulomb.v_s"};
  EXPECT_EQ(m.parameterNames(), expected);
  const std::vector<double> values = {1e12, 2.5, 1000.0, 50.0, 0.3, 2e-3};
  m.setParameters(values);
  EXPECT_EQ(m.parameters(), values);
  EXPECT_EQ(m.parameter("coulomb.mu"), 0.3);
}

TEST(Model, RejectsOutOfBoundsNonFiniteAndUnknown) {
  Model m = Model::withEffects({"stiffness", "coulomb"});
  EXPECT_THROW(m.setParameter("coulomb.mu", -0.1), InputError);
  EXPECT_THROW(m.setParameter("coulomb.mu", std::nan("")), InputError);
  EXPECT_THROW(m.setParameter("coulomb.nu", 0.1), InputError);
  EXPECT_THROW(m.setParameters(std::vector<double>{1.0}), InputError);
  EXPECT_THROW(Model::withEffects({"stiffness", "glue"}), InputError);
  EXPECT_THROW(Model::withEffects({"coulomb"}), InputError);  // needs stiffness
  EXPECT_THROW(Model::withEffects({"stiffness", "stiffness"}), InputError);
}

TEST(Model, EveryRegisteredEffectHasBoundedDefaults) {
  for (const auto& id : registeredEffectIds()) {
    const auto e = createEffect(id);
    ASSERT_NE(e, nullptr) << id;
    EXPECT_EQ(e->id(), id);
    for (const auto& p : e->parameterSpecs()) {
      EXPECT_LE(p.lower, p.default_value) << id << "." << p.name;
      EXPECT_GE(p.upper, p.default_value) << id << "." << p.name;
      EXPECT_FALSE(p.unit.empty()) << id << "." << p.name;
    }
  }
}

TEST(Model, NoContactGivesNothing) {
  const Model m = Model::withEffects({"stiffness", "damping", "coulomb", "bristle", "spin"});
  PairState state;
  state.z_W = Eigen::Vector3d(1e-6, 0, 0);
  const ContactResult r = m.evaluate(volume::ContactVolume{}, RelativeMotion{}, state);
  EXPECT_EQ(r.wrench.f_W, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.rates.z_W, Eigen::Vector3d::Zero());
}

TEST(Model, StiffnessDampingAndClamp) {
  Model m = Model::withEffects({"stiffness", "damping"});
  m.setParameter("damping.a", 3.0);
  const volume::ContactVolume cv = sphereContact();
  const double kv = m.parameter("stiffness.kv");
  RelativeMotion approach;
  approach.v_c_W = -0.1 * cv.n_W;  // δ̇ = 0.1 m/s
  const ContactResult r = m.evaluate(cv, approach, PairState{});
  // f_n = kv V (1 + a δ̇) n
  const Eigen::Vector3d expected = kv * cv.volume * (1.0 + 3.0 * 0.1) * cv.n_W;
  EXPECT_LT((r.wrench.f_W - expected).norm(), kRoundOff * expected.norm());
  // shares add up: stiffness kv V n, damping the rest
  EXPECT_LT((r.shares[0].f_W - kv * cv.volume * cv.n_W).norm(), kRoundOff * expected.norm());
  RelativeMotion separate;
  separate.v_c_W = 1.0 * cv.n_W;  // 1 + a δ̇ = −2 < 0: clamped to zero
  EXPECT_EQ(m.evaluate(cv, separate, PairState{}).wrench.f_W.norm(), 0.0);
}

TEST(Model, CoulombSlidingAndStribeckAtRest) {
  Model m = Model::withEffects({"stiffness", "coulomb", "stribeck"});
  m.setParameter("coulomb.mu", 0.2);
  m.setParameter("stribeck.mu_s", 0.35);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const Eigen::Vector3d t = tangent(cv.n_W);
  RelativeMotion fast;
  fast.v_c_W = 0.5 * t;  // v ≫ v_s: s = exp(−250000) = 0, μ_max = μ_C
  const ContactResult r = m.evaluate(cv, fast, PairState{});
  EXPECT_LT((r.wrench.f_W - (N * cv.n_W - 0.2 * N * t)).norm(), kRoundOff * N);
  RelativeMotion creep;
  creep.v_c_W = 1e-4 * t;  // v ≫ v_ε = 1e-5, s = exp(−0.01)
  const double s = std::exp(-0.01);
  const double mu_max = 0.2 + 0.15 * s;
  const ContactResult c = m.evaluate(cv, creep, PairState{});
  EXPECT_NEAR(c.mu_max, mu_max, kRoundOff);
  EXPECT_LT((c.wrench.f_W - (N * cv.n_W - mu_max * N * t)).norm(), kRoundOff * N);
}

// MODEL.md §3: with contensou, F = μ N |v_t|/v_avg and M = μ N r_gyr (r_gyr |ω_n|)/v_avg,
// v_avg = sqrt(|v_t|² + (r_gyr ω_n)²): the force and torque lie on the circle
// (F/μN)² + (M/(μ N r_gyr))² = 1.
TEST(Model, ContensouSharesOneFrictionBudget) {
  Model m = Model::withEffects({"stiffness", "coulomb", "spin", "contensou"});
  m.setParameter("coulomb.mu", 0.25);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume, r = cv.r_gyr;
  const Eigen::Vector3d t = tangent(cv.n_W);
  for (double ratio : {0.1, 0.7, 1.0, 3.0}) {  // r ω / v
    RelativeMotion mo;
    const double v = 0.02, w = ratio * v / r;
    mo.v_c_W = v * t;
    mo.w_W = w * cv.n_W;
    const double v_avg = std::hypot(v, r * w);
    const ContactResult res = m.evaluate(cv, mo, PairState{});
    const Eigen::Vector3d f_t = res.wrench.f_W - res.wrench.f_W.dot(cv.n_W) * cv.n_W;
    EXPECT_LT((f_t + 0.25 * N * (v / v_avg) * t).norm(), kRoundOff * N) << ratio;
    EXPECT_NEAR(res.wrench.tau_W.dot(cv.n_W), -0.25 * N * r * (r * w / v_avg), kRoundOff * N * r)
        << ratio;
    EXPECT_NEAR(std::pow(f_t.norm() / (0.25 * N), 2) +
                    std::pow(res.wrench.tau_W.norm() / (0.25 * N * r), 2),
                1.0, kRoundOff)
        << ratio;
  }
}

// MODEL.md §3: rolling resistance dissipates at the rate τ_r·ω_t = −kv a ω_tᵀ J_s ω_t.
TEST(Model, RollingResistancePower) {
  Model m = Model::withEffects({"stiffness", "damping", "rolling_resistance"});
  m.setParameter("damping.a", 4.0);
  const volume::ContactVolume cv = sphereContact();
  RelativeMotion roll;
  roll.w_W = 7.0 * tangent(cv.n_W) + 2.0 * cv.n_W;  // spin part is no rolling
  const Eigen::Vector3d w_t = roll.w_W - roll.w_W.dot(cv.n_W) * cv.n_W;
  const ContactResult r = m.evaluate(cv, roll, PairState{});
  const double expected = -m.parameter("stiffness.kv") * 4.0 * w_t.dot(cv.J_s * w_t);
  ASSERT_LT(expected, 0.0);
  EXPECT_NEAR(r.shares[2].tau_W.dot(roll.w_W), expected, kRoundOff * std::abs(expected));
}

// MODEL.md §3 bristle: stuck (s = 1) the bristle follows the slip, ż = v_t, and the force is
// −|f_n|(σ0 z + σ1 v_t) below the limit; sliding fast it saturates at μ_max |f_n|.
TEST(Model, BristleStuckAndSaturated) {
  Model m = Model::withEffects({"stiffness", "coulomb", "bristle", "spin"});
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const double s0 = m.parameter("bristle.sigma0"), s1 = m.parameter("bristle.sigma1");
  const Eigen::Vector3d t = tangent(cv.n_W);
  PairState state;
  state.z_W = 1e-5 * t + 3e-6 * cv.n_W;  // the normal part is projected away
  const ContactResult stuck = m.evaluate(cv, RelativeMotion{}, state);
  EXPECT_LT((stuck.wrench.f_W - (N * cv.n_W - N * s0 * 1e-5 * t)).norm(), kRoundOff * N);
  EXPECT_EQ(stuck.rates.z_W, Eigen::Vector3d::Zero());
  RelativeMotion slide;
  slide.v_c_W = 0.3 * t;
  const ContactResult sliding = m.evaluate(cv, slide, state);
  const Eigen::Vector3d f_t = sliding.wrench.f_W - N * cv.n_W;
  EXPECT_NEAR(f_t.norm(), 0.2 * N, kRoundOff * N);
  // s = 0: ż = (μ_C/σ1) dir(v) − (σ0/σ1) z
  EXPECT_LT((sliding.rates.z_W - ((0.2 / s1) * t - (s0 / s1) * 1e-5 * t)).norm(), kRoundOff);
}

TEST(Model, MisalignmentTurnsThePayloadAboutPlateAxes) {
  Model m = Model::withEffects({"misalignment"});
  m.setParameter("misalignment.rx", 0.01);
  const Eigen::Isometry3d X_W2 = test::randomPose(3);
  const Eigen::Isometry3d X_W1 = test::randomPose(4);
  const Eigen::Isometry3d X = m.adjustPayloadPose(X_W1, X_W2);
  EXPECT_EQ(X.translation(), X_W1.translation());
  const Eigen::AngleAxisd turn(X.linear() * X_W1.linear().transpose());
  EXPECT_NEAR(turn.angle(), 0.01, 1e-12);  // one rotation of 0.01 rad, to round-off
  EXPECT_NEAR(std::abs(turn.axis().dot(X_W2.linear().col(0))), 1.0, 1e-9);
}

TEST(Model, SettleProjectsAndResets) {
  const Model m = Model::withEffects({"stiffness", "coulomb", "stribeck", "bristle", "dwell"});
  const volume::ContactVolume cv = sphereContact();
  PairState state;
  state.z_W = 1e-5 * tangent(cv.n_W) + 2e-6 * cv.n_W;
  state.s_dw = 0.9;
  RelativeMotion slide;
  slide.v_c_W = 0.01 * tangent(cv.n_W);  // s ≈ 0 < s_dw: bonds break at once
  EXPECT_TRUE(m.settle(cv, slide, state));
  EXPECT_NEAR(state.z_W.dot(cv.n_W), 0.0, 1e-20);
  EXPECT_LT(state.s_dw, 1e-30);
  EXPECT_TRUE(m.settle(volume::ContactVolume{}, slide, state));
  EXPECT_EQ(state.z_W, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace vcontact::dynamics
