// coulomb (MODEL.md §3): f_t = −μ_max |f_n| dir_ε(v_t), μ_max = μ_C without stribeck.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Coulomb, SlidingForceIsMuTimesTheLoadAgainstTheSlip) {
  Model m = Model::withEffects({"stiffness", "coulomb"});
  m.setParameter("coulomb.mu", 0.3);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const Eigen::Vector3d t = tangent(cv.n_W);
  RelativeMotion fast;
  fast.v_c_W = 0.5 * t - 1e-9 * cv.n_W;  // the normal part is no slip
  const ContactResult r = m.evaluate(cv, fast, PairState{});
  EXPECT_LT((r.wrench.f_W - (N * cv.n_W - 0.3 * N * t)).norm(), kRoundOff * N);
}

TEST(Coulomb, BelowTheRegularisationSpeedTheForceIsLinearInTheSlip) {
  Model m = Model::withEffects({"stiffness", "coulomb"});
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const double v_eps = m.settings.v_eps;
  const Eigen::Vector3d t = tangent(cv.n_W);
  RelativeMotion creep;
  creep.v_c_W = 0.25 * v_eps * t;  // dir_ε(v) = v / v_ε = t / 4
  const ContactResult r = m.evaluate(cv, creep, PairState{});
  EXPECT_LT((r.shares[1].f_W + 0.2 * N * 0.25 * t).norm(), kRoundOff * N);
}

}  // namespace
}  // namespace vcontact::dynamics::test
