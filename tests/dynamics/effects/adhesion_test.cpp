// adhesion (MODEL.md §3 "Normal law"): f_adh = −σ_a A n, the friction load unchanged.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Adhesion, TensileForceIsTheStressTimesTheArea) {
  Model m = Model::withEffects({"stiffness", "adhesion"});
  m.setParameter("stiffness.kv", 3.1e12);
  m.setParameter("adhesion.sigma_a", 4e6);
  const volume::ContactVolume cv = sphereContact();
  const ContactResult r = m.evaluate(cv, RelativeMotion{}, PairState{});
  const Eigen::Vector3d expected = (3.1e12 * cv.volume - 4e6 * cv.area) * cv.n_W;
  EXPECT_LT((r.wrench.f_W - expected).norm(), kRoundOff * 3.1e12 * cv.volume);
  EXPECT_NEAR(r.f_n, 3.1e12 * cv.volume, kRoundOff * 3.1e12 * cv.volume);  // friction's load
}

// Near separation the adhesion outweighs the elastic force: a sphere 20 µm deep has
// V ≈ A d/2, so kv V < σ_a A when σ_a > kv d/2; the net normal force then pulls.
TEST(Adhesion, NetForceIsTensileNearSeparation) {
  Model m = Model::withEffects({"stiffness", "adhesion"});
  m.setParameter("stiffness.kv", 1e10);
  m.setParameter("adhesion.sigma_a", 1e10 * 20e-6);  // = kv d: twice the elastic stress
  const volume::ContactVolume cv = sphereContact();
  const ContactResult r = m.evaluate(cv, RelativeMotion{}, PairState{});
  EXPECT_LT(r.wrench.f_W.dot(cv.n_W), 0.0);
}

}  // namespace
}  // namespace vcontact::dynamics::test
