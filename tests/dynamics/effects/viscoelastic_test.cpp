// viscoelastic (MODEL.md §3 "Normal law"): a standard linear solid,
//   f_n = max(0, r f_e + q),  q̇ = (1 − r) (∂f_e/∂V) A δ̇ − q/τ.

#include <gtest/gtest.h>

#include <cmath>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

Model solid(double tau, double ratio) {
  Model m = Model::withEffects({"stiffness", "viscoelastic"});
  m.setParameter("stiffness.kv", 3.1e12);
  m.setParameter("viscoelastic.tau", tau);
  m.setParameter("viscoelastic.ratio", ratio);
  return m;
}

TEST(Viscoelastic, ForceIsTheRelaxedSpringPlusTheMaxwellBranch) {
  const Model m = solid(0.2, 0.4);
  const volume::ContactVolume cv = sphereContact();
  PairState state;
  const int q = stateOffset(m, "viscoelastic");
  state[q] = 1.5;  // N
  RelativeMotion pressing;
  pressing.v_c_W = -2e-6 * cv.n_W;  // δ̇ = 2 µm/s
  const ContactResult r = m.evaluate(cv, pressing, state);
  const double f_e = 3.1e12 * cv.volume;
  EXPECT_NEAR(r.f_n, 0.4 * f_e + 1.5, kRoundOff * f_e);
  // q̇ = (1 − r) kv A δ̇ − q/τ
  const double rate = 0.6 * 3.1e12 * cv.area * 2e-6 - 1.5 / 0.2;
  EXPECT_NEAR(r.rates[q], rate, kRoundOff * std::abs(rate) + 1e-12);
}

// A step indentation held: integrating q̇ from the instantaneous response q0 = (1 − r) f_e
// relaxes f_n to r f_e as e^(−t/τ) (closed form of the hold: δ̇ = 0 ⇒ q = q0 e^(−t/τ)). Explicit
// Euler with dt = τ/1000 for 3τ; its global error is ~ (dt/2τ)·t/τ·e^(−t/τ) ≈ 1e-4 relative.
TEST(Viscoelastic, HoldRelaxesToTheRelaxedStiffness) {
  const double tau = 0.05, ratio = 0.3;
  const Model m = solid(tau, ratio);
  const volume::ContactVolume cv = sphereContact();
  const double f_e = 3.1e12 * cv.volume;
  const int q = stateOffset(m, "viscoelastic");
  PairState state;
  state[q] = (1.0 - ratio) * f_e;
  const double dt = tau / 1000.0;
  for (int i = 0; i < 3000; ++i) state[q] += dt * m.evaluate(cv, RelativeMotion{}, state).rates[q];
  const double expected = ratio * f_e + (1.0 - ratio) * f_e * std::exp(-3.0);
  EXPECT_NEAR(m.evaluate(cv, RelativeMotion{}, state).f_n, expected, 1e-3 * expected);
}

// Unloading faster than the branch relaxes: the force is clamped at 0 (the surface lifts off
// the sample), never tensile.
TEST(Viscoelastic, ForceIsNeverTensile) {
  const Model m = solid(0.2, 0.5);
  const volume::ContactVolume cv = sphereContact();
  PairState state;
  state[stateOffset(m, "viscoelastic")] = -1e6;
  const ContactResult r = m.evaluate(cv, RelativeMotion{}, state);
  EXPECT_EQ(r.f_n, 0.0);
  EXPECT_EQ(r.wrench.f_W.norm(), 0.0);
}

}  // namespace
}  // namespace vcontact::dynamics::test
