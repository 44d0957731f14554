// The CGAL corefinement reference: against the exact half-space clip, against the closed form
// of two overlapping boxes, and for the symmetries every volume method must have.

#include "volume/cgal/corefinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::TriangleMesh;
using test::relativeDifference;

// Issue #3 tolerances for two exact methods: 1e-9 relative in V, 1e-7 in centroid and
// tensors. Both integrate the same polyhedron exactly; CGAL rounds its exact intersection
// points to double, moving them by ~eps·size, which at d ≥ 1e-3·size is ≤ 1e-12 relative.
constexpr double kVolumeTol = 1e-9;
constexpr double kMomentTol = 1e-7;

void expectSameContact(const ContactVolume& a, const ContactVolume& b) {
  ASSERT_GT(b.volume, 0.0);
  EXPECT_NEAR(a.volume, b.volume, kVolumeTol * b.volume);
  const double width = std::cbrt(b.volume);  // the region's size, for the centroid
  EXPECT_LE((a.p_WC - b.p_WC).norm(), kMomentTol * (b.p_WC.norm() + width));
  EXPECT_LE(relativeDifference(a.J_v, b.J_v), kMomentTol);
  EXPECT_LE(relativeDifference(a.J_s, b.J_s), kMomentTol);
  EXPECT_LE((a.n_W - b.n_W).norm(), kMomentTol);
}

TEST(CgalReference, AgreesWithHalfspaceClip) {
  struct Case {
    std::string name;
    TriangleMesh mesh;
    double size;
  };
  const Case cases[] = {{"sphere", geometry::tessellateSphere(0.0137, 48, 25), 0.0137},
                        {"cylinder", geometry::tessellateCylinder(0.009, 0.031, 64), 0.031},
                        {"torus", geometry::tessellateTorus(0.021, 0.0071, 48, 16), 0.028},
                        {"l_bracket", test::lBracket(0.023, 0.0061, 0.017), 0.023}};
  const Isometry3d X_WH = test::randomPose(21);
  for (const Case& c : cases) {
    const geometry::MeshBvh bvh(c.mesh);
    for (unsigned seed : {4u, 5u}) {
      for (double relDepth : {1e-3, 0.05, 0.3}) {
        SCOPED_TRACE(c.name + " seed " + std::to_string(seed) + " d " + std::to_string(relDepth));
        // The mesh centre a little under the plane's level by relDepth·size from its lowest.
        Isometry3d X_HM = test::randomPose(seed);
        double zmin = INFINITY;
        for (Eigen::Index i = 0; i < c.mesh.vertexCount(); ++i) {
          zmin = std::min(zmin, (X_HM * c.mesh.vertex(i)).z());
        }
        X_HM.translation().z() -= zmin + relDepth * c.size;
        const Isometry3d X_WM = X_WH * X_HM;
        const ContactVolume clip = meshHalfspaceContact(bvh, X_WM, X_WH);
        const ContactVolume cgal = cgalMeshHalfspaceContact(c.mesh, X_WM, X_WH).aggregate;
        expectSameContact(cgal, clip);
        EXPECT_EQ(cgal.method, Method::kCgal);
      }
    }
  }
}

// Box A (a_x, a_y, a_z) resting with its bottom d into box B below, A's footprint inside B's:
// the region is a box a_x × a_y × d; V = a_x a_y d, centroid at the middle of it,
// Σ = V diag(a_x², a_y², d²)/12, n = +z (MODEL.md §1: out of B into A). Re-run under a
// pose that moves both, with dimensions not representable in binary.
TEST(CgalReference, OverlappingBoxesClosedForm) {
  const Vector3d a(0.0113, 0.0071, 0.0093), b(0.031, 0.027, 0.0117);
  const double d = 0.00137;
  const Vector3d offset(0.0031, -0.0043, 0.0);  // A's footprint stays inside B's
  const Isometry3d X_WB = test::randomPose(8);
  const Isometry3d X_WA =
      X_WB * test::translation(offset + Vector3d(0, 0, 0.5 * b.z() + 0.5 * a.z() - d));
  const ContactVolume cv =
      cgalMeshMeshContact(geometry::tessellateBox(a), X_WA, geometry::tessellateBox(b), X_WB)
          .aggregate;
  const double V = a.x() * a.y() * d;
  const Matrix3d R = X_WB.linear();
  const Matrix3d Sigma_B = V / 12.0 * Vector3d(a.x() * a.x(), a.y() * a.y(), d * d).asDiagonal();
  const ContactVolume expected =
      assembleContactVolume(V, X_WB * (offset + Vector3d(0, 0, 0.5 * (b.z() - d))),
                            R * Sigma_B * R.transpose(), R.col(2), a.x() * a.y(), d, Method::kCgal);
  expectSameContact(cv, expected);
  // Exact constructions, rounded once to double: far below 1e-9 of the box's own size.
  EXPECT_NEAR(cv.area, expected.area, 1e-9 * expected.area);
  EXPECT_NEAR(cv.depth, d, 1e-9 * d);
}

