// spin (MODEL.md §3), Coulomb form: τ_s = −μ_max r_gyr |f_n| sgn_ε(ω_n) n.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Spin, CoulombTorqueOpposesTheSpin) {
  Model m = Model::withEffects({"stiffness", "coulomb", "spin"});
  m.setParameter("coulomb.mu", 0.25);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume, r = cv.r_gyr;
  RelativeMotion fast, slow;
  fast.w_W = -2.0 * cv.n_W;  // r |ω_n| ≫ v_ε: sgn_ε = −1
  EXPECT_NEAR(m.evaluate(cv, fast, PairState{}).shares[2].tau_W.dot(cv.n_W), 0.25 * r * N,
              kRoundOff * N * r);
  const double v_eps = m.settings.v_eps;
  slow.w_W = 0.5 * v_eps / r * cv.n_W;  // below the regularisation: sgn_ε = 1/2
  EXPECT_NEAR(m.evaluate(cv, slow, PairState{}).shares[2].tau_W.dot(cv.n_W), -0.125 * r * N,
              kRoundOff * N * r);
}

}  // namespace
}  // namespace vcontact::dynamics::test
