// stiffness (MODEL.md §3): f_n = kv V n.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Stiffness, NormalForceIsKvVAlongTheNormal) {
  Model m = Model::withEffects({"stiffness"});
  m.setParameter("stiffness.kv", 3.1e12);
  const volume::ContactVolume cv = sphereContact();
  RelativeMotion slide;  // the elastic force ignores the motion
  slide.v_c_W = 0.3 * tangent(cv.n_W) - 0.1 * cv.n_W;
  const ContactResult r = m.evaluate(cv, slide, PairState{});
  const Eigen::Vector3d expected = 3.1e12 * cv.volume * cv.n_W;
  EXPECT_LT((r.wrench.f_W - expected).norm(), kRoundOff * expected.norm());
  EXPECT_EQ(r.wrench.tau_W, Eigen::Vector3d::Zero());
  EXPECT_NEAR(r.f_n, expected.norm(), kRoundOff * expected.norm());
}

}  // namespace
}  // namespace vcontact::dynamics::test
