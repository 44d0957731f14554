// contensou (MODEL.md §3): C_v = |v_t| / v_avg, C_ω = r_gyr |ω_n| / v_avg.

#include <gtest/gtest.h>

#include <cmath>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

// F = μ N |v_t|/v_avg and M = μ N r_gyr (r_gyr |ω_n|)/v_avg, v_avg = sqrt(|v_t|² + (r_gyr ω_n)²):
// the force and torque lie on the circle (F/μN)² + (M/(μ N r_gyr))² = 1.
TEST(Contensou, SharesOneFrictionBudget) {
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

}  // namespace
}  // namespace vcontact::dynamics::test
