// The patches of the fast mesh–mesh method (mesh_mesh.hpp, step 5): the components of A ∩ B
// against the exact half-space clip of the same polyhedra (a plate mesh whose top face is the
// plane), with the bodies in either order, and a plate face whose region is a ring.

#include <gtest/gtest.h>

#include <numbers>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/mesh_mesh.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::TriangleMesh;

// Two exact methods on the same polyhedron (cgal_reference_test): 1e-9 in V, 1e-7 relative
// in the centroid (to the body size) and the tensors; both round only the crossing points and
// the sums of terms of the body's size.
constexpr double kVolumeTol = 1e-9;
constexpr double kMomentTol = 1e-7;

struct Body {
  explicit Body(TriangleMesh m) : bvh(std::move(m)), topo(bvh.mesh()) {}
  geometry::MeshBvh bvh;
  geometry::MeshTopology topo;
};

/// A plate of two triangles a face whose top face is z_H = 0 and which holds every foot.
const Body& plate() {
  static const Body b([] {
    TriangleMesh m = geometry::tessellateBox(Vector3d(0.2, 0.2, 0.05));
    m.vertices.rowwise() += Eigen::RowVector3d(0.0, 0.0, -0.025);
    return m;
  }());
  return b;
}

Isometry3d profileUp() {
  return Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
}

void expectSamePatches(const ContactPatches& fast, const ContactPatches& clip, double size) {
  ASSERT_EQ(fast.patches.size(), clip.patches.size());
  for (std::size_t k = 0; k < clip.patches.size(); ++k) {
    const ContactVolume& a = fast.patches[k];
    const ContactVolume& b = clip.patches[k];
    EXPECT_NEAR(a.volume, b.volume, kVolumeTol * b.volume) << k;
    EXPECT_LE((a.centroid - b.centroid).norm(), kMomentTol * size) << k;
    EXPECT_LE(test::relativeDifference(a.J_v, b.J_v), kMomentTol) << k;
    EXPECT_LE((a.normal - b.normal).norm(), kMomentTol) << k;
    EXPECT_NEAR(a.area, b.area, kMomentTol * b.area) << k;
  }
}

// A "U" on its legs pressed into a plate whose top face is two triangles, each holding part of
// both feet: the pieces on one plate face belong to two components, which a face-level union
// would merge. Two patches, equal to the half-space clip's; the bodies swapped give the same
// patches with flipped normals.
TEST(FastMeshMeshPatches, ULegsOnACoarsePlate) {
  const Body u(test::uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123));
  const Isometry3d X_WH = test::randomPose(12);
  const Isometry3d X_WM = X_WH * test::translation({-0.013, 0.004, -0.0031}) * profileUp();
  const ContactPatches clip = meshHalfspacePatches(u.bvh, u.topo, X_WM, X_WH);
  ASSERT_EQ(clip.patches.size(), 2u);
  const ContactPatches ab = meshMeshContact(u.bvh, u.topo, X_WM, plate().bvh, plate().topo, X_WH);
  expectSamePatches(ab, clip, 0.0161);
  const ContactPatches ba = meshMeshContact(plate().bvh, plate().topo, X_WH, u.bvh, u.topo, X_WM);
  expectSamePatches(swapped(ba), clip, 0.0161);
  EXPECT_NEAR(ab.patches[0].volume + ab.patches[1].volume, ab.aggregate.volume,
              1e-12 * ab.aggregate.volume);  // the same pieces summed about two apexes
}

// A cup pressed rim-first into one plate triangle: that face's region is a square ring (an
// outer loop and a hole); the region is one component, as the clip says.
TEST(FastMeshMeshPatches, RingOnOnePlateFace) {
  const Body cup(test::squareCup(0.0131, 0.0093, 0.0217, 0.0041));
  const Isometry3d X_WH = test::randomPose(13);
  const Isometry3d flip(Eigen::AngleAxisd(std::numbers::pi, Vector3d::UnitX()));
  const Isometry3d X_WM = X_WH * test::translation({0.05, -0.05, 0.0217 - 0.0029}) * flip;
  const ContactPatches clip = meshHalfspacePatches(cup.bvh, cup.topo, X_WM, X_WH);
  ASSERT_EQ(clip.patches.size(), 1u);
  const ContactPatches fast =
      meshMeshContact(cup.bvh, cup.topo, X_WM, plate().bvh, plate().topo, X_WH);
  expectSamePatches(fast, clip, 0.0217);
}

}  // namespace
}  // namespace vcontact::volume
