// rolling_resistance (MODEL.md §3): τ_r = −kv a J_s ω_t.

#include <gtest/gtest.h>

#include <cmath>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

// Rolling resistance dissipates at the rate τ_r·ω_t = −kv a ω_tᵀ J_s ω_t.
TEST(RollingResistance, DissipatesAtTheRateOfJs) {
  Model m = Model::withEffects({"stiffness", "damping", "rolling_resistance"});
  m.setParameter("damping.a", 4.0);
  const volume::ContactVolume cv = sphereContact();
  RelativeMotion roll;
  roll.w_W = 7.0 * tangent(cv.n_W) + 2.0 * cv.n_W;  // spin part is no rolling
  const Eigen::Vector3d w_t_W = roll.w_W - roll.w_W.dot(cv.n_W) * cv.n_W;
  const ContactResult r = m.evaluate(cv, roll, PairState{});
  const double expected = -m.parameter("stiffness.kv") * 4.0 * w_t_W.dot(cv.J_s * w_t_W);
  ASSERT_LT(expected, 0.0);
  EXPECT_NEAR(r.shares[2].tau_W.dot(roll.w_W), expected, kRoundOff * std::abs(expected));
}

}  // namespace
}  // namespace vcontact::dynamics::test
