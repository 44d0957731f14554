// dwell (MODEL.md §3 "Dwell time"): state s_dw replaces s in μ_max;
//   ṡ_dw = (s − s_dw)/τ_dw while s > s_dw;  s_dw = s when s ≤ s_dw.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Dwell, StickStateGrowsAtRestAndLimitsMuMax) {
  Model m = Model::withEffects({"stiffness", "coulomb", "stribeck", "dwell"});
  m.setParameter("coulomb.mu", 0.2);
  m.setParameter("stribeck.mu_s", 0.35);
  m.setParameter("dwell.tau_dw", 0.4);
  const volume::ContactVolume cv = sphereContact();
  const int s_dw = stateOffset(m, "dwell");
  PairState state;
  state[s_dw] = 0.3;
  const ContactResult rest = m.evaluate(cv, RelativeMotion{}, state);  // s = 1
  EXPECT_NEAR(rest.rates[s_dw], (1.0 - 0.3) / 0.4, kRoundOff);
  EXPECT_NEAR(rest.mu_max, 0.2 + 0.15 * 0.3, kRoundOff);
}

TEST(Dwell, BondsBreakAtOnce) {
  const Model m = Model::withEffects({"stiffness", "coulomb", "stribeck", "bristle", "dwell"});
  const volume::ContactVolume cv = sphereContact();
  const int s_dw = stateOffset(m, "dwell");
  PairState state;
  state[s_dw] = 0.9;
  RelativeMotion slide;
  slide.v_c_W = 0.01 * tangent(cv.n_W);  // s ≈ 0 < s_dw: bonds break at once
  EXPECT_TRUE(m.settle(cv, slide, state));
  EXPECT_LT(state[s_dw], 1e-30);  // s = exp(−(0.01/v_s)²) = exp(−100) ≈ 4e-44
}

}  // namespace
}  // namespace vcontact::dynamics::test
