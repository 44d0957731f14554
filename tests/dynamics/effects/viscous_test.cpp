// viscous (MODEL.md §3): −|f_n| σ2 v_t and −r_gyr² |f_n| σ2 ω_n n.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Viscous, ForceAndSpinTorqueAreLinearInTheMotion) {
  Model m = Model::withEffects({"stiffness", "viscous"});
  m.setParameter("viscous.sigma2", 4.0);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume, r = cv.r_gyr;
  RelativeMotion mo;
  mo.v_c_W = 0.02 * tangent(cv.n_W);
  mo.w_W = 3.0 * cv.n_W + 5.0 * cv.n_W.cross(tangent(cv.n_W));  // rolling part: no term
  const ContactResult res = m.evaluate(cv, mo, PairState{});
  const Wrench& w = res.shares[1];
  EXPECT_LT((w.f_W + N * 4.0 * mo.v_c_W).norm(), kRoundOff * N);
  EXPECT_LT((w.tau_W + r * r * N * 4.0 * 3.0 * cv.n_W).norm(), kRoundOff * N * r);
}

}  // namespace
}  // namespace vcontact::dynamics::test
