// The column method against the exact methods (half-space clip, CGAL corefinement) on the
// named bodies of issue #3, its own error estimate, symmetry, invariance and its δ field.

#include "volume/columns/columns.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/cgal/corefinement.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::MeshBvh;
using geometry::TriangleMesh;
using test::relativeDifference;

constexpr double kRequested = 1e-3;  // ColumnOptions default: two levels agree on V to this

/// How far a column result may be from an exact one: the midpoint rule across lines with a
/// region boundary that cuts cells converges at least like h^{3/2} (h the line spacing),
/// faster than the level-to-level difference it reports, so the true error is below the
/// estimate; a factor 2 allows for an estimate that happens to be small by cancellation.
double volumeTolerance(const ContactVolume& columns) { return 2.0 * columns.relative_error; }

void expectNearExact(const ContactVolume& col, const ContactVolume& exact) {
  ASSERT_GT(exact.volume, 0.0);
  ASSERT_GT(col.volume, 0.0);
  EXPECT_LE(col.relative_error, kRequested);
  EXPECT_NEAR(col.volume, exact.volume, volumeTolerance(col) * exact.volume);
  // Centroid and tensors carry the same quadrature error, amplified where the region is
  // thin (second moments across the plate weight the rim): 10× the volume tolerance.
  const double width = std::sqrt(exact.area);
  EXPECT_LE((col.p_WC - exact.p_WC).norm(), 10.0 * volumeTolerance(col) * width);
  EXPECT_LE(relativeDifference(col.J_v, exact.J_v), 10.0 * volumeTolerance(col));
  // The normal from coarse axis passes: sums of ±dS over crossings, error ~ the rim cells.
  EXPECT_LE((col.n_W - exact.n_W).norm(), 2e-2);
}

struct PairCase {
  std::string name;
  TriangleMesh a, b;
  Isometry3d X_BA;  ///< pose of A in B's frame
};

Isometry3d pose(const Vector3d& t, double angle, const Vector3d& axis) {
  Isometry3d X = test::translation(t);
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return X;
}

std::vector<PairCase> pairCases() {
  const TriangleMesh plate = geometry::tessellateBox(Vector3d(0.08, 0.07, 0.02));
  return {
      {"sphere_on_plate", geometry::tessellateSphere(0.0137, 48, 25), plate,
       pose({0.003, -0.002, 0.01 + 0.0137 - 0.0021}, 0.3, {1, 2, 3})},
      {"cylinder_on_side", geometry::tessellateCylinder(0.009, 0.031, 64), plate,
       pose({0.001, 0.002, 0.01 + 0.009 - 0.0013}, M_PI / 2, {1, 0, 0})},
      {"torus_flat", geometry::tessellateTorus(0.021, 0.0071, 48, 16), plate,
       pose({0.0, 0.001, 0.01 + 0.0071 - 0.0017}, 0.0, {0, 0, 1})},
      {"l_bracket_edge", test::lBracket(0.023, 0.0061, 0.017), plate,
       pose({-0.01, -0.004, 0.01 + 0.0006}, 0.07, {1, 1, 0})},
      {"peg_in_hole", geometry::tessellateCylinder(0.0052, 0.03, 40),
       geometry::tessellateTorus(0.0111, 0.0061, 40, 16),
       pose({0.0004, 0.0, 0.003}, 0.2, {1, 0, 0})},
  };
}

TEST(Columns, AgreesWithCgalOnNamedPairs) {
  const Isometry3d X_WB = test::randomPose(13);
  for (const PairCase& c : pairCases()) {
    SCOPED_TRACE(c.name);
    const MeshBvh a(c.a), b(c.b);
    const Isometry3d X_WA = X_WB * c.X_BA;
    const ContactVolume col = columnsContact({&a, X_WA}, {&b, X_WB});
    const ContactVolume ref = cgalMeshMeshContact(c.a, X_WA, c.b, X_WB).aggregate;
    expectNearExact(col, ref);
  }
}

