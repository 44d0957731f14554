// The FCL broad phase against brute-force box overlap, before and after bodies move.

#include "geometry/broad_phase.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "geometry/tessellate.hpp"

namespace vcontact::geometry {
namespace {

using Eigen::Vector3d;

bool overlap(const Aabb& a, const Aabb& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

std::vector<std::pair<int, int>> bruteForce(const std::vector<Aabb>& boxes) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < int(boxes.size()); ++i) {
    for (int j = i + 1; j < int(boxes.size()); ++j) {
      if (overlap(boxes[i], boxes[j])) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

Aabb randomBox(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(0.0, 1.0), size(0.01, 0.2);
  const Vector3d lo(pos(rng), pos(rng), pos(rng));
  return {lo, lo + Vector3d(size(rng), size(rng), size(rng))};
}

TEST(BroadPhase, MatchesBruteForceBeforeAndAfterMotion) {
  std::mt19937 rng(7);
  std::vector<Aabb> boxes;
  BroadPhase bp;
  for (int i = 0; i < 60; ++i) {
    boxes.push_back(randomBox(rng));
    EXPECT_EQ(bp.add(boxes.back()), i);
  }
  const auto before = bruteForce(boxes);
  ASSERT_FALSE(before.empty());  // the case must exercise some overlaps
  EXPECT_EQ(bp.overlappingPairs(), before);
  for (int i = 0; i < 60; i += 3) {
    boxes[i] = randomBox(rng);
    bp.update(i, boxes[i]);
  }
  EXPECT_EQ(bp.overlappingPairs(), bruteForce(boxes));
}

TEST(BroadPhase, MeshBoundsFollowThePose) {
  const TriangleMesh box = tessellateBox(Vector3d(0.2, 0.1, 0.05));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Vector3d(1.0, 2.0, 3.0);
  const Aabb b = worldBounds(box, X);
  // Rotated a quarter turn about z, the 0.2 × 0.1 footprint becomes 0.1 × 0.2.
  EXPECT_LE((b.min - Vector3d(0.95, 1.9, 2.975)).norm(), 1e-15);
  EXPECT_LE((b.max - Vector3d(1.05, 2.1, 3.025)).norm(), 1e-15);
}

/// Is every point of `points` placed by X inside `box`?
bool holds(const Aabb& box, const TriangleMesh& points, const Eigen::Isometry3d& X) {
  for (Eigen::Index i = 0; i < points.vertexCount(); ++i) {
    const Vector3d p = X * points.vertex(i);
    if ((p.array() < box.min.array()).any() || (p.array() > box.max.array()).any()) return false;
  }
  return true;
}

// The simulator's broad phase places each shape's own bounds by its pose (O(1) per body): the
// placed box must hold the shape at any pose (a pair left out would lose a contact), and at the
// identity it must be the shape's own box up to the growth (a loose box would only cost queries,
// but it would hide a wrong extent). Points on the shapes' surfaces: the vertices of fine
// tessellations, which lie on the exact surfaces.
TEST(BroadPhase, PlacedBoundsHoldTheShapeAtAnyPose) {
  struct Case {
    Shape shape;
    TriangleMesh surface;
  };
  auto mesh = std::make_shared<const TriangleMesh>(tessellateTorus(0.03, 0.01, 48, 24));
  const std::vector<Case> cases = {
      {Sphere{0.02}, tessellateSphere(0.02, 64, 32)},
      {Cylinder{0.01, 0.05}, tessellateCylinder(0.01, 0.05, 64)},
      {Box{Vector3d(0.1, 0.02, 0.03)}, tessellateBox(Vector3d(0.1, 0.02, 0.03))},
      {Mesh{mesh, "torus"}, *mesh}};
  for (const Case& c : cases) {
    SCOPED_TRACE(describe(c.shape));
    const std::optional<Aabb> local = localBounds(c.shape);
    ASSERT_TRUE(local.has_value());
    const Aabb atOrigin = placedBounds(*local, Eigen::Isometry3d::Identity());
    const Aabb exact = bounds(c.surface);
    // The tessellation's vertices lie on the surface, to a few ulps of a ~1e-2 m size.
    EXPECT_LE((atOrigin.min - exact.min).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LE((atOrigin.max - exact.max).cwiseAbs().maxCoeff(), 1e-10);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 50; ++k) {
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      const Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
      X.linear() = q.normalized().toRotationMatrix();
      X.translation() = Vector3d(u(rng), u(rng), u(rng)) * 10.0;
      EXPECT_TRUE(holds(placedBounds(*local, X), c.surface, X)) << "pose " << k;
    }
  }
  EXPECT_FALSE(localBounds(HalfSpace{}).has_value());
}

}  // namespace
}  // namespace vcontact::geometry
