// Surface recognition on tessellations of known primitives: the kinds found, the faces they
// cover, and the recovered parameters against the ones the mesh was made from, also after a
// rigid motion, in single precision, and on a surface that is not analytic.

#include "geometry/surface_recognition.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "support/test_support.hpp"

namespace vcontact::geometry {
namespace {

// The vertices of the tessellations lie on the true surface to rounding, and the polish is
// a least-squares fit to them, so the parameters come back to rounding times the
// conditioning of the fit; 1e-9 of the part's size leaves six orders of margin and still
// fails on any faceting error (the chords of these meshes miss their surfaces by 1e-3 or more).
constexpr double kParameterTolerance = 1e-9;

TriangleMesh moved(TriangleMesh m, const Eigen::Isometry3d& X) {
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i)
    m.vertices.row(i) = (X * m.vertex(i)).transpose();
  return m;
}

// A truncated cone of axis z: radius r0 at z = 0, r1 at z = h, `n` segments, capped by fans.
TriangleMesh frustum(double r0, double r1, double h, int n) {
  TriangleMesh m;
  m.vertices.resize(2 * n + 2, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    m.vertices.row(i) << r0 * std::cos(a), r0 * std::sin(a), 0.0;
    m.vertices.row(n + i) << r1 * std::cos(a), r1 * std::sin(a), h;
  }
  m.vertices.row(2 * n) << 0.0, 0.0, 0.0;
  m.vertices.row(2 * n + 1) << 0.0, 0.0, h;
  m.triangles.resize(4 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.row(4 * i) << i, j, n + j;
    m.triangles.row(4 * i + 1) << i, n + j, n + i;
    m.triangles.row(4 * i + 2) << 2 * n, j, i;              // bottom cap, facing −z
    m.triangles.row(4 * i + 3) << 2 * n + 1, n + i, n + j;  // top cap, facing +z
  }
  return m;
}

std::map<SurfaceKind, int> kinds(const SurfaceRecognition& r) {
  std::map<SurfaceKind, int> k;
  for (const RecognisedSurface& s : r.surfaces) ++k[s.kind];
  return k;
}

const RecognisedSurface& only(const SurfaceRecognition& r, SurfaceKind kind) {
  for (const RecognisedSurface& s : r.surfaces)
    if (s.kind == kind) return s;
  throw std::runtime_error(std::string("no ") + surfaceKindName(kind));
}

// The distance between two axes' directions, either way round.
double axisError(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::min((a - b).norm(), (a + b).norm());
}

TEST(SurfaceRecognition, SphereIsOneSphereCoveringEveryFace) {
  const double R = 0.01;
  const TriangleMesh m = tessellateSphere(R, 32, 16);  // 960 triangles
  const SurfaceRecognition r = recogniseSurfaces(m);
  ASSERT_EQ(r.surfaces.size(), 1u) << describe(r.surfaces.at(0));
  const RecognisedSurface& s = r.surfaces[0];
  EXPECT_EQ(s.kind, SurfaceKind::kSphere);
  EXPECT_TRUE(s.convex);
  EXPECT_EQ(static_cast<Eigen::Index>(s.faces.size()), m.triangleCount());
  EXPECT_EQ(r.free_form_faces, 0);
  EXPECT_NEAR(s.radius, R, kParameterTolerance * R);
  EXPECT_LT(s.point.norm(), kParameterTolerance * R);
  EXPECT_LT(s.max_residual, kParameterTolerance * R);
}

TEST(SurfaceRecognition, CylinderIsASideAndTwoCaps) {
  const double R = 0.004, L = 0.02;
  const TriangleMesh m = tessellateCylinder(R, L, 128);  // 512 triangles
  const SurfaceRecognition r = recogniseSurfaces(m);
  EXPECT_EQ(kinds(r),
            (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 2}, {SurfaceKind::kCylinder, 1}}));
  EXPECT_EQ(r.free_form_faces, 0);
  const RecognisedSurface& c = only(r, SurfaceKind::kCylinder);
  EXPECT_NEAR(c.radius, R, kParameterTolerance * L);
  EXPECT_LT(axisError(c.axis, Eigen::Vector3d::UnitZ()), kParameterTolerance);
  EXPECT_LT(c.point.head<2>().norm(), kParameterTolerance * L);
  EXPECT_EQ(c.faces.size(), 256u);
  for (const RecognisedSurface& s : r.surfaces) {
    if (s.kind != SurfaceKind::kPlane) continue;
    EXPECT_NEAR(std::abs(s.axis.z()), 1.0, kParameterTolerance);
    EXPECT_NEAR(std::abs(s.point.z()), L / 2, kParameterTolerance * L);
    EXPECT_NEAR(s.axis.z() * s.point.z(), L / 2, kParameterTolerance * L);  // normals point out
  }
}