// Regression: two separate regions pressed unequally (a part on two feet, one barely
// touching). The axis passes resolve the thin one in some directions only; the integration
// box must still hold both. Exact: V = s² (d₁ + d₂), normal +z.
TEST(Columns, KeepsAThinSecondRegion) {
  const double s = 0.01, d1 = 1e-3, d2 = 2e-5;
  TriangleMesh feet = geometry::tessellateBox(Vector3d::Constant(s));
  const TriangleMesh second = feet;
  feet.vertices.col(0).array() -= 0.02;
  feet.vertices.col(2).array() += s / 2 - d1;
  feet.vertices.conservativeResize(16, 3);
  feet.vertices.bottomRows(8) = second.vertices;
  feet.vertices.bottomRows(8).col(0).array() += 0.02;
  feet.vertices.bottomRows(8).col(2).array() += s / 2 - d2;
  feet.triangles.conservativeResize(24, 3);
  feet.triangles.bottomRows(12) = second.triangles.array() + 8;
  const TriangleMesh plate = geometry::tessellateBox(Vector3d(0.08, 0.03, 0.01));
  const MeshBvh a(feet), b(plate);
  const Isometry3d X_WB = test::translation({0, 0, -0.005});  // plate top at z = 0
  const ContactVolume col = columnsContact({&a, Isometry3d::Identity()}, {&b, X_WB});
  EXPECT_NEAR(col.volume, s * s * (d1 + d2), volumeTolerance(col) * s * s * (d1 + d2));
  EXPECT_GT(col.volume, s * s * d1 * (1 + 0.5 * d2 / d1));  // the thin foot is counted
  EXPECT_LE((col.n_W - Vector3d::UnitZ()).norm(), 2e-2);
}

// A "U" on its legs on a half-space and on a plate mesh: the wet lines under the two feet are
// apart, so two patches, each within the method's tolerance of the exact clip's patch (same
// order, sortPatches), in the same order.
TEST(Columns, PatchesOfTwoFeet) {
  const auto u = std::make_shared<const TriangleMesh>(
      test::uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123));
  const geometry::Shape shape = geometry::Mesh{u, "U"};
  const MeshBvh bvh(*u);
  const geometry::MeshTopology topo(*u);
  const Isometry3d X_WH = test::randomPose(14);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, -0.0031}) *
                          Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
  const ContactPatches exact = meshHalfspacePatches(bvh, topo, X_WM, X_WH);
  ASSERT_EQ(exact.patches.size(), 2u);
  const auto plate = std::make_shared<const TriangleMesh>([] {
    TriangleMesh m = geometry::tessellateBox(Vector3d(0.2, 0.2, 0.05));
    m.vertices.col(2).array() -= 0.025;  // top face z_H = 0
    return m;
  }());
  const ContactPatches onPlane = columnsPatches(shape, X_WM, geometry::HalfSpace{}, X_WH, nullptr);
  const ContactPatches onPlate =
      columnsPatches(shape, X_WM, geometry::Mesh{plate, "plate"}, X_WH, nullptr);
  for (const ContactPatches* col : {&onPlane, &onPlate}) {
    ASSERT_EQ(col->patches.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      const ContactVolume& c = col->patches[k];
      const ContactVolume& e = exact.patches[k];
      EXPECT_NEAR(c.volume, e.volume, volumeTolerance(c) * e.volume) << k;
      EXPECT_LE((c.p_WC - e.p_WC).norm(), 10.0 * volumeTolerance(c) * std::sqrt(e.area));
    }
  }
}

// Regression: a layer a few µm thick lying in a coordinate plane (a cube face down on a plate,
// both axis-aligned) slips between the lines of the x and y passes at every resolution; the
// z pass alone must be enough. Exact: V = s² d, n = +z, for a half-space and a mesh plate.
TEST(Columns, FindsAThinAxisAlignedLayer) {
  const double s = 0.02, d = 1e-5;
  const MeshBvh cube(geometry::tessellateBox(Vector3d::Constant(s)));
  const MeshBvh plate(geometry::tessellateBox(Vector3d(0.06, 0.06, 0.01)));
  const Isometry3d X_WA = test::translation({0.001, -0.002, s / 2 - d});
  const ColumnBody onHalfspace{nullptr, Isometry3d::Identity()};
  const ColumnBody onMesh{&plate, test::translation({0, 0, -0.005})};
  for (const ColumnBody& b : {onHalfspace, onMesh}) {
    const ContactVolume col = columnsContact({&cube, X_WA}, b);
    // Every wet line has the same δ, so the midpoint rule is exact and only the rounding of
    // δ = 1e-5 from coordinates of 1e-2 remains (ε·1e-2/1e-5 ≈ 2e-13 relative).
    EXPECT_NEAR(col.volume, s * s * d, std::max(volumeTolerance(col), 1e-12) * s * s * d);
    EXPECT_LE((col.n_W - Vector3d::UnitZ()).norm(), 1e-9);
  }
}

