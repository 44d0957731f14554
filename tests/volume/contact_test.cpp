// The dispatcher: each method reaches its backend for the pairs it handles, the bodies can
// come in either order, and unhandled pairs fail with a message naming both shapes.

#include "volume/contact.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "support/test_support.hpp"
#include "volume/bvh_cache.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

geometry::Shape torusShape() {
  return geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(
                            geometry::tessellateTorus(0.021, 0.0071, 48, 16)),
                        "torus"};
}

// Through the dispatcher (cached tree) and directly (reference clip): the same polyhedron,
// 1e-12 for the summation order (halfspace_clip_test bounds it more finely).
TEST(ComputeContact, HalfspaceInEitherOrder) {
  const geometry::Shape torus = torusShape();
  const Isometry3d X_WH = test::randomPose(3);
  const Isometry3d X_WM = X_WH * test::translation({0.001, 0.0, 0.0071 - 0.002});
  const auto& mesh = *std::get<geometry::Mesh>(torus).mesh;
  const ContactVolume ref = meshHalfspaceContact(mesh, X_WM, X_WH);
  const ContactVolume ab = computeContact(torus, X_WM, geometry::HalfSpace{}, X_WH);
  const ContactVolume ba = computeContact(geometry::HalfSpace{}, X_WH, torus, X_WM);
  ASSERT_GT(ref.volume, 0.0);
  EXPECT_EQ(ab.method, Method::kHalfspace);
  EXPECT_NEAR(ab.volume, ref.volume, 1e-12 * ref.volume);
  EXPECT_NEAR(ba.volume, ref.volume, 1e-12 * ref.volume);
  EXPECT_LE((ab.normal - X_WH.linear().col(2)).norm(), 1e-15);
  EXPECT_LE((ba.normal + X_WH.linear().col(2)).norm(), 1e-15);
}

// Two meshes default to fast (exact, mesh_mesh_test checks it against cgal); cgal and
// columns agree within twice the columns' own estimate (the bound columns_test justifies).
TEST(ComputeContact, MeshPairMethods) {
  const geometry::Shape peg = geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(
                                                 geometry::tessellateCylinder(0.0052, 0.03, 40)),
                                             "peg"};
  const geometry::Shape ring =
      geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(
                         geometry::tessellateTorus(0.0111, 0.0061, 40, 16)),
                     "ring"};
  const Isometry3d X_WP = test::translation({0.0004, 0.0, 0.003});
  EXPECT_EQ(defaultMethod(peg, ring), Method::kFast);
  const ContactVolume col =
      computeContact(peg, X_WP, ring, Isometry3d::Identity(), Method::kColumns);
  const ContactVolume cgal = computeContact(peg, X_WP, ring, Isometry3d::Identity(), Method::kCgal);
  ASSERT_GT(cgal.volume, 0.0);
  EXPECT_EQ(col.method, Method::kColumns);
  EXPECT_EQ(cgal.method, Method::kCgal);
  EXPECT_NEAR(col.volume, cgal.volume, 2.0 * col.relative_error * cgal.volume);
}

TEST(ComputeContact, UnhandledPairsNameBothShapes) {
  const geometry::Shape torus = torusShape();
  const Isometry3d I = Isometry3d::Identity();
  try {
    computeContact(torus, I, geometry::HalfSpace{}, I, Method::kFast);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("torus"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--method fast"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      computeContact(geometry::Sphere{0.01}, I, geometry::HalfSpace{}, I, Method::kColumns),
      InputError);
  EXPECT_THROW(computeContact(geometry::Sphere{0.01}, I, torus, I, Method::kCgal), InputError);
}

// handles() is what the readers check before a run; it must say exactly what a query does:
// every method against every pair of shape kinds, both orders, a query throws InputError iff
// handles() says no (and requireHandles throws then too). The shapes are apart, so the
// queries that run are cheap.
TEST(ComputeContact, HandlesSaysWhatTheQueryDoes) {
  const std::vector<geometry::Shape> shapes = {
      geometry::Sphere{0.01}, geometry::Cylinder{0.01, 0.02},
      geometry::Box{Vector3d(0.01, 0.02, 0.03)}, geometry::HalfSpace{}, torusShape()};
  const Isometry3d far = test::translation({0.0, 0.0, 0.5});
  int handled = 0;
  for (Method m :
       {Method::kAnalytic, Method::kHalfspace, Method::kCgal, Method::kFast, Method::kColumns}) {
    for (const auto& a : shapes) {
      for (const auto& b : shapes) {
        const std::string what =
            methodName(m) + ": " + geometry::describe(a) + " against " + geometry::describe(b);
        bool queried = true;
        try {
          computeContact(a, far, b, Isometry3d::Identity(), m);
        } catch (const InputError&) {
          queried = false;
        }
        EXPECT_EQ(handles(m, a, b), queried) << what;
        if (queried) {
          EXPECT_NO_THROW(requireHandles(m, a, b)) << what;
          ++handled;
        } else {
          EXPECT_THROW(requireHandles(m, a, b), InputError) << what;
        }
      }
    }
  }
  // analytic 6, halfspace 2, cgal 3, fast 1, columns 3 (two half-spaces are no pair for it).
  EXPECT_EQ(handled, 15);
}

// The tree is built once per mesh and shared.
TEST(BvhCache, SameMeshSameTree) {
  const auto mesh = std::make_shared<const geometry::TriangleMesh>(
      geometry::tessellateBox(Vector3d(0.01, 0.02, 0.03)));
  EXPECT_EQ(bvhOf(mesh).get(), bvhOf(mesh).get());
  const auto other = std::make_shared<const geometry::TriangleMesh>(*mesh);
  EXPECT_NE(bvhOf(mesh).get(), bvhOf(other).get());
}

}  // namespace
}  // namespace vcontact::volume
