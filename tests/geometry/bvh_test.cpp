// The bounding-volume hierarchy (geometry/bvh.hpp): structural invariants that every query
// relies on (each triangle in exactly one leaf, children partitioning their parent, boxes and
// slabs bounding their triangles), on meshes of uniform and of very mixed triangle sizes, and
// the property the surface-area split is there for: large flat faces are not mixed into the
// leaves of a small, finely faceted feature next to them.

#include "geometry/bvh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/tessellate.hpp"

namespace vcontact::geometry {
namespace {

using Eigen::Vector3d;

// Box and slab bounds are computed from the same doubles they bound, through a centre
// 0.5 (lo + hi) and a difference with it: a few roundings of the mesh's coordinates.
constexpr double kBoundRounding = 1e-14;

/// Both meshes as one (two closed components), B's triangles after A's.
TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b, const Vector3d& offsetB) {
  TriangleMesh m;
  m.vertices.resize(a.vertexCount() + b.vertexCount(), 3);
  m.vertices << a.vertices, (b.vertices.rowwise() + offsetB.transpose());
  m.triangles.resize(a.triangleCount() + b.triangleCount(), 3);
  m.triangles << a.triangles, (b.triangles.array() + static_cast<int>(a.vertexCount())).matrix();
  return m;
}

/// A 40 x 40 x 2 mm plate (12 triangles) with a 1 mm sphere of about 1,000 triangles resting
/// above its centre: a CAD part's flat face beside a finely faceted pin.
TriangleMesh plateWithBead() {
  return joined(tessellateBox(Vector3d(0.04, 0.04, 0.002)), tessellateSphere(0.001, 32, 17),
                Vector3d(0.0, 0.0, 0.0025));
}

double sizeOf(const TriangleMesh& m) { return bounds(m).size().norm(); }

void expectStructure(const MeshBvh& bvh, int maxLeafSize) {
  const TriangleMesh& mesh = bvh.mesh();
  const auto& nodes = bvh.nodes();
  const auto n = static_cast<int>(mesh.triangleCount());
  const double tol = kBoundRounding * sizeOf(mesh);

  std::vector<int> sorted = bvh.order();
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(static_cast<std::size_t>(n));
  std::iota(identity.begin(), identity.end(), 0);
  ASSERT_EQ(sorted, identity) << "order() is not a permutation of the triangles";
  ASSERT_EQ(bvh.root().first, 0);
  ASSERT_EQ(bvh.root().count, n);

  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const BvhNode& node = nodes[i];
    SCOPED_TRACE("node " + std::to_string(i));
    ASSERT_GE(node.count, 1);
    if (node.isLeaf()) {
      EXPECT_LE(node.count, maxLeafSize);
    } else {
      EXPECT_GT(node.count, maxLeafSize);
      const BvhNode& left = nodes[static_cast<std::size_t>(node.left)];
      const BvhNode& right = nodes[static_cast<std::size_t>(node.right)];
      EXPECT_EQ(left.first, node.first);
      EXPECT_EQ(right.first, left.first + left.count);
      EXPECT_EQ(left.count + right.count, node.count);
    }
    for (int j = node.first; j < node.first + node.count; ++j) {
      const int f = bvh.order()[static_cast<std::size_t>(j)];
      for (int k = 0; k < 3; ++k) {
        const Vector3d r = mesh.corner(f, k) - node.center;
        EXPECT_TRUE((r.cwiseAbs().array() <= node.halfExtent.array() + tol).all());
        const double s = r.dot(node.normalAxis);
        EXPECT_GE(s, node.axialLo - tol);
        EXPECT_LE(s, node.axialHi + tol);
        EXPECT_LE((r - s * node.normalAxis).norm(), node.radialExtent + tol);
      }
    }
  }
}

TEST(MeshBvh, StructureOfUniformSphere) {
  for (int leaf : {1, 4, 8}) {
    SCOPED_TRACE("maxLeafSize " + std::to_string(leaf));
    expectStructure(MeshBvh(tessellateSphere(0.01, 40, 21), leaf), leaf);
  }
}

TEST(MeshBvh, StructureOfMixedSizes) {
  expectStructure(MeshBvh(plateWithBead()), MeshBvh::kDefaultLeafSize);
  expectStructure(MeshBvh(plateWithBead(), 4), 4);
}

TEST(MeshBvh, CoincidentCentroidsStillSplit) {
  // Eight coincident copies of one sphere: every centroid occurs eight times, so a node of
  // up to eight triangles may have no plane between its centroids. The split falls back to
  // the median and the build terminates with leaves of at most maxLeafSize.
  const TriangleMesh one = tessellateSphere(0.01, 8, 5);
  TriangleMesh m = one;
  for (int copy = 1; copy < 8; ++copy) m = joined(m, one, Vector3d::Zero());
  expectStructure(MeshBvh(m, 4), 4);
}

TEST(MeshBvh, FlatFaceIsNotMixedIntoFeatureLeaves) {
  // The plate's 12 triangles span 40 mm; the bead's are about 0.2 mm. A leaf holding both
  // has a box the size of the plate, and any query near the bead would test the plate's
  // triangles at every one of the bead's leaves. A median split does this (the widest
  // centroid axis runs across the plate and the median falls inside the bead).
  const TriangleMesh mesh = plateWithBead();
  const int plateTriangles = 12;
  for (const int leaf : {4, MeshBvh::kDefaultLeafSize}) {
    SCOPED_TRACE("maxLeafSize " + std::to_string(leaf));
    const MeshBvh bvh(mesh, leaf);
    int mixedLeaves = 0, beadLeaves = 0;
    for (const BvhNode& node : bvh.nodes()) {
      if (!node.isLeaf()) continue;
      int plate = 0;
      for (int j = node.first; j < node.first + node.count; ++j) {
        plate += bvh.order()[static_cast<std::size_t>(j)] < plateTriangles ? 1 : 0;
      }
      mixedLeaves += (plate > 0 && plate < node.count) ? 1 : 0;
      beadLeaves += plate == 0 ? 1 : 0;
    }
    EXPECT_GT(beadLeaves, 800 / leaf);
    EXPECT_EQ(mixedLeaves, 0);
  }
}

}  // namespace
}  // namespace vcontact::geometry
