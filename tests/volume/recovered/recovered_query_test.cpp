// The method table's `recovered` row (volume/recovered/recovered_query.hpp) through the one
// query, computeContact: the bundled peg tilted 5° in the bundled block touches the bore's wall
// at both ends on opposite sides, and the slices give two patches as `fast` does on the
// polyhedra, and the whole agrees with the refinement of both meshes; each patch is summed from
// its own slices, so the patches add up to the whole (volume, first and second moments) to
// rounding, an independent check of the split. A peg pressed sideways along its length is one
// patch, the whole. A spool on its side on the plane touches it with both collars: two patches on
// the recovered surfaces as on the polyhedra; three balls of one mesh, refined, three. A mesh on a
// half-space without a closed form falls back to the exact clip, says why, and keeps the clip's
// patches; a sphere on the plane is the closed form; the row refuses primitives.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "io/shape_spec.hpp"
#include "volume/contact.hpp"
#include "volume/recovered/recovered_surface.hpp"
#include "volume/recovered/refinement.hpp"
#include "volume/revolution_references.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

geometry::Shape bundled(const std::string& name) {
  const std::string dir = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/meshes/";
  return geometry::Mesh{std::make_shared<geometry::TriangleMesh>(io::readMesh(dir + name).mesh),
                        name};
}

QueryOptions recovered() {
  QueryOptions q;
  q.method = Method::kRecovered;
  q.depth = DepthMode::kDeepest;
  return q;
}

// Σ = J-derived second moment about the world origin of one region: ∫ p pᵀ dV from its
// centroid, V and J_v (J_v = tr(Σ_c) I − Σ_c, so Σ_c = tr(J_v)/2 I − J_v).
Matrix3d secondMoment(const ContactVolume& cv) {
  const Matrix3d central = 0.5 * cv.J_v.trace() * Matrix3d::Identity() - cv.J_v;
  return central + cv.volume * cv.p_WC * cv.p_WC.transpose();
}

// The pose: the peg 1.16 mm off the bore's axis, its middle 11.8 mm up, rolled 5°.
TEST(RecoveredQuery, TiltedPegInItsBoreIsTwoPatchesOnOppositeWalls) {
  const geometry::Shape peg = bundled("peg_d10.stl"), block = bundled("block_hole_d10.stl");
  const Isometry3d X_WA = io::parsePose("0,-0.00116,0.0118,5,0,0", "pose");
  const ContactPatches c = computeContact(peg, X_WA, block, Isometry3d::Identity(), recovered());
  ASSERT_EQ(c.surface.representation, Representation::kRevolutionInBore) << c.surface.reason;
  ASSERT_EQ(c.patches.size(), 2u);
  QueryOptions fast;
  fast.method = Method::kFast;
  const ContactPatches poly = computeContact(peg, X_WA, block, Isometry3d::Identity(), fast);
  ASSERT_EQ(poly.patches.size(), 2u);  // the polyhedra agree on the count
  const ContactVolume &p0 = c.patches[0], &p1 = c.patches[1];
  EXPECT_LT(p0.n_W.dot(p1.n_W), -0.9);  // opposite walls
  // the peg's lower 3.2 mm are in the block: one patch at the rim of the bore (z = 0), one at
  // the peg's tip, 2.6 mm apart along its axis
  const Vector3d axis = X_WA.linear().col(2);
  EXPECT_GT(std::abs(axis.dot(p0.p_WC - p1.p_WC)), 2e-3);
  // the whole against the refinement of both meshes (an independent method on the same
  // surfaces, its own estimate 0.1 %): within both bounds. At this pose the slices once missed
  // the rim's region, which lives inside the band where the block's face crosses the peg's
  // slices, between two presence samples (4.06e-11 m³ against 7.23e-11)
  const RecoveredContact ref = refinedMeshMeshContact(
      *recoverSurface(std::get<geometry::Mesh>(peg).mesh)->body, X_WA,
      *recoverSurface(std::get<geometry::Mesh>(block).mesh)->body, Isometry3d::Identity());
  ASSERT_EQ(ref.representation, Representation::kRefined);
  EXPECT_NEAR(c.aggregate.volume, ref.cv.volume,
              ref.volume_error_bound + c.surface.volume_error_bound + 1e-3 * ref.cv.volume);
  EXPECT_NEAR(c.aggregate.volume, ref.cv.volume, 1e-3 * ref.cv.volume);
  // the same regions as the polyhedra's, patch for patch by position (within a few peg radii
  // of each other's centroid: the 64-gon's chords move them by far less than the peg's size)
  for (const ContactVolume& p : c.patches) {
    double nearest = 1.0;
    for (const ContactVolume& q : poly.patches)
      nearest = std::min(nearest, (p.p_WC - q.p_WC).norm());
    EXPECT_LT(nearest, 1e-3) << "a recovered patch with no polyhedral patch near it";
  }
  // the patches add up to the whole: V, ∫p dV, ∫p pᵀ dV (the aggregate is summed over all the
  // slices in one sum, the patches over theirs: rounding of the quadrature's sums, 1e-12)
  const double V = p0.volume + p1.volume;
  EXPECT_NEAR(V, c.aggregate.volume, 1e-12 * V);
  const Vector3d m1 = p0.volume * p0.p_WC + p1.volume * p1.p_WC;
  EXPECT_NEAR((m1 - c.aggregate.volume * c.aggregate.p_WC).norm(), 0.0, 1e-10 * V * 0.03);
  const Matrix3d m2 = secondMoment(p0) + secondMoment(p1);
  EXPECT_NEAR((m2 - secondMoment(c.aggregate)).norm(), 0.0, 1e-9 * V * 0.03 * 0.03);
  EXPECT_EQ(c.aggregate.method, Method::kRecovered);
  for (const ContactVolume& p : c.patches) {
    EXPECT_EQ(p.method, Method::kRecovered);
    EXPECT_GT(p.depth, 0.0);
    EXPECT_LE(p.depth, c.aggregate.depth);
  }
  // swapped: the same patches, normals reversed
  const ContactPatches s = computeContact(block, Isometry3d::Identity(), peg, X_WA, recovered());
  ASSERT_EQ(s.patches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR((s.patches[i].n_W + c.patches[i].n_W).norm(), 0.0, 1e-12);
    EXPECT_NEAR(s.patches[i].volume, c.patches[i].volume, 1e-12 * V);
  }
}

