// The triangle-pair and box filters of the exact mesh–mesh intersection: each may only answer
// "certainly apart" for pairs that are apart, and must answer it for the clear cases it exists
// to drop (otherwise the exact predicates run on every pair). Fixtures are small triangles whose
// answer can be read off by eye; coordinates are exact in binary unless stated.

#include "volume/fast/triangle_pair.hpp"

#include <gtest/gtest.h>

namespace vcontact::volume::internal {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

// The unit right triangle in z = 0, normal +z.
PlacedFace floorFace() { return placedFace({0, 0, 0}, {1, 0, 0}, {0, 1, 0}); }

TEST(TrianglePair, PlacedFaceHasItsNormalBoxAndBound) {
  const PlacedFace F = floorFace();
  EXPECT_EQ(F.n, Vector3d(0, 0, 1));
  EXPECT_EQ(F.lo, Vector3d(0, 0, 0));
  EXPECT_EQ(F.hi, Vector3d(1, 1, 0));
  EXPECT_EQ(F.nBound, kOrientBound);  // ‖u‖₁ = ‖v‖₁ = 1
}

TEST(TrianglePair, PlaneSidesCertainAndUncertain) {
  const PlacedFace F = floorFace();
  int side[3];
  const Vector3d above[3] = {{0, 0, 1}, {1, 1, 2}, {0.25, 0.5, 0.5}};
  EXPECT_EQ(planeSides(F, above, side), 1);
  const Vector3d below[3] = {{0, 0, -1}, {1, 1, -2}, {0.25, 0.5, -0.5}};
  EXPECT_EQ(planeSides(F, below, side), -1);
  // One corner on the plane exactly: within rounding, so not certain.
  const Vector3d touching[3] = {{0, 0, 1}, {1, 1, 0}, {0.25, 0.5, 0.5}};
  EXPECT_EQ(planeSides(F, touching, side), 0);
  EXPECT_EQ(side[0], 1);
  EXPECT_EQ(side[1], 0);
  EXPECT_FALSE(allCertain(side));
  // Straddling: certain sides, not all equal.
  const Vector3d straddling[3] = {{0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, 0.1, 1}};
  EXPECT_EQ(planeSides(F, straddling, side), 0);
  EXPECT_TRUE(allCertain(side));
  EXPECT_EQ(loneCorner(side), 0);
}

// Guigue–Devillers: a vertical triangle that pierces the floor triangle meets it; the same
// triangle moved beyond the floor's hypotenuse (x + y = 1) still straddles the plane, so only
// the interval test can drop it.
TEST(TrianglePair, CertainlyDisjointOnlyWhenApart) {
  const PlacedFace F = floorFace();
  const auto check = [&](const PlacedFace& G) {
    int sideG[3], sideF[3];
    EXPECT_EQ(planeSides(F, G.corner, sideG), 0);
    EXPECT_EQ(planeSides(G, F.corner, sideF), 0);
    EXPECT_TRUE(allCertain(sideG) && allCertain(sideF));
    return certainlyDisjoint(G.corner, sideG, F.corner, sideF);
  };
  // In the plane x = 0.25: corners below and above the floor, crossing it at y ∈ [0.125, 0.375].
  const PlacedFace piercing = placedFace({0.25, 0.25, -1}, {0.25, 0.5, 1}, {0.25, 0.0, 1});
  EXPECT_FALSE(check(piercing));
  // The same in the plane x = 0.9375: it crosses z = 0 at y ∈ [0.125, 0.375], beyond x + y = 1.
  const PlacedFace beside = placedFace({0.9375, 0.25, -1}, {0.9375, 0.5, 1}, {0.9375, 0.0, 1});
  EXPECT_TRUE(check(beside));
}

TEST(TrianglePair, BoxTests) {
  const PlacedFace F = floorFace();
  const PlacedFace far = placedFace({2, 0, 0}, {3, 0, 0}, {2, 1, 0});
  EXPECT_FALSE(faceBoxesOverlap(F, far, 0.5));
  EXPECT_TRUE(faceBoxesOverlap(F, far, 1.0));  // grown by 1 the boxes touch at x = 2
  EXPECT_TRUE(boxesOverlap({0, 0, 0}, {1, 1, 1}, {2.5, 0, 0}, {1, 1, 1}, 0.5));
  EXPECT_FALSE(boxesOverlap({0, 0, 0}, {1, 1, 1}, {2.5, 0, 0}, {1, 1, 1}, 0.25));
  // A quarter turn about z maps the box's half-sizes (1, 2, 3) to (2, 1, 3).
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.5 * EIGEN_PI, Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Vector3d(1, 0, 0);
  const auto [center, half] = placedBox(X, Vector3d(1, 0, 0), Vector3d(1, 2, 3));
  EXPECT_LE((center - Vector3d(1, 1, 0)).norm(), 1e-15);  // cos(π/2) rounds to 6e-17
  EXPECT_LE((half - Vector3d(2, 1, 3)).norm(), 1e-15);    // likewise
}

TEST(TrianglePair, SegmentMeetsBox) {
  const Vector3d c(0, 0, 0), h(1, 1, 1);
  EXPECT_TRUE(segmentMeetsBox({-2, 0, 0}, {2, 0, 0}, c, h));       // through
  EXPECT_TRUE(segmentMeetsBox({0, 0, 0}, {5, 5, 5}, c, h));        // from inside
  EXPECT_FALSE(segmentMeetsBox({-2, 0, 0}, {-1.5, 0, 0}, c, h));   // stops short
  EXPECT_FALSE(segmentMeetsBox({-2, 2, 0}, {2, 2, 0}, c, h));      // parallel, outside
  EXPECT_FALSE(segmentMeetsBox({-2, 0.5, 0}, {0.5, 3, 0}, c, h));  // passes the corner by
}

}  // namespace
}  // namespace vcontact::volume::internal