// Peg in hole: a cylinder through a torus whose hole is slightly narrower. Swapping the
// bodies keeps V, p_c and J and flips n (MODEL.md §1); 1e-9/1e-7 as for two exact methods.
TEST(CgalReference, SwappingBodiesFlipsOnlyTheNormal) {
  const TriangleMesh peg = geometry::tessellateCylinder(0.0052, 0.03, 40);
  const TriangleMesh ring = geometry::tessellateTorus(0.0111, 0.0061, 40, 16);
  const Isometry3d X_WR = test::randomPose(2);
  Isometry3d X_RP = test::translation(Vector3d(0.0004, 0.0, 0.003));
  X_RP.linear() = Eigen::AngleAxisd(0.2, Vector3d::UnitX()).toRotationMatrix();
  const Isometry3d X_WP = X_WR * X_RP;
  const ContactVolume ab = cgalMeshMeshContact(peg, X_WP, ring, X_WR).aggregate;
  const ContactVolume ba = cgalMeshMeshContact(ring, X_WR, peg, X_WP).aggregate;
  expectSameContact(ab, swapped(ba));
}

// A "U" on its legs in a half-space, and in a box whose top face is the same plane: the
// corefined region has two components, each matching the exact clip's patch (same order,
// sortPatches) to the exact-method tolerances, with the plate's normal.
TEST(CgalReference, PatchesAgreeWithHalfspaceClip) {
  const TriangleMesh u = test::uPrism({0.0107, 0.0213, 0.0071, 0.0093, 0.0161}, 0.0123);
  const geometry::MeshBvh bvh(u);
  const geometry::MeshTopology topo(u);
  const Isometry3d X_WH = test::randomPose(11);
  const Isometry3d X_WM = X_WH * test::translation({0, 0, -0.0031}) *
                          Isometry3d(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()));
  const ContactPatches clip = meshHalfspacePatches(bvh, topo, X_WM, X_WH);
  const Vector3d plate(0.1, 0.1, 0.05);  // encloses the feet; top face z_H = 0
  const ContactPatches inHalfspace = cgalMeshHalfspaceContact(u, X_WM, X_WH);
  const ContactPatches inBox = cgalMeshMeshContact(u, X_WM, geometry::tessellateBox(plate),
                                                   X_WH * test::translation({0, 0, -0.025}));
  ASSERT_EQ(clip.patches.size(), 2u);
  for (const ContactPatches* cgal : {&inHalfspace, &inBox}) {
    ASSERT_EQ(cgal->patches.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      const ContactVolume& a = cgal->patches[k];
      const ContactVolume& b = clip.patches[k];
      EXPECT_NEAR(a.volume, b.volume, kVolumeTol * b.volume);
      EXPECT_LE((a.p_WC - b.p_WC).norm(), kMomentTol * 0.0161);
      EXPECT_LE(relativeDifference(a.J_v, b.J_v), kMomentTol);
      EXPECT_LE((a.n_W - b.n_W).norm(), kMomentTol);
    }
    EXPECT_NEAR(cgal->patches[0].volume + cgal->patches[1].volume, cgal->aggregate.volume,
                1e-12 * cgal->aggregate.volume);  // two sums of the same faces in two orders
  }
}

// Apart, and a face resting exactly on a face (zero-volume contact): no contact, no NaN.
TEST(CgalReference, NoContactGivesZeroWithoutNaN) {
  const TriangleMesh box = geometry::tessellateBox(Vector3d(0.01, 0.01, 0.01));
  for (double gap : {0.001, 0.0}) {
    const ContactVolume cv = cgalMeshMeshContact(box, test::translation({0.002, 0.001, 0.01 + gap}),
                                                 box, Isometry3d::Identity())
                                 .aggregate;
    EXPECT_EQ(cv.volume, 0.0);
    EXPECT_TRUE(cv.p_WC.allFinite() && cv.J_v.allFinite() && std::isfinite(cv.r_gyr));
  }
}

}  // namespace
}  // namespace vcontact::volume
