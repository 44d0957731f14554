// The dispatcher: each method reaches its backend for the pairs it handles, the bodies can
// come in either order, and unhandled pairs fail with a message naming both shapes.

#include "volume/contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "support/test_support.hpp"
#include "volume/columns/columns.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/kernels/bvh_cache.hpp"
#include "volume/methods.hpp"
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
  const ContactVolume ab = computeContact(torus, X_WM, geometry::HalfSpace{}, X_WH).aggregate;
  const ContactVolume ba = computeContact(geometry::HalfSpace{}, X_WH, torus, X_WM).aggregate;
  ASSERT_GT(ref.volume, 0.0);
  EXPECT_EQ(ab.method, Method::kHalfspace);
  EXPECT_NEAR(ab.volume, ref.volume, 1e-12 * ref.volume);
  EXPECT_NEAR(ba.volume, ref.volume, 1e-12 * ref.volume);
  // The normal is z_H itself (MODEL.md §1: the half-space's): copied, or negated, exactly.
  EXPECT_LE((ab.n_W - X_WH.linear().col(2)).norm(), 1e-15);
  EXPECT_LE((ba.n_W + X_WH.linear().col(2)).norm(), 1e-15);
}

// Two meshes default to fast (exact, fast_surface_integration_test checks it against cgal); cgal
// and columns agree within twice the columns' own estimate (the bound columns_test justifies).
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
      computeContact(peg, X_WP, ring, Isometry3d::Identity(), {Method::kColumns}).aggregate;
  const ContactVolume cgal =
      computeContact(peg, X_WP, ring, Isometry3d::Identity(), {Method::kCgal}).aggregate;
  ASSERT_GT(cgal.volume, 0.0);
  EXPECT_EQ(col.method, Method::kColumns);
  EXPECT_EQ(cgal.method, Method::kCgal);
  EXPECT_NEAR(col.volume, cgal.volume, 2.0 * col.relative_error * cgal.volume);
}

TEST(ComputeContact, UnhandledPairsNameBothShapes) {
  const geometry::Shape torus = torusShape();
  const Isometry3d I = Isometry3d::Identity();
  try {
    computeContact(torus, I, geometry::HalfSpace{}, I, {Method::kFast});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("torus"), std::string::npos) << what;
    EXPECT_EQ(e.source(), "volume method fast") << what;  // the quantity, never a CLI flag
    EXPECT_NE(what.find("; it intersects two meshes"), std::string::npos) << what;
  }
  EXPECT_THROW(
      computeContact(geometry::Sphere{0.01}, I, geometry::HalfSpace{}, I, {Method::kColumns}),
      InputError);
  EXPECT_THROW(computeContact(geometry::Sphere{0.01}, I, torus, I, {Method::kCgal}), InputError);
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
  ASSERT_FALSE(methodTable().empty());
  for (const MethodRow& row : methodTable()) {
    int handled = 0;
    for (const auto& a : shapes) {
      for (const auto& b : shapes) {
        const std::string what = std::string(row.name) + ": " + geometry::describe(a) +
                                 " against " + geometry::describe(b);
        bool queried = true;
        try {
          computeContact(a, far, b, Isometry3d::Identity(), {row.id});
        } catch (const InputError&) {
          queried = false;
        }
        EXPECT_EQ(row.handles(a, b), queried) << what;
        EXPECT_EQ(handles(row.id, a, b), queried) << what;
        EXPECT_EQ(row.handles(b, a), queried) << what << " (either order)";
        if (queried) {
          EXPECT_NO_THROW(requireHandles(row.id, a, b)) << what;
          ++handled;
        } else {
          EXPECT_THROW(requireHandles(row.id, a, b), InputError) << what;
        }
      }
    }
    EXPECT_GT(handled, 0) << row.name << " takes no pair of the five shape kinds";
  }
}

