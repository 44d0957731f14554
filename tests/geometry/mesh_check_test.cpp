// Every defect the mesh check knows is rejected with its own message; inverted meshes are
// flipped with a warning; good meshes pass unchanged.

#include "geometry/mesh_check.hpp"

#include <gtest/gtest.h>

#include "geometry/defect_meshes.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/tessellate.hpp"

namespace vcontact::geometry {
namespace {

using test::rejection;

TriangleMesh withoutFace(const TriangleMesh& m, Eigen::Index drop) {
  TriangleMesh out = m;
  out.triangles.resize(m.triangleCount() - 1, 3);
  for (Eigen::Index f = 0, k = 0; f < m.triangleCount(); ++f) {
    if (f != drop) out.triangles.row(k++) = m.triangles.row(f);
  }
  return out;
}

TEST(MeshCheck, GoodMeshesPassUnchanged) {
  for (TriangleMesh m : {tessellateSphere(1, 16, 8), tessellateCylinder(1, 2, 12),
                         tessellateBox({1, 2, 3}), tessellateTorus(2, 0.5, 16, 8)}) {
    const TriangleMesh before = m;
    const MeshCheckResult r = checkAndRepair(m);
    EXPECT_FALSE(r.flipped);
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_EQ(m.triangles, before.triangles);
  }
}

TEST(MeshCheck, OpenMeshNamesBoundaryEdgesAndAVertex) {
  const std::string msg = rejection(withoutFace(tessellateBox({1, 1, 1}), 0));
  EXPECT_NE(msg.find("3 boundary edges, mesh is not closed; first at vertex ("), std::string::npos)
      << msg;
}

TEST(MeshCheck, InconsistentOrientationIsRejected) {
  TriangleMesh m = tessellateSphere(1, 12, 6);
  m.triangles.row(5) = m.triangles.row(5).reverse().eval();
  const std::string msg = rejection(m);
  EXPECT_NE(msg.find("3 edges listed in the same direction by both faces, orientation is "
                     "inconsistent"),
            std::string::npos)
      << msg;
}

TEST(MeshCheck, NonManifoldEdgeIsRejected) {
  // Two boxes sharing one edge's vertices would be an edge with four faces: glue a second
  // copy of one face pair onto the same vertices.
  TriangleMesh m = tessellateBox({1, 1, 1});
  TriangleMesh doubled = m;
  doubled.triangles.resize(2 * m.triangleCount(), 3);
  doubled.triangles << m.triangles, m.triangles;
  const std::string msg = rejection(doubled);
  EXPECT_NE(msg.find("shared by more than two faces"), std::string::npos) << msg;
}

TEST(MeshCheck, DegenerateFaceIsRejected) {
  TriangleMesh m = tessellateBox({1, 1, 1});
  m.triangles(3, 2) = m.triangles(3, 1);
  const std::string msg = rejection(m);
  EXPECT_NE(msg.find("1 degenerate face (zero area); first is face 3"), std::string::npos) << msg;
}

TEST(MeshCheck, CollinearFaceIsDegenerate) {
  TriangleMesh m = tessellateBox({1, 1, 1});
  // Vertex 0 moved onto the midpoint of edge 2-3 of its face (0, 2, 3): zero area.
  m.vertices.row(0) = 0.5 * (m.vertices.row(2) + m.vertices.row(3));
  const std::string msg = rejection(m);
  EXPECT_NE(msg.find("degenerate face"), std::string::npos) << msg;
}

TEST(MeshCheck, NonFiniteVertexIsRejected) {
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    TriangleMesh m = tessellateBox({1, 1, 1});
    m.vertices(4, 1) = bad;
    const std::string msg = rejection(m);
    EXPECT_NE(msg.find("1 vertex with a NaN or infinite coordinate; first is vertex 4"),
              std::string::npos)
        << msg;
  }
}

TEST(MeshCheck, IndexOutOfRangeIsRejected) {
  TriangleMesh m = tessellateBox({1, 1, 1});
  m.triangles(0, 0) = 99;
  EXPECT_NE(rejection(m).find("refers to vertex 99, but the mesh has 8 vertices"),
            std::string::npos);
}

TEST(MeshCheck, InvertedMeshIsFlippedWithAWarning) {
  TriangleMesh m = tessellateSphere(1, 16, 8);
  const double V = meshMoments(m).m0;
  m.triangles.col(1).swap(m.triangles.col(2));
  const MeshCheckResult r = checkAndRepair(m);
  EXPECT_TRUE(r.flipped);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("flipped all"), std::string::npos);
  EXPECT_DOUBLE_EQ(meshMoments(m).m0, V);
}