// Against the exact clip for a mesh on a half-space, from shallow to deep.
TEST(Columns, AgreesWithHalfspaceClip) {
  const MeshBvh sphere(geometry::tessellateSphere(0.0137, 64, 33));
  const Isometry3d X_WH = test::randomPose(5);
  for (double d : {1e-4, 1e-3, 5e-3}) {
    SCOPED_TRACE(d);
    const Isometry3d X_WM = X_WH * pose({0.001, 0.0, 0.0137 - d}, 0.4, {0, 1, 1});
    const ContactVolume col = columnsContact({&sphere, X_WM}, {nullptr, X_WH});
    expectNearExact(col, meshHalfspaceContact(sphere, X_WM, X_WH));
  }
}

// Swapping the bodies flips n and keeps the rest, within the two runs' error estimates.
TEST(Columns, SwappingBodiesFlipsTheNormal) {
  const PairCase c = pairCases().back();
  const MeshBvh a(c.a), b(c.b);
  const ContactVolume ab = columnsContact({&a, c.X_BA}, {&b, Isometry3d::Identity()});
  const ContactVolume ba = columnsContact({&b, Isometry3d::Identity()}, {&a, c.X_BA});
  EXPECT_NEAR(ab.volume, ba.volume, (ab.relative_error + ba.relative_error) * ab.volume);
  EXPECT_LE((ab.n_W + ba.n_W).norm(), 2e-2);  // each from axis passes, as expectNearExact
}

// Moving both bodies by one rigid motion moves the result with them (within the estimates;
// the grid moves with the overlap box, which is axis-aligned in W, so lines differ).
TEST(Columns, InvariantUnderCommonMotion) {
  const PairCase c = pairCases().front();
  const MeshBvh a(c.a), b(c.b);
  const ContactVolume base = columnsContact({&a, c.X_BA}, {&b, Isometry3d::Identity()});
  const Isometry3d X = test::randomPose(17);
  const ContactVolume moved = columnsContact({&a, X * c.X_BA}, {&b, X});
  EXPECT_NEAR(moved.volume, base.volume,
              (moved.relative_error + base.relative_error) * base.volume);
  // The axis passes turn with W, not with the bodies: each normal as in expectNearExact.
  EXPECT_LE((moved.n_W - X.linear() * base.n_W).norm(), 2e-2);
}

// The δ field integrates to V: V = Σ δ dS on the finest grid (MODEL.md §1), exactly the sum
// the method itself formed, so only rounding separates them.
TEST(Columns, FieldIntegratesToVolume) {
  const PairCase c = pairCases()[1];
  const MeshBvh a(c.a), b(c.b);
  DepthField field;
  const ContactVolume cv = columnsContact({&a, c.X_BA}, {&b, Isometry3d::Identity()}, {}, &field);
  ASSERT_FALSE(field.depth.empty());
  double sum = 0.0;
  for (double d : field.depth) sum += d;
  // The same δ summed in another order (the backend's sums are parallel): rounding only.
  EXPECT_NEAR(sum * cv.area / double(field.depth.size()), cv.volume, 1e-12 * cv.volume);
  double maxDepth = 0.0;
  for (double d : field.depth) maxDepth = std::max(maxDepth, d);
  EXPECT_EQ(maxDepth, cv.depth);
}

// Apart, and a face resting exactly on a face: zero, and nothing NaN.
TEST(Columns, NoContactGivesZeroWithoutNaN) {
  const MeshBvh box(geometry::tessellateBox(Vector3d(0.01, 0.01, 0.01)));
  for (double gap : {0.001, 0.0}) {
    const ContactVolume cv =
        columnsContact({&box, test::translation({0.002, 0.001, 0.01 + gap})}, {&box, {}});
    EXPECT_EQ(cv.volume, 0.0);
    EXPECT_TRUE(cv.p_WC.allFinite() && cv.J_v.allFinite() && std::isfinite(cv.r_gyr));
  }
}

}  // namespace
}  // namespace vcontact::volume