// The table maps each method once: its name parses back to it, a query reports it, and an
// unknown name is refused naming every method of the table.
TEST(MethodTable, NamesRoundTrip) {
  std::string all;
  for (const MethodRow& row : methodTable()) {
    EXPECT_EQ(methodName(row.id), row.name);
    EXPECT_EQ(parseMethod(std::string(row.name)), row.id);
    EXPECT_EQ(&methodRow(row.id), &row);
  }
  const std::string msg = test::inputErrorMessage([] { parseMethod("sdf"); });
  for (const MethodRow& row : methodTable()) {
    EXPECT_NE(msg.find(std::string(row.name)), std::string::npos) << msg;
  }
  EXPECT_EQ(msg.find("--"), std::string::npos) << msg;  // no CLI flag below cli/
}

// defaultMethod is the first default row that takes the pair, for every ordered pair, and a
// pair no default row takes is refused; likewise defaultDepthFieldMethod among the rows that
// fill a depth field.
TEST(MethodTable, DefaultsAreTheFirstRowThatTakesThePair) {
  const std::vector<geometry::Shape> shapes = {
      geometry::Sphere{0.01}, geometry::Cylinder{0.01, 0.02},
      geometry::Box{Vector3d(0.01, 0.02, 0.03)}, geometry::HalfSpace{}, torusShape()};
  for (const auto& a : shapes) {
    for (const auto& b : shapes) {
      const std::string what = geometry::describe(a) + " against " + geometry::describe(b);
      const MethodRow* byDefault = nullptr;
      const MethodRow* withField = nullptr;
      for (const MethodRow& row : methodTable()) {
        if (!row.handles(a, b)) continue;
        if (row.is_default && !byDefault) byDefault = &row;
        if (row.fills_depth_field && !withField) withField = &row;
      }
      if (byDefault) {
        EXPECT_EQ(defaultMethod(a, b), byDefault->id) << what;
      } else {
        EXPECT_THROW(defaultMethod(a, b), InputError) << what;
      }
      if (withField) {
        EXPECT_EQ(defaultDepthFieldMethod(a, b), withField->id) << what;
      } else {
        EXPECT_THROW(defaultDepthFieldMethod(a, b), InputError) << what;
      }
    }
  }
}

// A depth field through the one entry point: by default from the first method that samples
// one, the same as the backend's own call; a method that samples none refuses it; a fixed
// resolution is one grid of that many lines (no estimate, inf).
TEST(ComputeContact, DepthFieldThroughTheEntryPoint) {
  const geometry::Shape torus = torusShape();
  const Isometry3d X_WH = test::randomPose(5);
  const Isometry3d X_WM = X_WH * test::translation({0.001, 0.0, 0.0071 - 0.002});
  const geometry::Shape plane = geometry::HalfSpace{};
  DepthField field;
  const ContactVolume cv = computeContact(torus, X_WM, plane, X_WH, {}, &field).aggregate;
  DepthField direct;
  const ContactVolume ref = columnsContact(torus, X_WM, plane, X_WH, &direct);
  ASSERT_GT(ref.volume, 0.0);
  EXPECT_TRUE(fillsDepthField(cv.method));
  // The same backend on the same grids; 1e-12 for the order of TBB's parallel sums.
  EXPECT_NEAR(cv.volume, ref.volume, 1e-12 * ref.volume);
  ASSERT_FALSE(field.depth.empty());
  EXPECT_EQ(field.depth, direct.depth);
  EXPECT_EQ(field.cell_area, direct.cell_area);
  double sum = 0.0;
  for (double d : field.depth) sum += d * field.cell_area;
  EXPECT_NEAR(sum, cv.volume, 1e-12 * cv.volume);  // V = Σ δ dS, up to the summation order

  DepthField fixed;
  const int lines = 32;
  const ContactVolume coarse =
      computeContact(torus, X_WM, plane, X_WH, {.method = cv.method, .fixed_resolution = lines},
                     &fixed)
          .aggregate;
  EXPECT_TRUE(std::isinf(coarse.relative_error));
  EXPECT_LE(fixed.depth.size(), std::size_t(lines * lines));
  EXPECT_GT(fixed.depth.size(), 0u);

  for (const MethodRow& row : methodTable()) {
    if (row.fills_depth_field || !row.handles(torus, plane)) continue;
    DepthField none;
    EXPECT_THROW(computeContact(torus, X_WM, plane, X_WH, {row.id}, &none), InputError) << row.name;
    EXPECT_TRUE(none.depth.empty()) << row.name;
  }
}

