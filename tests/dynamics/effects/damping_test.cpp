// damping (MODEL.md §3): f_n = kv V (1 + a δ̇_c) n, clamped so that f_n·n ≥ 0.

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vcontact::dynamics::test
