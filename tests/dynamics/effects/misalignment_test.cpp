// misalignment (MODEL.md §3): body A turned by rx, ry about axes parallel to body B's x, y.

#include <gtest/gtest.h>

#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Misalignment, TurnsThePayloadAboutPlateAxes) {
  Model m = Model::withEffects({"misalignment"});
  m.setParameter("misalignment.rx", 0.01);
  const Eigen::Isometry3d X_WB = vcontact::test::randomPose(3);
  const Eigen::Isometry3d X_WA = vcontact::test::randomPose(4);
  const Eigen::Isometry3d X_WA_tilted = m.adjustPayloadPose(X_WA, X_WB);
  EXPECT_EQ(X_WA_tilted.translation(), X_WA.translation());
  const Eigen::AngleAxisd turn(X_WA_tilted.linear() * X_WA.linear().transpose());
  EXPECT_NEAR(turn.angle(), 0.01, 1e-12);  // one rotation of 0.01 rad, to round-off
  // the axis from a 0.01 rad rotation matrix: its round-off over the angle, ~1e-14/0.01
  EXPECT_NEAR(std::abs(turn.axis().dot(X_WB.linear().col(0))), 1.0, 1e-9);
}

}  // namespace
}  // namespace vcontact::dynamics::test