// A primitive on a half-space is one convex region: the aggregate is the only patch, equal to
// it to the bit; apart, there is no patch and the aggregate is empty.
TEST(ComputeContact, AnalyticIsOnePatch) {
  const Isometry3d X_WH = test::randomPose(7);
  const double R = 0.0103, d = 0.0007;
  const Isometry3d X_WS = X_WH * test::translation({0.0, 0.0, R - d});
  const ContactPatches touching =
      computeContact(geometry::Sphere{R}, X_WS, geometry::HalfSpace{}, X_WH);
  ASSERT_EQ(touching.patches.size(), 1u);
  EXPECT_TRUE(touching.inContact());
  EXPECT_EQ(touching.patches[0].volume, touching.aggregate.volume);
  EXPECT_EQ(touching.patches[0].p_WC, touching.aggregate.p_WC);
  EXPECT_EQ(touching.patches[0].J_s, touching.aggregate.J_s);
  const ContactPatches apart = computeContact(
      geometry::Sphere{R}, X_WH * test::translation({0, 0, 2 * R}), geometry::HalfSpace{}, X_WH);
  EXPECT_FALSE(apart.inContact());
  EXPECT_EQ(apart.aggregate.volume, 0.0);
}

// Every method that takes the pair finds the U's two feet, on a half-space and on a plate
// mesh whose top face is the same plane, each foot's V equal to the exact clip's: to 1e-9 for
// the exact methods (two exact methods, cgal_corefinement_test), to twice the reported estimate
// for columns (columns_test).
TEST(ComputeContact, EveryMethodFindsTheSamePatches) {
  const auto u = std::make_shared<const geometry::TriangleMesh>(
      test::uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123));
  const geometry::Shape shape = geometry::Mesh{u, "U"};
  const geometry::Shape plane = geometry::HalfSpace{};
  geometry::TriangleMesh slab = geometry::tessellateBox(Vector3d(0.2, 0.2, 0.05));
  slab.vertices.col(2).array() -= 0.025;  // top face z_H = 0
  const geometry::Shape plate =
      geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(slab), "plate"};
  const Isometry3d X_WH = test::randomPose(18);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, -0.0031}) *
                          Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
  const ContactPatches exact = computeContact(shape, X_WM, plane, X_WH, {Method::kHalfspace});
  ASSERT_EQ(exact.patches.size(), 2u);
  int checked = 0;
  for (const MethodRow& row : methodTable()) {
    for (const geometry::Shape* other : {&plane, &plate}) {
      if (!row.handles(shape, *other)) continue;
      SCOPED_TRACE(std::string(row.name) + " on " + geometry::describe(*other));
      const ContactPatches c = computeContact(shape, X_WM, *other, X_WH, {row.id});
      ASSERT_EQ(c.patches.size(), 2u);
      for (std::size_t k = 0; k < 2; ++k) {
        // an approximate method's own estimate; `recovered` on the U's planes is the exact
        // polyhedral method it falls back to (no estimate: NaN)
        const double estimate = c.patches[k].relative_error;
        const double tol = row.exact || std::isnan(estimate) ? 1e-9 : 2.0 * estimate;
        EXPECT_NEAR(c.patches[k].volume, exact.patches[k].volume, tol * exact.patches[k].volume);
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);  // halfspace; fast on the plate; cgal, columns and recovered on both
}

// Decreasing volume, then the lexicographic centroid.
TEST(ContactPatches, SortOrder) {
  std::vector<ContactVolume> patches(3);
  patches[0].volume = 1.0;
  patches[0].p_WC = Vector3d(0.0, 1.0, 0.0);
  patches[1].volume = 2.0;
  patches[2].volume = 1.0;
  patches[2].p_WC = Vector3d(0.0, -1.0, 5.0);
  sortPatches(patches);
  EXPECT_EQ(patches[0].volume, 2.0);
  EXPECT_EQ(patches[1].p_WC.y(), -1.0);
  EXPECT_EQ(patches[2].p_WC.y(), 1.0);
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
