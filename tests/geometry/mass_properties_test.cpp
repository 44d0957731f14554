// Mass properties by the divergence theorem: exact for a box, convergent to the analytic
// sphere and cylinder as the mesh is refined, and consistent under rigid motion.

#include "geometry/mass_properties.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/tessellate.hpp"
#include "support/test_support.hpp"

namespace vcontact::geometry {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using test::relativeDifference;

TriangleMesh movedMesh(TriangleMesh mesh, const Eigen::Isometry3d& X) {
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    mesh.vertices.row(i) = (X * mesh.vertex(i)).transpose();
  }
  return mesh;
}

TEST(MassProperties, BoxIsExact) {
  // Dimensions not representable in binary, placed off the origin and rotated.
  const Vector3d s(0.031, 0.057, 0.013);
  const Eigen::Isometry3d X = test::randomPose(5);
  const Moments M = meshMoments(movedMesh(tessellateBox(s), X));
  const double V = s.prod();
  const Matrix3d I_body =
      (V / 12.0) * Vector3d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                            s.x() * s.x() + s.y() * s.y())
                       .asDiagonal();
  // A 12-face sum: rounding only, a few ulps of the largest term.
  EXPECT_NEAR(M.m0 / V, 1.0, 1e-13);
  EXPECT_LT((M.centroid() - X.translation()).norm(), 1e-15);
  EXPECT_LT(relativeDifference(M.centralInertia(), X.linear() * I_body * X.linear().transpose()),
            1e-12);
}

TEST(MassProperties, PrimitiveClosedFormsMatchTheirMeshesInTheLimit) {
  // solidMoments(box) must equal the box mesh exactly; sphere and cylinder converge.
  const Vector3d s(0.2, 0.3, 0.5);
  const Moments box = solidMoments(Box{s});
  const Moments boxMesh = meshMoments(tessellateBox(s));
  // The same solid, summed in 12 triangles instead of a closed form: rounding only (a few ulps).
  EXPECT_NEAR(box.m0 / boxMesh.m0, 1.0, 1e-14);
  EXPECT_LT(relativeDifference(box.m2, boxMesh.m2), 1e-14);
}

// An inscribed polyhedron with n segments misses a fraction of the volume that falls as
// 1/n² (chord sagitta ∝ (π/n)²): the error is bounded by that and divides by about 4 each
// time n doubles, so a gain or a loss of accuracy is both noticed.
TEST(MassProperties, SphereConvergesQuadratically) {
  const double R = 0.0137;
  const Moments exact = solidMoments(Sphere{R});
  double previous = 0.0;
  for (int n : {16, 32, 64, 128, 256}) {
    const Moments M = meshMoments(tessellateSphere(R, n, n / 2));
    const double err = 1.0 - M.m0 / exact.m0;
    const double errI = 1.0 - M.centralInertia()(0, 0) / exact.centralInertia()(0, 0);
    EXPECT_GT(err, 0.0) << "an inscribed mesh has less volume";
    EXPECT_LT(err, 2.0 * std::pow(M_PI / n, 2)) << n;
    EXPECT_GT(errI, 0.0);
    EXPECT_LT(M.centroid().norm(), 1e-15);
    if (previous > 0.0) {
      // Doubling n divides the error by 4 (ratio within [3.5, 4.5] as higher orders fade).
      EXPECT_GT(previous / err, 3.5) << n;
      EXPECT_LT(previous / err, 4.5) << n;
    }
    previous = err;
  }
}

TEST(MassProperties, CylinderMatchesPolygonPrismExactly) {
  // A cylinder mesh is an exact regular-polygon prism: V = (n/2) R² sin(2π/n) L.
  const double R = 0.0211, L = 0.0473;
  for (int n : {3, 7, 64, 1000}) {
    const Moments M = meshMoments(tessellateCylinder(R, L, n));
    const double V = 0.5 * n * R * R * std::sin(2 * M_PI / n) * L;
    // Exact for the prism: rounding of sums over up to 4,000 faces (1e-12 is ~5,000 ulps).
    EXPECT_NEAR(M.m0 / V, 1.0, 1e-12) << n;
    // Axial moment of inertia of the prism: ∫z² dV = V L²/12.
    EXPECT_NEAR(M.m2(2, 2) / (V * L * L / 12), 1.0, 1e-12) << n;
  }
  const Moments fine = meshMoments(tessellateCylinder(R, L, 4096));
  const Moments exact = solidMoments(Cylinder{R, L});
  EXPECT_NEAR(fine.m0 / exact.m0, 1.0, 1e-6);  // (2π/4096)²/6 ≈ 4e-7
  EXPECT_LT(relativeDifference(fine.centralInertia(), exact.centralInertia()), 2e-6);
}

TEST(MassProperties, MomentsTransformLikeTheSolid) {
  const TriangleMesh torus = tessellateTorus(0.05, 0.013, 48, 24);
  const Eigen::Isometry3d X = test::randomPose(9);
  const Moments direct = meshMoments(movedMesh(torus, X));
  const Moments mapped = transformed(meshMoments(torus), X);
  // Moving the 1,152 vertices rounds each coordinate once, and the two sums of 2,304 faces
  // round differently: 1e-13 is some hundred ulps of the sums, far below any formula error.
  EXPECT_NEAR(direct.m0 / mapped.m0, 1.0, 1e-13);
  EXPECT_LT((direct.m1 - mapped.m1).norm() / mapped.m1.norm(), 1e-13);
  EXPECT_LT(relativeDifference(direct.m2, mapped.m2), 1e-13);
}

TEST(MassProperties, DensityScalesMassAndInertia) {
  const MassProperties p = massProperties(solidMoments(Sphere{0.01}), 7900.0);
  const double m = 7900.0 * 4.0 / 3.0 * M_PI * 1e-6;
  // Products of the same constants in another order: rounding only.
  EXPECT_NEAR(p.mass / m, 1.0, 1e-14);
  EXPECT_NEAR(p.inertia(0, 0) / (0.4 * m * 1e-4), 1.0, 1e-14);  // (2/5) m R²
}

}  // namespace
}  // namespace vcontact::geometry