// Pressed sideways by 50 µm along its whole length in the bore: one run, the whole.
TEST(RecoveredQuery, PegPressedSidewaysIsOnePatch) {
  const geometry::Shape peg = bundled("peg_d10.stl"), block = bundled("block_hole_d10.stl");
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.translation() = Vector3d(0.0051 - 0.005 + 5e-5, 0.0, -0.01);
  const ContactPatches c = computeContact(peg, X_WA, block, Isometry3d::Identity(), recovered());
  ASSERT_EQ(c.surface.representation, Representation::kRevolutionInBore) << c.surface.reason;
  ASSERT_EQ(c.patches.size(), 1u);
  EXPECT_EQ(c.patches[0].volume, c.aggregate.volume);
  EXPECT_EQ(c.patches[0].p_WC, c.aggregate.p_WC);
  EXPECT_TRUE(c.surface.reason.empty());
}

// A spool (two collars of radius R and width w joined by 45° cones to a waist of radius rb, each
// cone tessellated in four rings, so that its faces lie on no sphere or torus) lying on its side
// 100 µm into the plane touches it with both collars: two patches on the recovered surfaces as
// on the polyhedra. Each recovered patch is one collar's segment times w plus the wetted slices
// of its cone, which are a pin's chamfer (pinOnItsSide(R, w + 2c, c, d) is a collar of width w
// with such a chamfer at each end); the polyhedra's patches lie at the same places, their
// volumes within the 64-gon's faceting (its flats sit R(1 − cos π/64) = 6 µm inside the circle,
// a few tens of percent of V at this depth).
TEST(RecoveredQuery, SpoolOnItsSideIsTwoPatchesOnEveryRepresentation) {
  const double R = 0.005, rb = 0.003, w = 0.004, L = 0.03, d = 1e-4, c = R - rb;
  std::vector<Eigen::Vector2d> profile = {{R, 0.0}, {R, w}};
  for (int i = 1; i <= 4; ++i) profile.emplace_back(R - 0.25 * i * c, w + 0.25 * i * c);
  for (int i = 3; i >= 0; --i) profile.emplace_back(R - 0.25 * i * c, L - w - 0.25 * i * c);
  profile.emplace_back(R, L);
  const geometry::Shape spool{geometry::Mesh{
      std::make_shared<geometry::TriangleMesh>(geometry::tessellateRevolution(profile, 64)),
      "spool"}};
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
  X_WA.translation().z() = R - d;
  const geometry::Shape plane = geometry::HalfSpace{};
  const ContactPatches rec =
      computeContact(spool, X_WA, plane, Isometry3d::Identity(), recovered());
  ASSERT_EQ(rec.surface.representation, Representation::kRevolution) << rec.surface.reason;
  ASSERT_EQ(rec.patches.size(), 2u);
  const double collar = 0.5 * (test::pinOnItsSide(R, w + 2.0 * c, c, d) + w * test::segment(R, d));
  for (const ContactVolume& p : rec.patches) {
    EXPECT_NEAR(p.volume, collar, 1e-7 * collar);
    EXPECT_NEAR(p.p_WC.y(), 0.0, 1e-9);
  }
  EXPECT_NEAR(rec.aggregate.volume, rec.patches[0].volume + rec.patches[1].volume,
              1e-14 * rec.aggregate.volume);
  for (const Method m : {Method::kHalfspace, Method::kCgal, Method::kColumns}) {
    QueryOptions q;
    q.method = m;
    const ContactPatches poly = computeContact(spool, X_WA, plane, Isometry3d::Identity(), q);
    SCOPED_TRACE(methodName(m));
    ASSERT_EQ(poly.patches.size(), 2u);
    for (const ContactVolume& p : poly.patches) {
      // the recovered patch at the same end of the spool
      const ContactVolume& same = (p.p_WC.x() < 0.5 * L) == (rec.patches[0].p_WC.x() < 0.5 * L)
                                      ? rec.patches[0]
                                      : rec.patches[1];
      EXPECT_LT((p.p_WC - same.p_WC).norm(), 0.05 * w);
      EXPECT_NEAR(p.volume, same.volume, 0.5 * same.volume);
    }
  }
}

