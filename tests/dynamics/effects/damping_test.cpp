// damping (MODEL.md §3): f_n = kv V (1 + a δ̇_c) n, clamped so that f_n·n ≥ 0.

#include <gtest/gtest.h>

#include "dynamics/restitution.hpp"
#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Damping, ApproachAddsForceAndSeparationIsClamped) {
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
  EXPECT_LT((r.shares[1].f_W - kv * cv.volume * 3.0 * 0.1 * cv.n_W).norm(),
            kRoundOff * expected.norm());
  RelativeMotion separate;
  separate.v_c_W = 1.0 * cv.n_W;  // 1 + a δ̇ = −2 < 0: clamped to zero
  EXPECT_EQ(m.evaluate(cv, separate, PairState{}).wrench.f_W.norm(), 0.0);
}

// The restitution the discrete stepper predicts rebounds with (Model::impactRestitution) is
// damping's exact e(a v) (restitution_test checks that relation against the impact's ODE), 1
// for a model that dissipates nothing, and falls with the approach speed.
TEST(Damping, PredictsTheRestitutionOfAHeadOnImpact) {
  Model m = Model::withEffects({"stiffness", "damping"});
  m.setParameter("damping.a", 0.8);
  for (const double v : {0.01, 0.3, 2.0}) {
    EXPECT_EQ(m.impactRestitution(v), dampedRestitution(0.8 * v)) << "v " << v;
  }
  EXPECT_GT(m.impactRestitution(0.3), m.impactRestitution(2.0));
  EXPECT_LT(m.impactRestitution(2.0), 1.0);
  EXPECT_EQ(Model::withEffects({"stiffness"}).impactRestitution(2.0), 1.0);
  m.setParameter("damping.a", 0.0);
  EXPECT_EQ(m.impactRestitution(2.0), 1.0);
}

}  // namespace
}  // namespace vcontact::dynamics::test
