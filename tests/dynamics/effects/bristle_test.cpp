// bristle (MODEL.md §3, Gonthier 2007): states z (in the contact plane) and θ_n,
//   ż = s v_t + (1 − s) ((C_v μ_C / σ1) dir_ε(v_t) − (σ0/σ1) z),  f_t = −|f_n| sat(σ0 z + σ1 ż,
//   μ_max).

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics::test {
namespace {

// Stuck (s = 1) the bristle follows the slip, ż = v_t, and the force is −|f_n|(σ0 z + σ1 v_t)
// below the limit; sliding fast it saturates at μ_max |f_n|.
TEST(Bristle, StuckAndSaturated) {
  Model m = Model::withEffects({"stiffness", "coulomb", "bristle", "spin"});
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const double s0 = m.parameter("bristle.sigma0"), s1 = m.parameter("bristle.sigma1");
  const Eigen::Vector3d t = tangent(cv.n_W);
  const int z = stateOffset(m, "bristle");
  PairState state;
  state.vector(z) = 1e-5 * t + 3e-6 * cv.n_W;  // the normal part is projected away
  const ContactResult stuck = m.evaluate(cv, RelativeMotion{}, state);
  EXPECT_LT((stuck.wrench.f_W - (N * cv.n_W - N * s0 * 1e-5 * t)).norm(), kRoundOff * N);
  EXPECT_EQ(Eigen::Vector3d(stuck.rates.vector(z)), Eigen::Vector3d::Zero());
  RelativeMotion slide;
  slide.v_c_W = 0.3 * t;
  const ContactResult sliding = m.evaluate(cv, slide, state);
  const Eigen::Vector3d f_t = sliding.wrench.f_W - N * cv.n_W;
  EXPECT_NEAR(f_t.norm(), 0.2 * N, kRoundOff * N);
  // s = 0: ż = (μ_C/σ1) dir(v) − (σ0/σ1) z
  EXPECT_LT((sliding.rates.vector(z) - ((0.2 / s1) * t - (s0 / s1) * 1e-5 * t)).norm(), kRoundOff);
}

// θ̇_n = s ω_n when stuck; the spin torque is then −r_gyr² |f_n| (σ0 θ_n + σ1 ω_n) n.
TEST(Bristle, TorsionalStateFollowsTheSpinWhenStuck) {
  Model m = Model::withEffects({"stiffness", "coulomb", "stribeck", "bristle", "spin"});
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume, r = cv.r_gyr;
  const double s0 = m.parameter("bristle.sigma0"), s1 = m.parameter("bristle.sigma1");
  const int theta = stateOffset(m, "bristle") + 3;
  PairState state;
  state[theta] = 1e-6;  // rad
  RelativeMotion turn;
  turn.w_W = 1e-12 / r * cv.n_W;  // (r ω_n / v_s)² = 1e-18: s = 1 exactly in double
  const ContactResult res = m.evaluate(cv, turn, state);
  EXPECT_NEAR(res.rates[theta], turn.w_W.norm(), kRoundOff * turn.w_W.norm());
  const double expected = -r * r * N * (s0 * 1e-6 + s1 * turn.w_W.norm());
  EXPECT_NEAR(res.wrench.tau_W.dot(cv.n_W), expected, kRoundOff * std::abs(expected));
}

TEST(Bristle, HasNoDistributedForm) {
  const Model m = Model::withEffects({"stiffness", "coulomb", "bristle"});
  EXPECT_THROW(m.checkDistributedFriction(), InputError);
}

}  // namespace
}  // namespace vcontact::dynamics::test
