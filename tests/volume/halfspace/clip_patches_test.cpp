// The patches of a mesh on a half-space (meshHalfspacePatches): the connected components of
// the clipped solid against their closed forms, joined through the cap where the surface
// alone does not connect them, and the aggregate left as the accelerated clip computes it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/kernels/mesh_convexity.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::MeshBvh;
using geometry::MeshTopology;
using geometry::TriangleMesh;
using test::twoShells;
using test::uPrism;
using test::UProfile;

// Per-patch closed forms of boxes are exact for the polyhedron; 1e-12 covers the rounding of
// sums of a few hundred fan terms of the body's size each against a region of its size.
constexpr double kClosedFormTol = 1e-12;

/// A mesh with its tree and topology, as the dispatcher would hold them.
struct Body {
  explicit Body(TriangleMesh m) : mesh(std::move(m)), bvh(mesh), topo(mesh) {}
  TriangleMesh mesh;
  MeshBvh bvh;
  MeshTopology topo;
};

/// Rotation taking a prism's profile y axis to +z (its extrusion z to −y).
Isometry3d profileUp() {
  return Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
}

double totalVolume(const ContactPatches& c) {
  double V = 0.0;
  for (const ContactVolume& p : c.patches) V += p.volume;
  return V;
}

void expectSumIsAggregate(const ContactPatches& c) {
  EXPECT_NEAR(totalVolume(c), c.aggregate.volume, kClosedFormTol * c.aggregate.volume);
}

// A "U" on its legs pressed d into the plane: each leg's foot is a box w·d·t, centred under the
// leg at depth d/2, with n = z_H. The legs differ in width, so the larger leads (sortPatches).
// Re-run under a random plane pose with dimensions not representable in binary.
TEST(HalfspacePatches, ULegsAreTwoBoxPatches) {
  const UProfile u{0.0107, 0.0213, 0.0071, 0.0093, 0.0161};
  const double t = 0.0123, d = 0.0031;
  const Body body(uPrism(u, t));
  for (unsigned seed : {0u, 4u}) {
    const Isometry3d X_WH = seed ? test::randomPose(seed) : Isometry3d::Identity();
    const Isometry3d X_WM = X_WH * test::translation({0, 0, -d}) * profileUp();
    const ContactPatches c = meshHalfspacePatches(body.bvh, body.topo, X_WM, X_WH);
    ASSERT_EQ(c.patches.size(), 2u);
    const double legX[2] = {0.5 * u.leftLeg, u.leftLeg + u.gap + 0.5 * u.rightLeg};
    const double legW[2] = {u.leftLeg, u.rightLeg};
    for (int k = 0; k < 2; ++k) {
      const ContactVolume& p = c.patches[static_cast<std::size_t>(k)];
      const Vector3d p_Hc(legX[k], -0.5 * t, -0.5 * d);
      EXPECT_NEAR(p.volume, legW[k] * t * d, kClosedFormTol * legW[k] * t * d);
      EXPECT_LE((p.p_WC - X_WH * p_Hc).norm(), kClosedFormTol * u.height);
      EXPECT_NEAR(p.depth, d, kClosedFormTol * u.height);
      EXPECT_NEAR(p.area, legW[k] * t, kClosedFormTol * legW[k] * t);
      EXPECT_LE((p.n_W - X_WH.linear().col(2)).norm(), kClosedFormTol);
    }
    expectSumIsAggregate(c);
  }
}

// The aggregate is the accelerated clip, to the bit, whether the query splits or not.
TEST(HalfspacePatches, AggregateIsTheClip) {
  const Body body(uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123));
  const Isometry3d X_WH = test::randomPose(3);
  for (double d : {0.0031, 0.0121}) {  // the legs alone; legs and bridge
    const Isometry3d X_WM = X_WH * test::translation({0, 0, -d}) * profileUp();
    const ContactPatches c = meshHalfspacePatches(body.bvh, body.topo, X_WM, X_WH);
    const ContactVolume clip = meshHalfspaceContact(body.bvh, X_WM, X_WH);
    EXPECT_EQ(c.aggregate.volume, clip.volume);
    EXPECT_EQ(c.aggregate.p_WC, clip.p_WC);
    EXPECT_EQ(c.aggregate.J_s, clip.J_s);
    EXPECT_EQ(c.patches.size(), d < 0.0093 ? 2u : 1u);
    expectSumIsAggregate(c);
  }
}

// A one-shell mesh whose cap is one loop is one patch: the aggregate itself, to the bit.
TEST(HalfspacePatches, OneLoopIsTheAggregate) {
  const Body body(geometry::tessellateSphere(0.0113, 48, 24));
  const Isometry3d X_WH = test::randomPose(5);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, 0.0113 - 0.0017});
  const ContactPatches c = meshHalfspacePatches(body.bvh, body.topo, X_WM, X_WH);
  ASSERT_EQ(c.patches.size(), 1u);
  EXPECT_EQ(c.patches[0].volume, c.aggregate.volume);
  EXPECT_EQ(c.patches[0].J_v, c.aggregate.J_v);
}

/// The square cup of the cup tests, lowered by d through its walls (floor < d < h).
struct CupCase {
  double a = 0.0131, b = 0.0093, h = 0.0217, floor = 0.0041, d = 0.0113;
  TriangleMesh mesh() const { return test::squareCup(a, b, h, floor); }
  /// V below the plane: the outer block less the pocket, 4a²d − 4b²(d − floor).
  double volume() const { return 4 * a * a * d - 4 * b * b * (d - floor); }
  /// Its patches with the plane at pose X_WH and the mesh lowered by d in it.
  ContactPatches patches(const Body& body, const Isometry3d& X_WH) const {
    return meshHalfspacePatches(body.bvh, body.topo, X_WH * test::translation({0, 0, -d}), X_WH);
  }
};

