// One test per repair: the defect is rejected by the check, the repair says what it changed,
// and the repaired mesh passes the check with the volume of the solid that was meant. Then the
// shell test: intersecting and nested shells are rejected, cavities and disjoint shells not.

#include "geometry/mesh_repair.hpp"

#include <gtest/gtest.h>

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