TEST(SurfaceRecognition, BoxIsSixPlanes) {
  const TriangleMesh m = tessellateBox({0.03, 0.02, 0.01});
  const SurfaceRecognition r = recogniseSurfaces(m);
  EXPECT_EQ(kinds(r), (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 6}}));
  EXPECT_EQ(r.free_form_faces, 0);
  for (const RecognisedSurface& s : r.surfaces) EXPECT_EQ(s.faces.size(), 2u);
  EXPECT_NEAR(r.surfaces[0].area, 0.03 * 0.02, 1e-15);  // largest first
}

TEST(SurfaceRecognition, TorusIsOneTorus) {
  const double R = 0.03, a = 0.01;
  const TriangleMesh m = tessellateTorus(R, a, 48, 24);
  const SurfaceRecognition r = recogniseSurfaces(m);
  ASSERT_EQ(r.surfaces.size(), 1u) << describe(r.surfaces.at(0));
  const RecognisedSurface& t = r.surfaces[0];
  EXPECT_EQ(t.kind, SurfaceKind::kTorus);
  EXPECT_NEAR(t.radius, R, kParameterTolerance * R);
  EXPECT_NEAR(t.minor_radius, a, kParameterTolerance * R);
  EXPECT_LT(axisError(t.axis, Eigen::Vector3d::UnitZ()), kParameterTolerance);
  EXPECT_EQ(r.free_form_faces, 0);
}

TEST(SurfaceRecognition, FrustumIsAConeAndTwoCaps) {
  const double r0 = 0.01, r1 = 0.006, h = 0.004;  // a 45° chamfer
  const TriangleMesh m = frustum(r0, r1, h, 96);
  const SurfaceRecognition r = recogniseSurfaces(m);
  EXPECT_EQ(kinds(r),
            (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 2}, {SurfaceKind::kCone, 1}}));
  const RecognisedSurface& c = only(r, SurfaceKind::kCone);
  EXPECT_NEAR(c.angle, std::atan((r0 - r1) / h), kParameterTolerance);
  EXPECT_LT((c.point - Eigen::Vector3d(0, 0, h * r0 / (r0 - r1))).norm(), kParameterTolerance * r0);
  EXPECT_LT(axisError(c.axis, Eigen::Vector3d::UnitZ()), kParameterTolerance);
  EXPECT_EQ(r.free_form_faces, 0);
}

TEST(SurfaceRecognition, ParametersFollowARigidMotion) {
  const double R = 0.004, L = 0.02;
  for (unsigned seed : {3u, 17u, 41u}) {
    const Eigen::Isometry3d X = test::randomPose(seed, 0.05);
    const SurfaceRecognition r = recogniseSurfaces(moved(tessellateCylinder(R, L, 128), X));
    const RecognisedSurface& c = only(r, SurfaceKind::kCylinder);
    EXPECT_NEAR(c.radius, R, kParameterTolerance * L) << seed;
    EXPECT_LT(axisError(c.axis, X.linear().col(2)), kParameterTolerance) << seed;
    // the axis passes through the moved origin
    const Eigen::Vector3d w = X.translation() - c.point;
    EXPECT_LT((w - c.axis * c.axis.dot(w)).norm(), kParameterTolerance * L) << seed;
    EXPECT_EQ(r.free_form_faces, 0) << seed;
  }
}

