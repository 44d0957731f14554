// power_law (MODEL.md §3 "Normal law"): f_n = kv V (V/V_ref)^(p−1), V_ref = 1 mm³.

#include <gtest/gtest.h>

#include <cmath>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

constexpr double kReferenceVolume = 1e-9;  // m³, MODEL.md §3

TEST(PowerLaw, NormalForceIsThePowerOfTheVolume) {
  const volume::ContactVolume cv = sphereContact();
  for (const double p : {0.75, 1.0, 1.6}) {
    Model m = Model::withEffects({"stiffness", "power_law"});
    m.setParameter("stiffness.kv", 3.1e12);
    m.setParameter("power_law.p", p);
    const ContactResult r = m.evaluate(cv, RelativeMotion{}, PairState{});
    const double expected = 3.1e12 * cv.volume * std::pow(cv.volume / kReferenceVolume, p - 1.0);
    EXPECT_NEAR(r.f_n, expected, kRoundOff * expected) << "p = " << p;
    EXPECT_LT((r.wrench.f_W - expected * cv.n_W).norm(), kRoundOff * expected);
  }
}

// p = 1 is the volumetric law to the bit: the effect's share is zero.
TEST(PowerLaw, ExponentOneIsTheVolumetricLaw) {
  const volume::ContactVolume cv = sphereContact();
  const Model plain = Model::withEffects({"stiffness"});
  const Model power = Model::withEffects({"stiffness", "power_law"});
  EXPECT_EQ(plain.evaluate(cv, RelativeMotion{}, PairState{}).wrench.f_W,
            power.evaluate(cv, RelativeMotion{}, PairState{}).wrench.f_W);
}

// The law's stiffness ∂f_n/∂V = p f_n/V (ContactContext::k_n, read by the discrete stepper),
// against a central difference in V (relative step 1e-6: truncation ~1e-12, round-off ~1e-10).
TEST(PowerLaw, NormalStiffnessIsTheDerivativeInTheVolume) {
  Model m = Model::withEffects({"stiffness", "power_law"});
  m.setParameter("power_law.p", 1.7);
  volume::ContactVolume cv = sphereContact();
  const double k_n = m.context(cv, RelativeMotion{}, PairState{}).k_n;
  const double V = cv.volume, h = 1e-6 * V;
  cv.volume = V + h;
  const double up = m.evaluate(cv, RelativeMotion{}, PairState{}).f_n;
  cv.volume = V - h;
  const double down = m.evaluate(cv, RelativeMotion{}, PairState{}).f_n;
  EXPECT_NEAR(k_n, (up - down) / (2.0 * h), 1e-8 * k_n);
}

}  // namespace
}  // namespace vcontact::dynamics::test
