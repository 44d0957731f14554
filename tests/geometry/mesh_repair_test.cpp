// One test per repair: the defect is rejected by the check, the repair says what it changed,
// and the repaired mesh passes the check with the volume of the solid that was meant. Then the
// shell test: intersecting and nested shells are rejected, cavities and disjoint shells not.

#include "geometry/mesh_repair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/defect_meshes.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/mesh_check.hpp"

namespace vcontact::geometry {
namespace {

using namespace vcontact::test;

// Repairs move no vertex of the intended solid (a weld keeps the first copy), so the volume
// differs only by the summation order of the divergence-theorem sum: a few ulps of the
// largest term, under 1e-14 relative.
constexpr double kRepairedVolumeTolerance = 1e-13;

using test::rejection;

struct Repaired {
  TriangleMesh mesh;
  std::vector<std::string> changes;
  double volume = 0.0;
};

Repaired repairAndCheck(const TriangleMesh& soup, RepairOptions options = {}) {
  RepairResult r = repairMesh(soup, options);
  checkAndRepair(r.mesh);
  return {r.mesh, r.changes, meshMoments(r.mesh).m0};
}

bool said(const std::vector<std::string>& changes, const std::string& what) {
  for (const auto& c : changes) {
    if (c.find(what) != std::string::npos) return true;
  }
  return false;
}

const double kBoxVolume = meshMoments(cadBox()).m0;

TEST(MeshRepair, WeldClosesASeamOfOneVertex) {
  const TriangleMesh seam = withSeam(cadBox(), 3, 1e-10);
  EXPECT_NE(rejection(seam).find("boundary edges, mesh is not closed"), std::string::npos);
  EXPECT_NE(rejection(seam).find("repairing the mesh welds vertices"), std::string::npos);
  const Repaired r = repairAndCheck(seam);
  EXPECT_TRUE(said(r.changes, "welded 1 vertex onto a neighbour closer than")) << r.changes[0];
  EXPECT_EQ(r.mesh.vertexCount(), 8);
  EXPECT_NEAR(r.volume / kBoxVolume, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, WeldClosesAMeridianSeam) {
  const TriangleMesh meant = tessellateSphere(0.02, 24, 12);
  const TriangleMesh seam = sphereWithMeridianSeam(2e-9);
  ASSERT_GT(seam.vertexCount(), meant.vertexCount());
  EXPECT_NE(rejection(seam).find("boundary edges"), std::string::npos);
  const Repaired r = repairAndCheck(seam);
  EXPECT_TRUE(said(r.changes, "welded 11 vertices")) << r.changes[0];
  EXPECT_EQ(r.mesh.vertexCount(), meant.vertexCount());
  EXPECT_NEAR(r.volume / meshMoments(meant).m0, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, GapAboveTheToleranceIsNotWelded) {
  // 1e-3 of the diagonal is a thousand times the default tolerance: a real gap.
  const TriangleMesh seam = withSeam(cadBox(), 3, 1e-4);
  const RepairResult r = repairMesh(seam, {});
  EXPECT_FALSE(said(r.changes, "welded"));
  EXPECT_NE(rejection(r.mesh).find("boundary edges"), std::string::npos);
}

TEST(MeshRepair, ZeroAreaFacesAreDroppedAndTheSurfaceRestitched) {
  const TriangleMesh flat = withZeroAreaFaces(cadBox(), 2);
  EXPECT_NE(rejection(flat).find("2 degenerate faces (zero area)"), std::string::npos);
  EXPECT_NE(rejection(flat).find("repairing the mesh drops zero-area faces"), std::string::npos);
  const Repaired r = repairAndCheck(flat);
  EXPECT_TRUE(said(r.changes, "dropped 2 zero-area faces and re-stitched their neighbours"));
  EXPECT_NEAR(r.volume / kBoxVolume, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, DuplicateFaceIsDropped) {
  const TriangleMesh twice = withDuplicateFace(cadBox(), 4);
  EXPECT_NE(rejection(twice).find("repairing the mesh drops duplicate faces"), std::string::npos);
  const Repaired r = repairAndCheck(twice);
  EXPECT_TRUE(said(r.changes, "dropped 1 duplicate face; first at"));
  EXPECT_EQ(r.mesh.triangleCount(), 12);
  EXPECT_NEAR(r.volume / kBoxVolume, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, ReversedFacesAreOriented) {
  const TriangleMesh mixed = withFacesReversed(cadBox(), {2, 7});
  EXPECT_NE(rejection(mixed).find("repairing the mesh orients its faces"), std::string::npos);
  const Repaired r = repairAndCheck(mixed);
  EXPECT_TRUE(said(r.changes, "reversed")) << r.changes.size();
  EXPECT_NEAR(r.volume / kBoxVolume, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, SmallHoleIsFilledOnlyWhenAsked) {
  const TriangleMesh meant = tessellateSphere(0.02, 24, 12);
  const TriangleMesh holed = withoutFaces(meant, {100});
  EXPECT_NE(rejection(repairMesh(holed, {}).mesh).find("3 boundary edges"), std::string::npos);
  const Repaired r = repairAndCheck(holed, {.fillHoles = true});
  EXPECT_TRUE(said(r.changes, "filled 1 hole with 1 triangle; first at"));
  // A triangular hole is filled by the triangle that was removed.
  EXPECT_NEAR(r.volume / meshMoments(meant).m0, 1.0, kRepairedVolumeTolerance);
}

// A cylinder of radius 1 and length 20 as an n-gon prism whose top cap is missing: a planar,
// convex hole of n edges (bottom cap: a fan from its centre).
TriangleMesh openPrism(int n) {
  TriangleMesh m;
  m.vertices.resize(2 * n + 1, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    m.vertices.row(i) << std::cos(a), std::sin(a), 0.0;
    m.vertices.row(n + i) << std::cos(a), std::sin(a), 20.0;
  }
  m.vertices.row(2 * n) << 0.0, 0.0, 0.0;
  m.triangles.resize(3 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.row(3 * i) << i, j, n + j;
    m.triangles.row(3 * i + 1) << i, n + j, n + i;
    m.triangles.row(3 * i + 2) << 2 * n, j, i;
  }
  return m;
}

// Issue 36: a 10,000-edge cap took minutes, since CGAL's fill is a fan of slivers from one
// corner and the shell tests compare every pair of its overlapping boxes. A planar convex hole
// is filled by a strip instead: the exact polygon (the prism's volume), and no corner in more
// than a few of its triangles.
TEST(MeshRepair, ALargePlanarConvexHoleIsFilledByAStrip) {
  constexpr int n = 2000;
  const Repaired r = repairAndCheck(openPrism(n), {.fillHoles = true});
  EXPECT_TRUE(said(r.changes, "filled 1 hole with 1998 triangles")) << r.changes.front();
  // the n-gon's area (n/2) r² sin(2π/n) times the length; the divergence sum over 6,000 faces
  // rounds to a few ulps of its largest terms
  const double prism = 0.5 * n * std::sin(2.0 * M_PI / n) * 20.0;
  EXPECT_NEAR(r.volume / prism, 1.0, 1e-12);
  std::vector<int> faces_at(static_cast<std::size_t>(r.mesh.vertexCount()), 0);
  for (Eigen::Index f = 0; f < r.mesh.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k) ++faces_at[static_cast<std::size_t>(r.mesh.triangles(f, k))];
  // the bottom centre is in n faces; a top corner in 3 side faces and at most 4 of the strip
  std::sort(faces_at.rbegin(), faces_at.rend());
  EXPECT_EQ(faces_at[0], n);
  EXPECT_LE(faces_at[1], 7);
}

TEST(MeshRepair, LargeHoleIsLeftOpen) {
  // A whole side of the box (perimeter 0.16 m) is above half the diagonal (0.046 m).
  const RepairResult r = repairMesh(withoutFaces(cadBox(), {0, 1}), {.fillHoles = true});
  EXPECT_TRUE(said(r.changes, "left 1 hole longer around than"));
  EXPECT_NE(rejection(r.mesh).find("boundary edges"), std::string::npos);
}

TEST(MeshRepair, InvertedShellIsTurnedOutward) {
  const Repaired r = repairAndCheck(inverted(cadBox()));
  EXPECT_TRUE(said(r.changes, "reversed 12 faces of outer shells that faced inward"));
  EXPECT_NEAR(r.volume / kBoxVolume, 1.0, kRepairedVolumeTolerance);
}

TEST(MeshRepair, GoodMeshIsLeftAlone) {
  const TriangleMesh torus = tessellateTorus(0.05, 0.01, 24, 12);
  const RepairResult r = repairMesh(torus, {});
  EXPECT_TRUE(r.changes.empty()) << r.changes[0];
  EXPECT_EQ(r.mesh.triangleCount(), torus.triangleCount());
}

TEST(MeshRepair, PolygonIsSplitIntoTrianglesOfItsOrientation) {
  // An L-shaped (non-convex) hexagon, counter-clockwise about +z: four triangles, all facing +z,
  // covering its area 3 (the unit square cells of the L).
  const std::vector<Eigen::Vector3d> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                          {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  const auto triangles = triangulatePolygon(l);
  ASSERT_EQ(triangles.size(), 4u);
  double area = 0.0;
  for (const auto& t : triangles) {
    const double z = (l[t[1]] - l[t[0]]).cross(l[t[2]] - l[t[0]]).z();
    EXPECT_GT(z, 0.0);
    area += 0.5 * z;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);
}

TEST(MeshShells, OverlappingShellsAreRejected) {
  const TriangleMesh two = joined(cadBox(), translated(cadBox(), {0.01, 0.0, 0.0}));
  EXPECT_NE(rejection(two).find("closed shells intersect or touch each other"), std::string::npos)
      << rejection(two);
}

TEST(MeshShells, ShellInsideAnotherWithTheSameOrientationIsRejected) {
  const TriangleMesh nested = joined(tessellateBox({0.1, 0.1, 0.1}), cadBox());
  EXPECT_NE(rejection(nested).find("lies inside another with the same orientation"),
            std::string::npos)
      << rejection(nested);
}

TEST(MeshShells, CavityFacingInwardIsASolid) {
  TriangleMesh hollow = joined(tessellateBox({0.1, 0.1, 0.1}), inverted(cadBox()));
  const MeshCheckResult r = checkAndRepair(hollow);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_NEAR(meshMoments(hollow).m0 / (0.1 * 0.1 * 0.1 - kBoxVolume), 1.0,
              kRepairedVolumeTolerance);
}

TEST(MeshShells, DisjointShellsAreAccepted) {
  TriangleMesh two = joined(cadBox(), translated(cadBox(), {0.1, 0.0, 0.0}));
  EXPECT_EQ(checkAndRepair(two).shells, 2u);
  EXPECT_NEAR(meshMoments(two).m0 / (2 * kBoxVolume), 1.0, kRepairedVolumeTolerance);
}

TEST(MeshShells, ShellsTouchingAtOneVertexAreRejected) {
  // Corner to corner: no volume overlaps, but the solid is not a manifold there, and CGAL's
  // intersection test counts the shared point.
  const TriangleMesh box = cadBox();
  const TriangleMesh touching = joined(box, translated(box, {0.03, 0.05, 0.07}));
  EXPECT_NE(rejection(touching).find("closed shells intersect or touch"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::geometry
