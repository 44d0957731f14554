// Contact on recovered surfaces without a closed form, by local refinement
// (geometry/surface_refinement.hpp, volume/recovered/refinement.hpp): the refinement is a
// valid closed mesh; a chamfered pin, a cone frustum and a torus on a plate and a pin in a bore
// against references that do not use the refinement; planes alone stay exactly as they were.

#include "volume/recovered/refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "geometry/mesh_check.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/surface_refinement.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "support/test_support.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/revolution_references.hpp"

namespace vcontact::volume {
namespace {

using geometry::recogniseSurfaces;
using geometry::TriangleMesh;
using vcontact::test::chamferedPin;
using vcontact::test::pinOnItsSide;
using vcontact::test::pinOutsideBore;
using vcontact::test::segment;

// The refinement aims at 0.1 % (RefinementOptions::tolerance) and reports a Richardson
// estimate; the tests accept 0.2 %: the estimate is of the leading 1/k² term only, and the
// references below carry errors of their own of 1e-5 or less.
constexpr double kAccepted = 2e-3;

// The refinement itself, on the faces that reach the plane: the bodies below are solids of
// revolution, which halfspaceContact answers by closed-form slices instead
// (recovered/revolution_body_test.cpp).
RecoveredContact refined(const RecoveredBody& body, const Eigen::Isometry3d& X_WM,
                         const Eigen::Isometry3d& X_WH) {
  return refinedHalfspaceContact(body, body.reachingFaces(X_WH.inverse() * X_WM), X_WM, X_WH);
}

TEST(SurfaceRefinement, IsClosedOrientedAndOnTheSurface) {
  const TriangleMesh pin = chamferedPin(0.005, 0.03, 0.001, 32);
  const geometry::SurfaceRecognition rec = recogniseSurfaces(pin);
  std::vector<int> all(static_cast<std::size_t>(pin.triangleCount()));
  for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
  const geometry::SurfaceRefinement same = geometry::refineSurfaces(pin, rec, all, 1);
  EXPECT_EQ(same.mesh.triangles, pin.triangles);
  EXPECT_EQ(same.mesh.vertices, pin.vertices);
  // half of the faces, so that split faces meet fanned ones
  const std::vector<int> half(all.begin(), all.begin() + static_cast<long>(all.size() / 2));
  for (int level : {2, 7}) {
    geometry::SurfaceRefinement r = geometry::refineSurfaces(pin, rec, half, level);
    EXPECT_GT(r.split_faces, 0);
    EXPECT_GT(r.fanned_faces, 0);
    const geometry::MeshCheckResult check = geometry::checkAndRepair(r.mesh);
    EXPECT_FALSE(check.flipped) << level;
    EXPECT_EQ(check.shells, 1u);
    // Every vertex of a split face lies on that face's surface (within the recognition
    // tolerance) or on the chord of a crease the two surfaces do not share.
    for (Eigen::Index f = 0; f < r.mesh.triangleCount(); ++f) {
      const int s = rec.face_surface[static_cast<std::size_t>(r.origin[f])];
      if (std::find(half.begin(), half.end(), r.origin[f]) == half.end() || s < 0) continue;
      const Eigen::Vector3d c =
          (r.mesh.corner(f, 0) + r.mesh.corner(f, 1) + r.mesh.corner(f, 2)) / 3.0;
      // the centroid of a sub-face misses the surface by its small chord gap only
      EXPECT_LT(std::abs(geometry::signedDistance(rec.surfaces[static_cast<std::size_t>(s)], c)),
                geometry::chordGap(pin, rec, r.origin[f]) / (level * level) * 1.5 + 1e-12);
    }
  }
}

TEST(RecoveredRefinement, ChamferedPinOnItsSideConvergesToTheTrueSolid) {
  const double r = 0.005, L = 0.03, c = 0.0005;
  const TriangleMesh pin = chamferedPin(r, L, c, 64);
  const geometry::SurfaceRecognition rec = recogniseSurfaces(pin);
  const RecoveredBody body(pin, rec);
  for (double ratio : {1e-3, 1e-2}) {
    const double d = ratio * r;
    const double expected = pinOnItsSide(r, L, c, d);
    for (unsigned seed : {0u, 7u}) {
      const Eigen::Isometry3d X_WH = seed ? test::randomPose(seed) : Eigen::Isometry3d::Identity();
      Eigen::Isometry3d X_HM = Eigen::Isometry3d::Identity();  // axis along x, a vertex row down
      X_HM.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
      X_HM.translation() = Eigen::Vector3d(0.001, 0.002, r - d);
      ASSERT_NEAR((X_HM.linear() * Eigen::Vector3d(r, 0, 0)).z(), -r, 1e-15);
      const RecoveredContact got = refined(body, X_WH * X_HM, X_WH);
      ASSERT_EQ(got.representation, Representation::kRefined) << got.reason;
      EXPECT_TRUE(got.converged);
      EXPECT_NEAR(got.cv.volume, expected, kAccepted * expected) << ratio << ' ' << seed;
      // the error estimate is of the size of the error: no smaller than a tenth of it
      EXPECT_GE(got.volume_error_bound, 0.1 * std::abs(got.cv.volume - expected));
      const double poly = meshHalfspaceContact(pin, X_WH * X_HM, X_WH).volume;
      EXPECT_GT(std::abs(poly - expected), 10.0 * std::abs(got.cv.volume - expected));
      bool cone = false;
      for (const PatchPart& p : got.parts)
        cone |= p.surface == "cone" && p.representation == "refined";
      EXPECT_TRUE(cone);
    }
  }
}

// A frustum lying on a generator: its reference is the polyhedral clip of a 16,384-segment
// tessellation of the same frustum, made apart from the refinement (its chords miss the cone
// by r·π²/(2n²) ≈ 2e-8 r, which moves V at d/r = 1e-2 by about 4e-6 of itself).
TEST(RecoveredRefinement, ConeFrustumOnAGeneratorMatchesAFineTessellation) {
  const double r0 = 0.01, r1 = 0.006, h = 0.02;
  const auto frustum = [&](int n) {
    return geometry::tessellateRevolution({{r0, 0.0}, {r1, h}}, n);
  };
  const TriangleMesh coarse = frustum(64), fine = frustum(16384);
  const geometry::SurfaceRecognition rec = recogniseSurfaces(coarse);
  const double d = 1e-2 * r1;
  // the cone's outward normal along the generator at angle 0 turned straight down
  const Eigen::Vector3d n_M = Eigen::Vector3d(h, 0.0, r0 - r1).normalized();
  Eigen::Isometry3d X_HM = Eigen::Isometry3d::Identity();
  X_HM.linear() =
      Eigen::Quaterniond::FromTwoVectors(n_M, -Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double lowest = (X_HM.linear() * Eigen::Vector3d(r0, 0, 0)).z();
  X_HM.translation() = Eigen::Vector3d(0, 0, -lowest - d);
  const Eigen::Isometry3d X_WH = test::randomPose(11);
  const double expected = meshHalfspaceContact(fine, X_WH * X_HM, X_WH).volume;
  const RecoveredContact got = refined(RecoveredBody(coarse, rec), X_WH * X_HM, X_WH);
  ASSERT_EQ(got.representation, Representation::kRefined) << got.reason;
  EXPECT_NEAR(got.cv.volume, expected, kAccepted * expected);
}

// A torus lying flat pressed d into a plate: by Pappus, the volume swept by the tube's segment
// of height d about the axis, whose centroid is at the major radius R: V = 2πR·segment(r, d).
TEST(RecoveredRefinement, TorusLyingFlatIsPappusVolume) {
  const double R = 0.03, r = 0.01, d = 1e-2 * r;
  const TriangleMesh m = geometry::tessellateTorus(R, r, 48, 24);
  const geometry::SurfaceRecognition rec = recogniseSurfaces(m);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = r - d;
  const RecoveredContact got =
      RecoveredBody(m, rec).halfspaceContact(X, Eigen::Isometry3d::Identity());
  ASSERT_EQ(got.representation, Representation::kRefined) << got.reason;
  const double expected = 2.0 * M_PI * R * segment(r, d);
  EXPECT_NEAR(got.cv.volume, expected, kAccepted * expected);
  EXPECT_GT(got.level, 1);
}

// Standing on its flat end, the pin touches with the end disk of radius r − c and the start of
// the chamfer: V = ∫₀^d π(r − c + z)² dz. The polyhedron's end is a 64-gon, 0.16 % short of
// the disk; the refinement rounds the rim (the cone and the plane agree on it).
TEST(RecoveredRefinement, PinOnItsFlatEndIsTheRoundDisk) {
  const double r = 0.005, c = 0.0005, d = 1e-6;
  const TriangleMesh pin = chamferedPin(r, 0.03, c, 64);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = -d;
  const RecoveredContact got =
      refined(RecoveredBody(pin, recogniseSurfaces(pin)), X, Eigen::Isometry3d::Identity());
  ASSERT_EQ(got.representation, Representation::kRefined);
  const double a = r - c;
  const double expected = M_PI * (std::pow(a + d, 3) - std::pow(a, 3)) / 3.0;
  EXPECT_NEAR(got.cv.volume, expected, kAccepted * expected);
  const double poly = meshHalfspaceContact(pin, X, Eigen::Isometry3d::Identity()).volume;
  EXPECT_LT(poly, (1.0 - 1e-3) * expected);
}

// A part of planes only (a prism on an L-shaped section tilted onto an edge): nothing to
// refine, and the answer is the clip's, bit for bit.
TEST(RecoveredRefinement, PlanesOnlyStayExactlyTheClip) {
  const TriangleMesh box = geometry::tessellateBox({0.02, 0.03, 0.01});
  Eigen::Isometry3d X = test::randomPose(21);
  X.translation() = Eigen::Vector3d(0.001, 0.0, 0.0);
  const Eigen::Isometry3d X_WH = test::randomPose(22);
  const RecoveredContact got =
      RecoveredBody(box, recogniseSurfaces(box)).halfspaceContact(X_WH * X, X_WH);
  EXPECT_EQ(got.representation, Representation::kShape);
  const ContactVolume clip = meshHalfspaceContact(box, X_WH * X, X_WH);
  ASSERT_TRUE(clip.inContact());
  EXPECT_EQ(got.cv.volume, clip.volume);
  EXPECT_EQ(got.cv.p_WC, clip.p_WC);
}

// A chamfered pin in the bundled block's bore (block_hole_d10.stl: 40 × 40 × 20 mm, a 64-gon
// bore of radius 5.1 mm, single-precision STL), axes parallel, pressed sideways by d into the
// wall along the whole 20 mm of the block (the chamfers lie outside it): V = 20 mm times the
// part of the pin's disk outside the bore's.
TEST(RecoveredRefinement, PinPressedIntoABoreIsTheDiskOutsideTheBore) {
  const std::string dir = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/meshes/";
  const TriangleMesh block = io::readMesh(dir + "block_hole_d10.stl").mesh;
  const geometry::SurfaceRecognition blockRec = recogniseSurfaces(block);
  const double r = 0.005, R = 0.0051, L = 0.03, depth = 0.02;
  const TriangleMesh pin = chamferedPin(r, L, 0.0005, 64);
  const geometry::SurfaceRecognition pinRec = recogniseSurfaces(pin);
  const RecoveredBody a(pin, pinRec), b(block, blockRec);
  for (double ratio : {1e-3, 1e-2}) {
    const double d = ratio * r, e = R - r + d;
    const double expected = depth * pinOutsideBore(r, R, e);
    const Eigen::Vector3d side = Eigen::Vector3d(std::cos(0.3), std::sin(0.3), 0.0);
    Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();
    X_BA.translation() = e * side + Eigen::Vector3d(0, 0, -0.025);
    RecoveredContact first;
    // under a random rigid motion at the shallower depth only (each query takes seconds)
    const std::vector<unsigned> seeds =
        ratio < 5e-3 ? std::vector<unsigned>{0u, 31u} : std::vector<unsigned>{0u};
    for (unsigned seed : seeds) {
      const Eigen::Isometry3d X_WB = seed ? test::randomPose(seed) : Eigen::Isometry3d::Identity();
      const RecoveredContact got = refinedMeshMeshContact(a, X_WB * X_BA, b, X_WB);
      ASSERT_EQ(got.representation, Representation::kRefined) << got.reason;
      EXPECT_NEAR(got.cv.volume, expected, kAccepted * expected) << ratio;
      EXPECT_TRUE(got.converged);
      int refined = 0;
      for (const PatchPart& p : got.parts) refined += p.representation == "refined";
      EXPECT_EQ(refined, 2);  // the pin's cylinder and the block's concave bore
      if (!seed) {
        first = got;
        continue;
      }
      // the refinements are made in the body frames, so a rigid motion of both changes only
      // the rounding of the fast method's crossings and sums: 1e-9 of V is far above that
      EXPECT_NEAR(got.cv.volume, first.cv.volume, 1e-9 * expected);
      EXPECT_NEAR((got.cv.p_WC - X_WB * first.cv.p_WC).norm(), 0.0, 1e-9);
    }
    // the polyhedra: the fast method on the unrefined meshes
    const geometry::MeshBvh ta(pin), tb(block);
    const ContactVolume poly =
        meshMeshContact(ta, geometry::MeshTopology(pin), X_BA, tb, geometry::MeshTopology(block),
                        Eigen::Isometry3d::Identity(), nullptr, false)
            .aggregate;
    // The polyhedra are off by 4 % at d/r = 1e-3 and only 0.1 % at 1e-2 (the pin's chords lose
    // interference, the bore's chords add some, and here the two nearly cancel); the refined
    // answer is closer by far at both.
    EXPECT_GT(std::abs(poly.volume - expected), 10.0 * std::abs(first.cv.volume - expected));
    std::cout << "d/r " << ratio << ": V " << expected << ", refined " << first.cv.volume
              << " (level " << first.level << ", bound " << first.volume_error_bound
              << "), polyhedra " << poly.volume << '\n';
  }
}

// Two faceted spheres of r = 10 mm (the bundled 1,440- and 280-face balls) 19.5 mm apart on
// their recovered surfaces: the deepest column of the lens is along the line of centres,
// 2r − c = 0.5 mm. A query leaves the depth out unless RefinementOptions::exact_depth asks
// (one more query of the converged level), and asking changes nothing else. The refined
// surfaces lie within the chord gap G/k² of the spheres at the converged level k, which keeps
// V within its 1e-3 tolerance; the depth, a difference of two radii, is held to the same 1e-3.
TEST(RecoveredRefinement, TheDepthOfTwoRefinedSpheresIsTheirOverlapWhenAsked) {
  const std::string dir = std::string(VCONTACT_ASSETS_DIR) + "/meshes/";
  const TriangleMesh fine = io::readMesh(dir + "ball_r10mm.stl").mesh;
  const TriangleMesh coarse = io::readMesh(dir + "ball_r10mm_2k.stl").mesh;
  const geometry::SurfaceRecognition fineRec = recogniseSurfaces(fine);
  const geometry::SurfaceRecognition coarseRec = recogniseSurfaces(coarse);
  const RecoveredBody a(fine, fineRec), b(coarse, coarseRec);
  const double r = 0.01, c = 0.0195;
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  X_WA.translation().z() = c;
  const RecoveredContact plain = refinedMeshMeshContact(a, X_WA, b, Eigen::Isometry3d::Identity());
  RefinementOptions asked;
  asked.exact_depth = true;
  const RecoveredContact deep =
      refinedMeshMeshContact(a, X_WA, b, Eigen::Isometry3d::Identity(), asked);
  ASSERT_EQ(plain.representation, Representation::kRefined) << plain.reason;
  EXPECT_TRUE(std::isnan(plain.cv.depth));
  EXPECT_NEAR(deep.cv.depth, 2 * r - c, 1e-3 * (2 * r - c));
  EXPECT_EQ(deep.cv.volume, plain.cv.volume);
  EXPECT_EQ(deep.cv.p_WC, plain.cv.p_WC);
  EXPECT_EQ(deep.level, plain.level);
}

}  // namespace
}  // namespace vcontact::volume