TEST(MeshCheck, FlatClosedSurfaceIsRejected) {
  // A box squashed to zero height: closed, consistently oriented, but encloses nothing, and
  // its faces are degenerate or not, depending on which; either defect must be reported.
  TriangleMesh m = tessellateBox({1, 1, 1});
  m.vertices.col(2).setZero();
  EXPECT_FALSE(rejection(m).empty());
}

// Issue 36: a box with a corner pushed through the opposite face passed as closed,
// consistently oriented and outward; a single shell's self-intersection was never looked for.
TEST(MeshCheck, CornerPushedThroughTheOppositeFaceIsRefused) {
  const TriangleMesh m = test::boxWithCornerPushedThrough();
  ASSERT_LT(m.vertex(7).z(), -0.035);  // below the bottom face
  const std::string msg = rejection(m);
  EXPECT_EQ(msg.rfind("the surface passes through itself (faces ", 0), 0u) << msg;
  EXPECT_NE(msg.find("intersect; first at ("), std::string::npos) << msg;
  EXPECT_NE(msg.find("--remove-self-intersections"), std::string::npos) << msg;
}

// The same box's mass properties, which the self-intersection test stops before: refused on
// their own, as every mesh's are once it passed the other checks.
TEST(MeshCheck, ImpossibleMassPropertiesAreRefused) {
  const std::string folded =
      test::inputErrorMessage([] { checkMassProperties(test::boxWithCornerFolded()); });
  EXPECT_EQ(folded.rfind("impossible mass properties: the principal moments of inertia at unit "
                         "density, ",
                         0),
            0u)
      << folded;
  EXPECT_NE(folded.find("include a negative one"), std::string::npos) << folded;
  const std::string pushed =
      test::inputErrorMessage([] { checkMassProperties(test::boxWithCornerPushedThrough()); });
  EXPECT_EQ(pushed.rfind("impossible mass properties: the centroid (-0.0192045", 0), 0u) << pushed;
  for (const TriangleMesh& good :
       {tessellateSphere(1, 16, 8), tessellateTorus(2, 0.5, 16, 8), test::cadBox()}) {
    EXPECT_NO_THROW(checkMassProperties(good));
  }
}

// A centroid outside the bounds: a box of side 2 facing outward and one of side 1.9 turned
// inside out beside it, 20 to the -x side. Their signed volumes add to 8 - 6.859 = 1.141 at
// x = (8 · 0 - 6.859 · (-20)) / 1.141 = 120.23, far beyond the bounds' x <= 1.
TEST(MeshCheck, CentroidOutsideTheBoundsIsRefused) {
  TriangleMesh m = tessellateBox({2, 2, 2});
  const TriangleMesh inner = tessellateBox({1.9, 1.9, 1.9});
  const Eigen::Index v0 = m.vertexCount(), f0 = m.triangleCount();
  m.vertices.conservativeResize(v0 + inner.vertexCount(), 3);
  m.triangles.conservativeResize(f0 + inner.triangleCount(), 3);
  for (Eigen::Index i = 0; i < inner.vertexCount(); ++i) {
    m.vertices.row(v0 + i) = inner.vertices.row(i) + Eigen::RowVector3d(-20.0, 0.0, 0.0);
  }
  const int offset = static_cast<int>(v0);
  for (Eigen::Index f = 0; f < inner.triangleCount(); ++f) {  // reversed: facing inward
    m.triangles.row(f0 + f) << inner.triangles(f, 0) + offset, inner.triangles(f, 2) + offset,
        inner.triangles(f, 1) + offset;
  }
  const std::string msg = test::inputErrorMessage([&] { checkMassProperties(m); });
  EXPECT_EQ(msg.rfind("impossible mass properties: the centroid (120.2", 0), 0u) << msg;
}

TEST(MeshCheck, EmptyMeshIsRejected) {
  EXPECT_NE(rejection(TriangleMesh{}).find("no faces"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::geometry