// A square cup cut through its walls: its outer surface and its pocket below the plane meet
// only at the annular cap (two loops, one region): one patch of the closed-form V.
TEST(HalfspacePatches, CupCutThroughItsWallsIsOnePatch) {
  const CupCase cup;
  const ContactPatches c = cup.patches(Body(cup.mesh()), test::randomPose(6));
  ASSERT_EQ(c.patches.size(), 1u);
  EXPECT_NEAR(c.patches[0].volume, cup.volume(), kClosedFormTol * cup.volume());
  expectSumIsAggregate(c);
}

// The same cup beside a box in one mesh (two shells, so the labelled path): the cup's
// outer and pocket walls join through its cap, the box, wholly below, is the other patch.
TEST(HalfspacePatches, CupBesideABoxJoinsThroughItsCap) {
  const CupCase cup;
  const double s = 0.0101;  // < d: the box ends below the plane
  TriangleMesh box = geometry::tessellateBox(Vector3d(s, s, s));
  box.vertices.rowwise() += Eigen::RowVector3d(0.05, 0, 0.5 * s);  // on z = 0, like the cup
  const ContactPatches c = cup.patches(Body(twoShells(cup.mesh(), box)), test::randomPose(19));
  ASSERT_EQ(c.patches.size(), 2u);
  EXPECT_NEAR(c.patches[0].volume, cup.volume(), kClosedFormTol * cup.volume());
  EXPECT_NEAR(c.patches[1].volume, s * s * s, kClosedFormTol * s * s * s);
  expectSumIsAggregate(c);
}

// A torus standing on edge, cut above its centre: two loops, two cap regions, joined through
// the bottom of the ring's surface: one patch.
TEST(HalfspacePatches, RingCutAboveItsCentreIsOnePatch) {
  const double R = 0.0211, r = 0.0071;
  const Body body(geometry::tessellateTorus(R, r, 48, 16));
  const Isometry3d X_WH = test::randomPose(6);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, -0.0037}) * profileUp();
  const ContactPatches c = meshHalfspacePatches(body.bvh, body.topo, X_WM, X_WH);
  ASSERT_EQ(c.patches.size(), 1u);
  expectSumIsAggregate(c);
  EXPECT_LE((c.patches[0].p_WC - c.aggregate.p_WC).norm(), kClosedFormTol * R);
}

// Two boxes in one mesh, one crossing the plane and one wholly below it: two patches, the
// submerged one the whole box (its shell has no cap at all).
TEST(HalfspacePatches, ShellWhollyBelowIsItsOwnPatch) {
  const double s = 0.0103, d = 0.0029;
  TriangleMesh crossing = geometry::tessellateBox(Vector3d(s, s, s));
  TriangleMesh submerged = geometry::tessellateBox(Vector3d(s, s, s));
  crossing.vertices.rowwise() += Eigen::RowVector3d(0, 0, 0.5 * s - d);
  submerged.vertices.rowwise() += Eigen::RowVector3d(3 * s, 0, -s);
  const Body body(twoShells(crossing, submerged));
  const Isometry3d X_WH = test::randomPose(8);
  const ContactPatches c = meshHalfspacePatches(body.bvh, body.topo, X_WH, X_WH);
  ASSERT_EQ(c.patches.size(), 2u);
  EXPECT_NEAR(c.patches[0].volume, s * s * s, kClosedFormTol * s * s * s);
  EXPECT_NEAR(c.patches[1].volume, s * s * d, kClosedFormTol * s * s * d);
  EXPECT_LE((c.patches[0].p_WC - X_WH * Vector3d(3 * s, 0, -s)).norm(), kClosedFormTol * s);
  EXPECT_NEAR(c.patches[1].depth, d, kClosedFormTol * s);
  expectSumIsAggregate(c);
}

// The bodies swapped (half-space as B1): the same patches with their normals flipped.
TEST(HalfspacePatches, EitherOrderThroughTheBackend) {
  const auto mesh = std::make_shared<const TriangleMesh>(
      uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123));
  const geometry::Shape shape = geometry::Mesh{mesh, "U"};
  const geometry::Shape plane = geometry::HalfSpace{};
  const Isometry3d X_WH = test::randomPose(9);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, -0.0031}) * profileUp();
  const ContactPatches ab = halfspaceClipContact(shape, X_WM, plane, X_WH);
  const ContactPatches ba = halfspaceClipContact(plane, X_WH, shape, X_WM);
  ASSERT_EQ(ab.patches.size(), 2u);
  ASSERT_EQ(ba.patches.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(ab.patches[k].volume, ba.patches[k].volume);
    EXPECT_EQ(ab.patches[k].n_W, -ba.patches[k].n_W);
  }
}

// Convex meshes skip the patch labels; every concave edge or second shell disqualifies.
TEST(HalfspacePatches, ConvexityOfTheFixtures) {
  const TriangleMesh box = geometry::tessellateBox(Vector3d(0.01, 0.02, 0.03));
  EXPECT_TRUE(MeshConvexity(geometry::tessellateSphere(0.01, 24, 12)).convex);
  EXPECT_TRUE(MeshConvexity(box).convex);
  EXPECT_FALSE(MeshConvexity(uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123)).convex);
  EXPECT_FALSE(MeshConvexity(test::squareCup(0.0131, 0.0093, 0.0217, 0.0041)).convex);
  EXPECT_FALSE(MeshConvexity(twoShells(box, box)).convex);
  TriangleMesh open = box;
  open.triangles.conservativeResize(10, 3);
  EXPECT_FALSE(MeshConvexity(open).convex);
}

}  // namespace
}  // namespace vcontact::volume
