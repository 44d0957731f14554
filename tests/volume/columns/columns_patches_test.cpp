// The patches of the column method between two meshes (columns/columns.hpp) against the exact fast
// method on the same poses, through the dispatcher: regions on opposite walls, four key flanks
// with tangential normals, a dumbbell's two caps, a U's two feet (columns/columns_agreement.hpp).

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "columns_agreement.hpp"
#include "support/test_support.hpp"
#include "volume/contact.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::TriangleMesh;

geometry::Shape shape(TriangleMesh mesh, const std::string& name) {
  return geometry::Mesh{std::make_shared<const TriangleMesh>(std::move(mesh)), name};
}

/// fast and columns on one pose; fast's patch count is the expected one.
void expectSameAsFast(const geometry::Shape& a, const Isometry3d& X_WA, const geometry::Shape& b,
                      const Isometry3d& X_WB, std::size_t patches, double size) {
  const ContactPatches fast =
      computeContact(a, X_WA, b, X_WB, {Method::kFast, 0, DepthMode::kDeepest});
  const ContactPatches columns = computeContact(a, X_WA, b, X_WB, {Method::kColumns});
  ASSERT_EQ(fast.patches.size(), patches);
  test::expectColumnsAgree(fast, columns, size);
}

// A round peg tilted 0.03 rad in a hole with 0.2 mm clearance: two patches on opposite walls.
TEST(ColumnsPatches, TiltedPegBearsOnOppositeWalls) {
  const geometry::Shape hole = shape(test::tube(0.0203, 0.0101, 0.0203, 64), "hole");
  const geometry::Shape peg = shape(geometry::tessellateCylinder(0.0099, 0.0407, 64), "peg");
  const Isometry3d X_WH = test::randomPose(15);
  const Isometry3d X_WP = X_WH * Isometry3d(Eigen::AngleAxisd(0.03, Vector3d::UnitX()));
  expectSameAsFast(peg, X_WP, hole, X_WH, 2, 0.0203);
}

// A four-key shaft turned 0.03 rad in a hub of four blocks: one patch per leading flank, each
// with a tangential normal, none shared by two patches.
TEST(ColumnsPatches, KeyedShaftTurnedInItsHub) {
  const double a = 0.0041, L = 0.0149, gap = 0.0002, w = 0.0051;
  const geometry::Shape hub = shape(test::keyedHub(a, gap, w), "hub");
  const geometry::Shape shaft = shape(test::keyedShaft(a, L, 0.0203), "shaft");
  const Isometry3d X_WH = test::randomPose(17);
  const Isometry3d X_WS = X_WH * Isometry3d(Eigen::AngleAxisd(0.03, Vector3d::UnitZ()));
  expectSameAsFast(shaft, X_WS, hub, X_WH, 4, L);
}

// Two spheres of one body pressed into a plate mesh: one cap each.
TEST(ColumnsPatches, DumbbellEnds) {
  const double R = 0.0103, d = 0.0017, half = 0.031;
  const auto [left, right] = test::dumbbellEnds(R, half);
  const Isometry3d X_WH = test::randomPose(16);
  const Isometry3d X_WM = X_WH * test::translation({0.004, -0.007, R - d});
  expectSameAsFast(shape(test::twoShells(left, right), "dumbbell"), X_WM,
                   shape(test::plateTopAtZero(), "plate"), X_WH, 2, R);
}

}  // namespace
}  // namespace vcontact::volume
