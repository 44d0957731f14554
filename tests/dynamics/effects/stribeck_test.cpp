// stribeck (MODEL.md §3): μ_max = μ_C + (μ_S − μ_C) s, and the relation μ_S ≥ μ_C.

#include <gtest/gtest.h>

#include <cmath>

#include "effect_fixtures.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Stribeck, FastSlidingUsesMuCAndCreepRisesTowardMuS) {
  Model m = Model::withEffects({"stiffness", "coulomb", "stribeck"});
  m.setParameter("coulomb.mu", 0.2);
  m.setParameter("stribeck.mu_s", 0.35);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  const Eigen::Vector3d t = tangent(cv.n_W);
  RelativeMotion fast;
  fast.v_c_W = 0.5 * t;  // v ≫ v_s: s = exp(−250000) = 0, μ_max = μ_C
  const ContactResult r = m.evaluate(cv, fast, PairState{});
  EXPECT_LT((r.wrench.f_W - (N * cv.n_W - 0.2 * N * t)).norm(), kRoundOff * N);
  RelativeMotion creep;
  creep.v_c_W = 1e-4 * t;  // v ≫ v_ε = 1e-5, s = exp(−0.01)
  const double s = std::exp(-0.01);
  const double mu_max = 0.2 + 0.15 * s;
  const ContactResult c = m.evaluate(cv, creep, PairState{});
  EXPECT_NEAR(c.mu_max, mu_max, kRoundOff);
  EXPECT_LT((c.wrench.f_W - (N * cv.n_W - mu_max * N * t)).norm(), kRoundOff * N);
}

TEST(Stribeck, StaticBelowKineticFrictionIsABrokenRelation) {
  Model m = Model::withEffects({"stiffness", "coulomb", "stribeck"});
  m.setParameter("coulomb.mu", 0.3);
  m.setParameter("stribeck.mu_s", 0.25);
  try {
    m.validate();
    FAIL() << "mu_s < mu expected to throw";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "model");
    EXPECT_NE(e.message().find("stribeck.mu_s = 0.25 must be >= coulomb.mu = 0.3"),
              std::string::npos)
        << e.message();
  }
  m.setParameter("stribeck.mu_s", 0.3);  // equal is allowed
  EXPECT_NO_THROW(m.validate());
}

}  // namespace
}  // namespace vcontact::dynamics::test