// A 45° chamfer whose two rims are its only vertices lies on the cone through them and on a
// sphere centred on the axis; its edges along the rulings are straight on the cone and cut a
// chord through the sphere, so recognition takes the cone (docs/SURFACES.md, "Recognition").
// The 10 mm pin of 64 segments with 0.5 mm chamfers had them taken for spheres.
TEST(SurfaceRecognition, ChamfersThroughTwoRimsAreCones) {
  const double r = 0.01, L = 0.03, c = 0.0005;
  const TriangleMesh pin = tessellateRevolution({{r - c, 0.0}, {r, c}, {r, L - c}, {r - c, L}}, 64);
  for (unsigned seed : {0u, 5u, 29u}) {
    const Eigen::Isometry3d X =
        seed ? test::randomPose(seed, 0.05) : Eigen::Isometry3d(Eigen::Isometry3d::Identity());
    const SurfaceRecognition rec = recogniseSurfaces(moved(pin, X));
    EXPECT_EQ(kinds(rec),
              (std::map<SurfaceKind, int>{
                  {SurfaceKind::kPlane, 2}, {SurfaceKind::kCylinder, 1}, {SurfaceKind::kCone, 2}}))
        << seed;
    EXPECT_EQ(rec.free_form_faces, 0) << seed;
    // r = r − c + z below, r = r − c + (L − z) above: apexes on the axis, axes into the cones
    const Eigen::Vector3d apex[2] = {X * Eigen::Vector3d(0, 0, c - r),
                                     X * Eigen::Vector3d(0, 0, L - c + r)};
    const Eigen::Vector3d into[2] = {X.linear().col(2), -X.linear().col(2)};
    int found = 0;
    for (const RecognisedSurface& s : rec.surfaces) {
      if (s.kind != SurfaceKind::kCone) continue;
      const int k = (s.point - apex[0]).norm() < (s.point - apex[1]).norm() ? 0 : 1;
      found |= 1 << k;
      EXPECT_NEAR(s.angle, M_PI / 4, kParameterTolerance) << seed;
      EXPECT_LT((s.point - apex[k]).norm(), kParameterTolerance * L) << seed;
      EXPECT_LT((s.axis - into[k]).norm(), kParameterTolerance) << seed;
      EXPECT_TRUE(s.convex) << seed;
      EXPECT_EQ(s.faces.size(), 128u) << seed;
      EXPECT_LT(s.max_residual, kParameterTolerance * L) << seed;
    }
    EXPECT_EQ(found, 3) << seed;  // one cone at each end
  }
}

// A zone of a sphere of radius R between latitudes, rings at `latitudes` (radians, rising),
// 64 segments, flat ends.
TriangleMesh sphereZone(double R, const std::vector<double>& latitudes) {
  std::vector<Eigen::Vector2d> profile;
  for (double a : latitudes) profile.emplace_back(R * std::cos(a), R * std::sin(a));
  return tessellateRevolution(profile, 64);
}

// With a ring between its rims the zone fixes the sphere (three circles lie on no cone), and
// the tie-break has nothing to decide.
TEST(SurfaceRecognition, SphereZoneOfThreeRingsStaysASphere) {
  const double R = 0.01;
  const SurfaceRecognition rec = recogniseSurfaces(sphereZone(R, {0.0, 0.25, 0.5}));
  EXPECT_EQ(kinds(rec),
            (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 2}, {SurfaceKind::kSphere, 1}}));
  const RecognisedSurface& s = only(rec, SurfaceKind::kSphere);
  EXPECT_NEAR(s.radius, R, kParameterTolerance * R);
  EXPECT_LT(s.point.norm(), kParameterTolerance * R);
  EXPECT_EQ(s.faces.size(), 256u);
}

// A zone with vertices on its two rims only is a polyhedron the cone through them holds as
// well as the sphere: its edge midpoints, whatever the triangulation between the rims, lie in
// the meridian plane on the chord between the rims, which is the cone's line and inside the
// sphere's arc. Nothing in the mesh says sphere, and recognition takes the cone.
// The same zone with the top ring turned half a segment, so that no edge is a ruling (an
// antiprism band between two fans).
TriangleMesh twistedZone(double R, double a0, double a1, int n) {
  TriangleMesh m;
  m.vertices.resize(2 * n + 2, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n, u = t + M_PI / n;
    m.vertices.row(i) << R * std::cos(a0) * std::cos(t), R * std::cos(a0) * std::sin(t),
        R * std::sin(a0);
    m.vertices.row(n + i) << R * std::cos(a1) * std::cos(u), R * std::cos(a1) * std::sin(u),
        R * std::sin(a1);
  }
  m.vertices.row(2 * n) << 0.0, 0.0, R * std::sin(a0);
  m.vertices.row(2 * n + 1) << 0.0, 0.0, R * std::sin(a1);
  m.triangles.resize(4 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.row(4 * i) << i, j, n + i;
    m.triangles.row(4 * i + 1) << j, n + j, n + i;
    m.triangles.row(4 * i + 2) << 2 * n, j, i;
    m.triangles.row(4 * i + 3) << 2 * n + 1, n + i, n + j;
  }
  return m;
}