// Three 32 × 16 balls of one mesh, their centres a triangle, 50 µm into the plane with
// refinement: no closed form takes three spheres off one axis, so the faces that reach the plane
// are refined, and the finest level's regions are three patches, each its ball's cap within the
// refinement's tolerance (0.1 %, RefinementOptions::tolerance; the Richardson estimate
// volume_error_bound is an estimate: here 7.0e-14 m³ for an error of 7.2e-14 m³).
TEST(RecoveredQuery, ThreeBallsRefinedOnThePlaneAreThreePatches) {
  const double R = 0.005, d = 5e-5;
  const geometry::TriangleMesh ball = geometry::tessellateSphere(R, 32, 16);
  const Vector3d centres[3] = {{0.0, 0.0, 0.0}, {0.02, 0.0, 0.0}, {0.01, 0.015, 0.0}};
  geometry::TriangleMesh balls;
  const Eigen::Index nv = ball.vertexCount(), nt = ball.triangleCount();
  balls.vertices.resize(3 * nv, 3);
  balls.triangles.resize(3 * nt, 3);
  for (int i = 0; i < 3; ++i) {
    balls.vertices.middleRows(i * nv, nv) = ball.vertices.rowwise() + centres[i].transpose();
    balls.triangles.middleRows(i * nt, nt) = ball.triangles.array() + static_cast<int>(i * nv);
  }
  const geometry::Shape shape{
      geometry::Mesh{std::make_shared<geometry::TriangleMesh>(balls), "three balls"}};
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.translation().z() = R - d;
  QueryOptions q = recovered();
  q.refine = true;
  const geometry::Shape plane = geometry::HalfSpace{};
  const ContactPatches c = computeContact(shape, X_WA, plane, Isometry3d::Identity(), q);
  ASSERT_EQ(c.surface.representation, Representation::kRefined) << c.surface.reason;
  ASSERT_EQ(c.patches.size(), 3u);
  const double cap = M_PI * d * d * (3 * R - d) / 3;
  double sum = 0.0;
  const double tolerance = RefinementOptions{}.tolerance;
  ASSERT_TRUE(c.surface.converged);
  for (const ContactVolume& p : c.patches) {
    EXPECT_NEAR(p.volume, cap, tolerance * cap);
    sum += p.volume;
  }
  EXPECT_NEAR(sum, c.aggregate.volume, 1e-12 * c.aggregate.volume);
  EXPECT_NEAR(c.aggregate.volume, 3.0 * cap, tolerance * 3.0 * cap);
}

// A 32 × 16 sphere 10 µm into the plane: the cap's closed form; a box (planes only) has none
// and is the exact clip with its reason; a cylinder primitive is not the row's.
TEST(RecoveredQuery, OnAPlaneClosedFormElseTheClip) {
  const double R = 0.01, d = 1e-5;
  const geometry::Shape ball{geometry::Mesh{
      std::make_shared<geometry::TriangleMesh>(geometry::tessellateSphere(R, 32, 16)), "ball"}};
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.translation().z() = R - d;
  const geometry::Shape plane = geometry::HalfSpace{};
  const ContactPatches c = computeContact(ball, X_WA, plane, Isometry3d::Identity(), recovered());
  ASSERT_EQ(c.surface.representation, Representation::kSphere) << c.surface.reason;
  const double cap = M_PI * d * d * (3 * R - d) / 3;
  EXPECT_NEAR(c.aggregate.volume, cap, 1e-9 * cap);
  ASSERT_EQ(c.patches.size(), 1u);
  const geometry::Shape box{geometry::Mesh{
      std::make_shared<geometry::TriangleMesh>(geometry::tessellateBox(Vector3d(0.01, 0.01, 0.01))),
      "box"}};
  X_WA.translation().z() = 0.005 - d;
  const ContactPatches b = computeContact(box, X_WA, plane, Isometry3d::Identity(), recovered());
  EXPECT_EQ(b.surface.representation, Representation::kShape);
  EXPECT_FALSE(b.surface.reason.empty());
  QueryOptions clip;
  clip.method = Method::kHalfspace;
  const ContactPatches ref = computeContact(box, X_WA, plane, Isometry3d::Identity(), clip);
  EXPECT_EQ(b.aggregate.volume, ref.aggregate.volume);  // the clip itself
  EXPECT_EQ(b.patches.size(), ref.patches.size());
  EXPECT_FALSE(handles(Method::kRecovered, geometry::Cylinder{0.01, 0.02}, plane));
  EXPECT_TRUE(handles(Method::kRecovered, plane, box));
  EXPECT_TRUE(handles(Method::kRecovered, box, box));
}

}  // namespace
}  // namespace vcontact::volume
