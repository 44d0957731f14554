// The patches of the fast mesh–mesh method (fast/surface_integration.hpp, step 5): the components
// of A ∩ B against the exact half-space clip of the same polyhedra (a plate mesh whose top face is
// the plane), with the bodies in either order, and a plate face whose region is a ring.

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/cgal/corefinement.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::TriangleMesh;

// Two exact methods on the same polyhedron (cgal_corefinement_test): 1e-9 in V, 1e-7 relative
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
  static const Body b(test::plateTopAtZero());
  return b;
}

Isometry3d profileUp() {
  return Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
}

/// The patch of `list` whose centroid is nearest to that of `p` (the tests match patches
/// across methods by place: equal volumes may sort either way by rounding).
const ContactVolume& nearest(const std::vector<ContactVolume>& list, const ContactVolume& p) {
  return *std::min_element(list.begin(), list.end(), [&p](const auto& x, const auto& y) {
    return (x.p_WC - p.p_WC).norm() < (y.p_WC - p.p_WC).norm();
  });
}

void expectSamePatches(const ContactPatches& fast, const ContactPatches& clip, double size) {
  ASSERT_EQ(fast.patches.size(), clip.patches.size());
  for (std::size_t k = 0; k < clip.patches.size(); ++k) {
    const ContactVolume& b = clip.patches[k];
    const ContactVolume& a = nearest(fast.patches, b);
    EXPECT_NEAR(a.volume, b.volume, kVolumeTol * b.volume) << k;
    EXPECT_LE((a.p_WC - b.p_WC).norm(), kMomentTol * size) << k;
    EXPECT_LE(test::relativeDifference(a.J_v, b.J_v), kMomentTol) << k;
    EXPECT_LE((a.n_W - b.n_W).norm(), kMomentTol) << k;
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

// A round peg tilted in a hole with 0.2 mm clearance, longer than the hole: it bears on the
// hole's wall near the top on one side and near the bottom on the other (two-point contact).
// Two patches on opposite walls, with opposite in-plane normals; fast agrees with cgal.
TEST(FastMeshMeshPatches, TiltedPegBearsOnOppositeWalls) {
  const Body hole(test::tube(0.0203, 0.0101, 0.0203, 64));
  const Body peg(geometry::tessellateCylinder(0.0099, 0.0407, 64));
  const Isometry3d X_WH = test::randomPose(15);
  const Isometry3d X_WP = X_WH * Isometry3d(Eigen::AngleAxisd(0.03, Vector3d::UnitX()));
  const ContactPatches fast = meshMeshContact(peg.bvh, peg.topo, X_WP, hole.bvh, hole.topo, X_WH);
  const ContactPatches cgal = cgalMeshMeshContact(peg.bvh.mesh(), X_WP, hole.bvh.mesh(), X_WH);
  ASSERT_EQ(fast.patches.size(), 2u);
  expectSamePatches(fast, cgal, 0.0203);
  const Vector3d axis_W = X_WP.linear().col(2);
  const Vector3d& n0 = fast.patches[0].n_W;
  const Vector3d& n1 = fast.patches[1].n_W;
  EXPECT_LT(n0.dot(n1), -0.99);  // opposite, up to the facets and the 0.03 rad tilt
  EXPECT_LT(std::abs(n0.dot(axis_W)), 0.05);
  // the two centroids lie on either side of the hole's centre along the axis
  EXPECT_LT((fast.patches[0].p_WC - X_WH.translation()).dot(X_WH.linear().col(2)) *
                (fast.patches[1].p_WC - X_WH.translation()).dot(X_WH.linear().col(2)),
            0.0);
}

// Two spheres of one body (a dumbbell's ends, two shells) pressed into a plate: each patch is
// the exact clip of its sphere alone by the plate's top plane.
TEST(FastMeshMeshPatches, DumbbellEndsMatchEachSphereAlone) {
  const double R = 0.0103, d = 0.0017, half = 0.031;
  const auto [left, right] = test::dumbbellEnds(R, half);
  const Body dumbbell(test::twoShells(left, right));
  const Body leftAlone(left), rightAlone(right);
  const Isometry3d X_WH = test::randomPose(16);
  const Isometry3d X_WM = X_WH * test::translation({0.004, -0.007, R - d});
  const ContactPatches fast =
      meshMeshContact(dumbbell.bvh, dumbbell.topo, X_WM, plate().bvh, plate().topo, X_WH);
  ContactPatches alone;
  for (const Body* b : {&leftAlone, &rightAlone}) {
    alone.patches.push_back(meshHalfspacePatches(b->bvh, b->topo, X_WM, X_WH).aggregate);
  }
  expectSamePatches(fast, alone, R);
}

// A keyed shaft turned by 0.03 rad in a hub of four blocks, one beside the leading flank of
// each key with 0.2 mm clearance: one patch per flank, with tangential normals (across the
// flank, neither radial nor axial); cgal finds the same four components.
TEST(FastMeshMeshPatches, KeyedShaftTurnedInItsHub) {
  const double a = 0.0041, L = 0.0149, gap = 0.0002, w = 0.0051;
  const Body shaft(test::keyedShaft(a, L, 0.0203));
  const Body hub(test::keyedHub(a, gap, w));
  const Isometry3d X_WH = test::randomPose(17);
  const Isometry3d X_WS = X_WH * Isometry3d(Eigen::AngleAxisd(0.03, Vector3d::UnitZ()));
  // with the exact depth pass (`deepest`), whose depths are checked below
  const ContactPatches fast =
      meshMeshContact(shaft.bvh, shaft.topo, X_WS, hub.bvh, hub.topo, X_WH, nullptr, true);
  const ContactPatches cgal = cgalMeshMeshContact(shaft.bvh.mesh(), X_WS, hub.bvh.mesh(), X_WH);
  ASSERT_EQ(fast.patches.size(), 4u);
  expectSamePatches(fast, cgal, L);
  const Vector3d axis_W = X_WH.linear().col(2);
  for (const ContactVolume& p : fast.patches) {
    // the key's own direction (of the four quarter turns of the shaft's x axis, the one
    // nearest the patch): the flank's normal is across it
    const Vector3d p_S = X_WS.inverse() * p.p_WC;
    const Vector3d key_S =
        std::abs(p_S.x()) > std::abs(p_S.y()) ? Vector3d::UnitX() : Vector3d::UnitY();
    EXPECT_LT(std::abs(p.n_W.dot(X_WS.linear() * key_S)), 0.05);     // the hub is 0.03 rad off
    EXPECT_LT(std::abs(p.n_W.dot(axis_W)), 1e-9);                    // flanks parallel to the axis
    EXPECT_NEAR(p.volume, fast.patches[0].volume, 1e-9 * p.volume);  // four-fold symmetry
    // Deepest penetration along the patch's n, the flank's normal: the region is a prism over
    // a right triangle whose hypotenuse is the flank, and its longest column is the altitude
    // onto it, (x_f − x_1) sin φ, with x_1 where the flank meets the block's face y = a + gap
    // and x_f the block's far end (depth_test.cpp, KeyFlankInAHubBlock). Two exact methods:
    // 1e-9. The merged region's depth, along one normal for four flanks, is larger.
    const double phi = 0.03, t = (a + gap - a * std::cos(phi)) / std::sin(phi);
    const double x1 = t * std::cos(phi) - a * std::sin(phi), xf = 0.0101 + 0.00355;
    const double deepest = (xf - x1) * std::sin(phi);
    EXPECT_NEAR(p.depth, deepest, 1e-9 * deepest);
    EXPECT_GT(fast.aggregate.depth, 2 * p.depth);
  }
}

}  // namespace
}  // namespace vcontact::volume