TEST(SurfaceRecognition, SphereZoneOfTwoRingsIsTakenForTheCone) {
  const double R = 0.01, a0 = 0.0, a1 = 0.5;
  for (const TriangleMesh& m : {sphereZone(R, {a0, a1}), twistedZone(R, a0, a1, 64)}) {
    const SurfaceRecognition rec = recogniseSurfaces(m);
    EXPECT_EQ(kinds(rec),
              (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 2}, {SurfaceKind::kCone, 1}}));
    const RecognisedSurface& s = only(rec, SurfaceKind::kCone);
    const double r0 = R * std::cos(a0), r1 = R * std::cos(a1), z1 = R * std::sin(a1);
    EXPECT_NEAR(s.angle, std::atan((r0 - r1) / z1), kParameterTolerance);
    EXPECT_LT((s.point - Eigen::Vector3d(0, 0, z1 * r0 / (r0 - r1))).norm(),
              kParameterTolerance * R);
    EXPECT_EQ(s.faces.size(), 128u);
  }
}

TEST(SurfaceRecognition, SinglePrecisionFileIsStillASphere) {
  const double R = 0.01;
  TriangleMesh m = tessellateSphere(R, 48, 24);
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i)  // what an STL file stores
    for (int k = 0; k < 3; ++k) m.vertices(i, k) = static_cast<float>(m.vertices(i, k));
  const SurfaceRecognition r = recogniseSurfaces(m);
  ASSERT_EQ(r.surfaces.size(), 1u);
  // float rounding moves a vertex by up to 2^-24 of its coordinate: 6e-10 m here
  EXPECT_NEAR(r.surfaces[0].radius, R, 1e-9);
  EXPECT_LT(r.surfaces[0].max_residual, 2e-9);
  EXPECT_EQ(r.free_form_faces, 0);
}

TEST(SurfaceRecognition, RoughSurfaceStaysFreeForm) {
  // A sphere whose vertices are displaced radially by up to 1e-3 of its radius (a scan, a
  // sculpted part): 50 times the tolerance, so no face may be called spherical.
  const double R = 0.01;
  TriangleMesh m = tessellateSphere(R, 32, 16);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) m.vertices.row(i) *= 1.0 + u(rng);
  const SurfaceRecognition r = recogniseSurfaces(m);
  for (const RecognisedSurface& s : r.surfaces)
    EXPECT_NE(s.kind, SurfaceKind::kSphere) << describe(s);
  EXPECT_GT(r.free_form_faces, static_cast<int>(0.9 * static_cast<double>(m.triangleCount())));
}

TEST(SurfaceRecognition, SameMeshSameSurfaces) {
  const TriangleMesh m = tessellateTorus(0.03, 0.01, 48, 24);
  const SurfaceRecognition a = recogniseSurfaces(m), b = recogniseSurfaces(m);
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  EXPECT_EQ(a.face_surface, b.face_surface);
  for (std::size_t i = 0; i < a.surfaces.size(); ++i)
    EXPECT_EQ(a.surfaces[i].radius, b.surfaces[i].radius);
}

TEST(SurfaceRecognition, RefusesBadOptions) {
  const TriangleMesh m = tessellateBox({1, 1, 1});
  EXPECT_THROW(recogniseSurfaces(m, {.tolerance = 0.0}), InputError);
  EXPECT_THROW(recogniseSurfaces(m, {.tolerance = 1e-5, .crease_angle = 2.0}), InputError);
}

}  // namespace
}  // namespace vcontact::geometry
