// The exact local surface integration (volume/fast/surface_integration.hpp) against the CGAL
// corefinement reference on the same poses: convex and non-convex pairs, symmetry, rigid
// invariance, separation, and the degenerate contacts (touching, coplanar, identical).

#include "volume/fast/surface_integration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "geometry/mass_properties.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/moments.hpp"
#include "support/test_support.hpp"
#include "volume/cgal/corefinement.hpp"
#include "volume/contact.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

/// A mesh with its tree and topology, as the dispatcher caches them (by default with the
/// tree the engine builds).
struct Body {
  explicit Body(geometry::TriangleMesh m, int maxLeafSize = geometry::MeshBvh::kDefaultLeafSize)
      : bvh(std::move(m), maxLeafSize), topo(bvh.mesh()) {}
  const geometry::TriangleMesh& mesh() const { return bvh.mesh(); }
  geometry::MeshBvh bvh;
  geometry::MeshTopology topo;
};

/// The query with its exact depth pass (`deepest`; the default leaves depth NaN): the tests
/// below compare every field, depth included, with cgal's.
ContactVolume fast(const Body& a, const Isometry3d& X_WA, const Body& b, const Isometry3d& X_WB) {
  return meshMeshContact(a.bvh, a.topo, X_WA, b.bvh, b.topo, X_WB, nullptr, true).aggregate;
}

/// Worst relative differences of one comparison, to print and to bound.
struct Errors {
  double V = 0, p_WC = 0, J_v = 0, J_s = 0, n_W = 0;  // per ContactVolume member
};

/// fast vs cgal on one pose. Relative errors: V to V; the centroid to the region's size
/// (∛V, so that a far-off origin does not hide an error); tensors by max norm.
Errors compare(const ContactVolume& f, const ContactVolume& c) {
  Errors e;
  e.V = std::abs(f.volume - c.volume) / c.volume;
  e.p_WC = (f.p_WC - c.p_WC).norm() / std::cbrt(c.volume);
  e.J_v = test::relativeDifference(f.J_v, c.J_v);
  e.J_s = test::relativeDifference(f.J_s, c.J_s);
  e.n_W = (f.n_W - c.n_W).norm();
  return e;
}

// The required agreement with the exact reference. Both sum the same polyhedron's fan in
// double from its vertices rounded to double; only the crossing points (rounded once here,
// exact rationals rounded once there) and the summation order differ, a few ε relative per
// term. The terms are of the region's size (apexes at the region), so the result keeps
// ~1e-13 relative; the 1e-9 (V) and 1e-7 (centroid, tensors, normal) are the
// targets, checked as given.
constexpr double kVolumeTol = 1e-9;
constexpr double kMomentTol = 1e-7;

void expectAgree(const Body& a, const Isometry3d& X_WA, const Body& b, const Isometry3d& X_WB,
                 const std::string& what) {
  SCOPED_TRACE(what);
  const ContactVolume c = cgalMeshMeshContact(a.mesh(), X_WA, b.mesh(), X_WB).aggregate;
  const ContactVolume f = fast(a, X_WA, b, X_WB);
  ASSERT_GT(c.volume, 0.0);
  EXPECT_EQ(f.method, Method::kFast);
  EXPECT_TRUE(std::isnan(f.relative_error));
  const Errors e = compare(f, c);
  EXPECT_LE(e.V, kVolumeTol) << f.volume << " vs " << c.volume;
  EXPECT_LE(e.p_WC, kMomentTol);
  EXPECT_LE(e.J_v, kMomentTol);
  EXPECT_LE(e.J_s, kMomentTol);
  EXPECT_LE(e.n_W, kMomentTol);
  EXPECT_NEAR(f.area, c.area, kMomentTol * c.area);
  EXPECT_NEAR(f.depth, c.depth, kMomentTol * c.depth);
  std::printf("%-28s V %.3e  rel errors V %.1e  centroid %.1e  J_v %.1e  J_s %.1e  n %.1e\n",
              what.c_str(), c.volume, e.V, e.p_WC, e.J_v, e.J_s, e.n_W);
}

TEST(FastMeshMesh, TwoSpheres) {
  const Body s(geometry::tessellateSphere(0.01, 32, 17));
  Isometry3d X_WA = Isometry3d::Identity();
  X_WA.linear() = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  X_WA.translation() = Vector3d(0.0013, -0.0007, 0.0198);
  expectAgree(s, X_WA, s, Isometry3d::Identity(), "spheres shallow");
  X_WA.translation() = Vector3d(0.0013, -0.0007, 0.011);
  expectAgree(s, X_WA, s, Isometry3d::Identity(), "spheres deep");
}

Isometry3d pose(const Vector3d& axis, double angle, const Vector3d& t) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = t;
  return X;
}

/// A named pose pair of the cross-method table.
struct Case {
  std::string name;
  std::shared_ptr<const Body> a, b;
  Isometry3d X_WA, X_WB;
};

std::vector<Case> cases() {
  const auto sphere = std::make_shared<const Body>(geometry::tessellateSphere(0.01, 32, 17));
  const auto torus = std::make_shared<const Body>(geometry::tessellateTorus(0.021, 0.0071, 48, 16));
  const auto box = std::make_shared<const Body>(test::subdividedBox(Vector3d(0.06, 0.06, 0.02), 6));
  const auto bracket = std::make_shared<const Body>(test::lBracket(0.04, 0.008, 0.03));
  const auto cube =
      std::make_shared<const Body>(geometry::tessellateBox(Vector3d(0.015, 0.013, 0.011)));
  const auto plate = std::make_shared<const Body>(test::plateWithHole(0.02, 0.006, 0.005, 48));
  const auto peg = std::make_shared<const Body>(geometry::tessellateCylinder(0.0049, 0.03, 40));
  const auto big = std::make_shared<const Body>(geometry::tessellateSphere(0.015, 40, 21));
  const Isometry3d I = Isometry3d::Identity();
  return {
      // Ring-shaped region: the sphere sits in the torus' hole, touching the tube all round.
      {"sphere in torus hole", big, torus, pose({1, 0, 0}, 0.02, {0.0011, 0.0007, 0.0013}), I},
      // Ring-shaped region: the torus lies on the box's top face (z = 0.01), tilted.
      {"torus on box", torus, box,
       pose({1, 0.3, 0}, 0.05, {0.0017, -0.0023, 0.01 + 0.0071 - 0.0009}), I},
      // L-shaped region: a block pushed into the bracket's inner corner (x, y = 0.008).
      {"block in L-bracket corner", cube, bracket,
       pose({0, 0, 1}, 0.1, {0.008 + 0.0075 - 0.0006, 0.008 + 0.0065 - 0.0004, 0.0151}), I},
      // Two separate regions: a tilted peg bears on the hole's top edge on one side and its
      // bottom edge on the other.
      {"tilted peg in hole", peg, plate, pose({1, 0, 0}, 0.05, {0.00003, 0.0, 0.0031}), I},
      {"spheres shallow", sphere, sphere, pose({1, 2, 0}, 0.3, {0.0013, -0.0007, 0.0198}), I},
  };
}

TEST(FastMeshMesh, AgreesWithCgalOnNonConvexPairs) {
  for (const Case& c : cases()) expectAgree(*c.a, c.X_WA, *c.b, c.X_WB, c.name);
}

// The benchmark's pair (benchmarks/volume_bench.cpp, sphere_pair_10k): two 10k-triangle UV
// spheres 0.2 mm deep, B's pole fan of slivers inside the contact, where nearly parallel
// faces straddle each other's planes without meeting and the face-pair rejection
// (certainlyDisjoint) and the filtered edge tests decide most pairs. The same pair under
// random rigid motions of both bodies and with A turned about its centre (new face pairs,
// same depth): any crossing wrongly dropped breaks the segments or moves V by far more than
// kVolumeTol.
TEST(FastMeshMesh, FinelyFacetedShallowPairUnderRigidMotion) {
  const Body s(geometry::tessellateSphere(0.01, 100, 51));
  const Isometry3d X_WA = pose({1, 2, 0}, 0.3, {0.0013, -0.0007, 0.0198});
  expectAgree(s, X_WA, s, Isometry3d::Identity(), "10k spheres, benchmark pose");
  for (unsigned seed = 31; seed < 34; ++seed) {
    const Isometry3d P = test::randomPose(seed);
    expectAgree(s, P * X_WA, s, P, "10k spheres, moved " + std::to_string(seed));
    Isometry3d turned = X_WA;
    turned.linear() = X_WA.linear() * test::randomPose(seed + 100).linear();
    expectAgree(s, turned, s, Isometry3d::Identity(),
                "10k spheres, A turned " + std::to_string(seed));
  }
}

// The leaf pairs kept between queries (MeshMeshCache) along a path of poses as a
// simulation visits them: steps of a tenth of the cache's reach (reused), and now and then a
// jump of several reaches (re-recorded). Each query must give what a query without the cache
// gives: the same polyhedron from the same placed vertices, only the crossings found in
// another order (another integration apex), so the agreement is that of two summation
// orders, far inside the tolerances held against CGAL.
TEST(FastMeshMesh, CachedLeafPairsGiveTheFreshResultAlongAPath) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    MeshMeshCache cache;
    const double reach = MeshMeshCache::kReach *
                         (c.a->bvh.root().halfExtent.norm() + c.b->bvh.root().halfExtent.norm());
    Isometry3d X_WA = c.X_WA;
    int jumps = 0, inContact = 0;
    for (int k = 0; k < 60; ++k) {
      const bool jump = k % 20 == 19;
      const double step = (jump ? 3.0 : 0.1) * reach;
      const Isometry3d P = test::randomPose(1000 + k);
      // A small rigid motion of A about its pose: translation `step` along a random
      // direction (bounded so that A stays near the contact), rotation of step / 0.05 m.
      const Vector3d t = P.linear().col(0) * step;
      X_WA.translation() =
          c.X_WA.translation() + 0.5 * (X_WA.translation() - c.X_WA.translation()) + t;
      X_WA.linear() =
          Eigen::AngleAxisd(step / 0.05, P.linear().col(1)).toRotationMatrix() * X_WA.linear();
      jumps += jump ? 1 : 0;
      const ContactVolume fresh = fast(*c.a, X_WA, *c.b, c.X_WB);
      const ContactVolume cached =
          meshMeshContact(c.a->bvh, c.a->topo, X_WA, c.b->bvh, c.b->topo, c.X_WB, &cache).aggregate;
      ASSERT_EQ(cached.inContact(), fresh.inContact()) << "step " << k;
      if (!fresh.inContact()) continue;
      ++inContact;
      const Errors e = compare(cached, fresh);
      EXPECT_LE(e.V, kVolumeTol) << "step " << k;
      EXPECT_LE(e.p_WC, kMomentTol) << "step " << k;
      EXPECT_LE(e.J_v, kMomentTol) << "step " << k;
      EXPECT_LE(e.J_s, kMomentTol) << "step " << k;
      EXPECT_LE(e.n_W, kMomentTol) << "step " << k;
    }
    EXPECT_GT(inContact, 30);
    // Recorded at the first query and after every jump (each moves A by more than the reach).
    EXPECT_GE(cache.refreshes, 1 + jumps);
    EXPECT_GT(cache.reuses, 40);
  }
}

// A pair that moves farther than the reach between queries (a landing) wastes each recording:
// after one unused recording the cache descends plainly, keeping only the pose, records again
// once two queries come within the reach, and records at the next jump after a reused one.
// Each answer is the fresh one (the plain descent is the fresh query's own path; the reused
// pairs come in the descent's order, so the same crossings in the same order).
TEST(FastMeshMesh, CacheDescendsPlainlyAfterAnUnusedRecording) {
  const std::vector<Case> all = cases();
  const Case& c = all.front();
  MeshMeshCache cache;
  const double reach = MeshMeshCache::kReach *
                       (c.a->bvh.root().halfExtent.norm() + c.b->bvh.root().halfExtent.norm());
  // 4 jumps of 3 reaches, 4 steps of a tenth of the reach, then a jump again.
  const double steps[] = {0, 3, -3, 3, -3, 0.1, 0.1, 0.1, 0.1, 3};
  Isometry3d X_WA = c.X_WA;
  const Vector3d dir = Vector3d(1, 2, 2) / 3.0;  // a unit vector
  for (double s : steps) {
    X_WA.translation() += dir * (s * reach);
    const ContactVolume fresh = fast(*c.a, X_WA, *c.b, c.X_WB);
    const ContactVolume cached =
        meshMeshContact(c.a->bvh, c.a->topo, X_WA, c.b->bvh, c.b->topo, c.X_WB, &cache).aggregate;
    EXPECT_EQ(cached.volume, fresh.volume) << "step " << s;
    EXPECT_EQ(cached.p_WC, fresh.p_WC) << "step " << s;
  }
  // Recorded at the first query, descended plainly at the 4 jumps, recorded at the first
  // small step, reused by the next 3, recorded at the last jump.
  EXPECT_EQ(cache.plain, 4);
  EXPECT_EQ(cache.refreshes, 3);
  EXPECT_EQ(cache.reuses, 3);
}

// Another pair of trees, or the same trees swapped, is never answered from the cache.
TEST(FastMeshMesh, CacheIsForItsOwnTrees) {
  const std::vector<Case> all = cases();
  const Case& c = all.front();
  const Case& d = all[1];
  MeshMeshCache cache;
  meshMeshContact(c.a->bvh, c.a->topo, c.X_WA, c.b->bvh, c.b->topo, c.X_WB, &cache);
  const ContactVolume other =
      meshMeshContact(d.a->bvh, d.a->topo, d.X_WA, d.b->bvh, d.b->topo, d.X_WB, &cache).aggregate;
  EXPECT_EQ(cache.refreshes, 2);
  EXPECT_EQ(cache.reuses, 0);
  EXPECT_NEAR(other.volume, fast(*d.a, d.X_WA, *d.b, d.X_WB).volume, kVolumeTol * other.volume);
  EXPECT_FALSE(cache.covers(d.b->bvh, d.a->bvh, cache.X_BA));
}

// Moving both bodies by one rigid motion moves the region with them. The placed vertices
// round differently (ε times the 0.37 m translation), which moves V by about that over the
// region's depth (≥ 0.1 mm here): ~1e-12; 1e-10 bounds it with room.
TEST(FastMeshMesh, InvariantUnderMovingBothBodies) {
  constexpr double kTol = 1e-10;
  unsigned seed = 11;
  for (const Case& c : cases()) {
    const Isometry3d P = test::randomPose(seed++);
    const ContactVolume ref = fast(*c.a, c.X_WA, *c.b, c.X_WB);
    const ContactVolume moved = fast(*c.a, P * c.X_WA, *c.b, P * c.X_WB);
    SCOPED_TRACE(c.name);
    ASSERT_GT(ref.volume, 0.0);
    EXPECT_NEAR(moved.volume, ref.volume, kTol * ref.volume);
    EXPECT_LE((moved.p_WC - P * ref.p_WC).norm(),
              kTol * std::cbrt(ref.volume) + 1e-15 * 0.37);  // + a few ulps of |P|'s 0.37 m
    EXPECT_LE((moved.n_W - P.linear() * ref.n_W).norm(), kTol);
    const Eigen::Matrix3d R = P.linear();
    EXPECT_LE(test::relativeDifference(moved.J_v, R * ref.J_v * R.transpose()), kTol);
    expectAgree(*c.a, P * c.X_WA, *c.b, P * c.X_WB, c.name + " (moved)");
  }
}

// Swapping A and B gives the same region seen from the other side: the same V, centroid and
// tensors, the normal flipped. The perturbation moves the other body then, and the crossings
// are found in another order: rounding only, ε amplified by the region's extent over its
// thickness (~1e3 for the peg's 60 µm crescents), so 1e-10.
TEST(FastMeshMesh, SymmetricInTheBodies) {
  constexpr double kTol = 1e-10;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const ContactVolume ab = fast(*c.a, c.X_WA, *c.b, c.X_WB);
    const ContactVolume ba = fast(*c.b, c.X_WB, *c.a, c.X_WA);
    ASSERT_GT(ab.volume, 0.0);
    EXPECT_NEAR(ba.volume, ab.volume, kTol * ab.volume);
    EXPECT_LE((ba.p_WC - ab.p_WC).norm(), kTol * std::cbrt(ab.volume));
    EXPECT_LE((ba.n_W + ab.n_W).norm(), kTol);
    EXPECT_LE(test::relativeDifference(ba.J_v, ab.J_v), kTol);
    EXPECT_NEAR(ba.area, ab.area, kTol * ab.area);
  }
}

TEST(FastMeshMesh, ApartIsZero) {
  const Body s(geometry::tessellateSphere(0.01, 32, 17));
  // Boxes overlap (corners of the bounding cubes) but the spheres do not: the containment
  // test runs and must say outside.
  const Isometry3d X_WA = pose({0, 0, 1}, 0.0, {0.0145, 0.0145, 0.0});
  const ContactVolume cv = fast(s, X_WA, s, Isometry3d::Identity());
  EXPECT_EQ(cv.volume, 0.0);
  EXPECT_FALSE(cv.inContact());
  EXPECT_EQ(cv.method, Method::kFast);
  const ContactVolume far =
      fast(s, pose({0, 0, 1}, 0.0, {1.0, 0.0, 0.0}), s, Isometry3d::Identity());
  EXPECT_EQ(far.volume, 0.0);
}

// A body wholly inside the other: no crossing at all, found by the containment test, and
// the region is the small body itself. Its boundary lies on the small body alone, so
// MODEL.md §1 leaves n undefined (the CGAL reference reports no contact when the small body
// is B, and a rounding-noise normal when it is A); the moments are compared, and n must be
// a unit vector pointing from B's centre towards p_c.
TEST(FastMeshMesh, BodyWhollyInside) {
  const Body small(geometry::tessellateSphere(0.004, 24, 13));
  const Body big(geometry::tessellateSphere(0.015, 40, 21));
  const Isometry3d I = Isometry3d::Identity();
  const Isometry3d X_WS = pose({1, 1, 0}, 0.4, {0.0021, -0.0013, 0.0017});
  const ContactVolume c = cgalMeshMeshContact(small.mesh(), X_WS, big.mesh(), I).aggregate;
  ASSERT_GT(c.volume, 0.0);
  const ContactVolume in = fast(small, X_WS, big, I);
  const ContactVolume out = fast(big, I, small, X_WS);
  for (const ContactVolume* f : {&in, &out}) {
    EXPECT_NEAR(f->volume, c.volume, kVolumeTol * c.volume);
    EXPECT_LE((f->p_WC - c.p_WC).norm(), kMomentTol * std::cbrt(c.volume));
    EXPECT_LE(test::relativeDifference(f->J_v, c.J_v), kMomentTol);
    EXPECT_NEAR(f->n_W.norm(), 1.0, 1e-15);  // normalised: an ulp or two
  }
  EXPECT_LE((in.n_W - in.p_WC.normalized()).norm(), 1e-12);  // big is centred at 0
  EXPECT_LE((out.n_W - (out.p_WC - X_WS.translation()).normalized()).norm(), 1e-12);
}

/// Every output finite (no NaN from a degenerate contact).
void expectFinite(const ContactVolume& cv) {
  EXPECT_TRUE(std::isfinite(cv.volume));
  EXPECT_TRUE(cv.p_WC.allFinite());
  EXPECT_TRUE(cv.n_W.allFinite());
  EXPECT_TRUE(cv.J_v.allFinite());
  EXPECT_TRUE(cv.J_s.allFinite());
  EXPECT_TRUE(std::isfinite(cv.area) && std::isfinite(cv.depth) && std::isfinite(cv.r_gyr));
}

// Faces that touch exactly (A's bottom face on B's top face, z = 0.01 in both, exact in
// binary): no overlap, in either order (the perturbation then moves A apart, or into B by
// an infinitesimal, which the noise floor removes).
TEST(FastMeshMesh, TouchingFacesAreZero) {
  const Body box(geometry::tessellateBox(Vector3d(0.02, 0.02, 0.02)));
  const Isometry3d above = pose({0, 0, 1}, 0.0, {0.0037, 0.0029, 0.02});
  const ContactVolume ab = fast(box, above, box, Isometry3d::Identity());
  const ContactVolume ba = fast(box, Isometry3d::Identity(), box, above);
  expectFinite(ab);
  expectFinite(ba);
  EXPECT_EQ(ab.volume, 0.0);
  EXPECT_EQ(ba.volume, 0.0);
  const ContactVolume c =
      cgalMeshMeshContact(box.mesh(), above, box.mesh(), Isometry3d::Identity()).aggregate;
  EXPECT_EQ(c.volume, 0.0);
}

// Box on box, overlapping 3 mm, with every side face coplanar with one of the other box
// and, with different subdivisions, edges of one lying in faces of the other and crossing
// its edges exactly. V = 0.02 · 0.02 · 0.003 up to the rounding of 0.017.
TEST(FastMeshMesh, CoplanarFacesMatchCgal) {
  const Body a(test::subdividedBox(Vector3d(0.02, 0.02, 0.02), 3));
  const Body b(test::subdividedBox(Vector3d(0.02, 0.02, 0.02), 2));
  const Isometry3d X_WA = pose({0, 0, 1}, 0.0, {0.0, 0.0, 0.017});
  for (bool swap : {false, true}) {
    SCOPED_TRACE(swap);
    const ContactVolume f =
        swap ? fast(b, Isometry3d::Identity(), a, X_WA) : fast(a, X_WA, b, Isometry3d::Identity());
    const ContactVolume c =
        swap ? cgalMeshMeshContact(b.mesh(), Isometry3d::Identity(), a.mesh(), X_WA).aggregate
             : cgalMeshMeshContact(a.mesh(), X_WA, b.mesh(), Isometry3d::Identity()).aggregate;
    expectFinite(f);
    // Axis-aligned boxes: the exact slab up to the fan sums' rounding.
    EXPECT_NEAR(f.volume, 0.02 * 0.02 * 0.003, 1e-12 * f.volume);
    EXPECT_NEAR(f.volume, c.volume, kVolumeTol * c.volume);
    EXPECT_LE((f.p_WC - c.p_WC).norm(), kMomentTol * std::cbrt(c.volume));
    EXPECT_LE(test::relativeDifference(f.J_v, c.J_v), kMomentTol);
    EXPECT_LE((f.n_W - c.n_W).norm(), kMomentTol);
    EXPECT_NEAR(f.area, c.area, kMomentTol * c.area);
  }
}

// The same mesh at the same pose: every face coincides with one of the other; the region is
// the whole body (the limit under the perturbation), as CGAL finds.
TEST(FastMeshMesh, IdenticalMeshesAtIdenticalPoses) {
  const Body torus(geometry::tessellateTorus(0.021, 0.0071, 24, 12));
  const Isometry3d X = test::randomPose(5, 0.05);
  const ContactVolume f = fast(torus, X, torus, X);
  expectFinite(f);
  geometry::Moments M;
  for (Eigen::Index t = 0; t < torus.mesh().triangleCount(); ++t) {
    M += geometry::tetrahedronMoments(X.translation(), X * torus.mesh().corner(t, 0),
                                      X * torus.mesh().corner(t, 1), X * torus.mesh().corner(t, 2));
  }
  EXPECT_NEAR(f.volume, M.m0, 1e-12 * M.m0);  // the same fan, summed in another order
  const ContactVolume c = cgalMeshMeshContact(torus.mesh(), X, torus.mesh(), X).aggregate;
  EXPECT_NEAR(f.volume, c.volume, kVolumeTol * c.volume);
  EXPECT_LE((f.p_WC - c.p_WC).norm(), kMomentTol * std::cbrt(c.volume));
  EXPECT_LE(test::relativeDifference(f.J_v, c.J_v), kMomentTol);
}

// The answer may not depend on the order in which the trees report face pairs. In the
// identical pose every edge crossing lies on an edge of the other mesh, so crossings tie
// along their edges; their order must come from the perturbation, not from the traversal.
// Trees of different leaf sizes, and a mesh whose triangles are listed in reverse, visit
// the pairs in different orders.
TEST(FastMeshMesh, IdenticalPosesWhateverTheTraversalOrder) {
  const geometry::TriangleMesh mesh = geometry::tessellateTorus(0.021, 0.0071, 24, 12);
  const geometry::TriangleMesh reversed{mesh.vertices, mesh.triangles.colwise().reverse()};
  const Isometry3d X = test::randomPose(7, 0.05);
  const double V = geometry::meshMoments(mesh).m0;
  for (int leaf : {1, 2, 4, 16}) {
    for (const geometry::TriangleMesh* m : {&mesh, &reversed}) {
      SCOPED_TRACE("leaf size " + std::to_string(leaf) + (m == &mesh ? "" : ", reversed"));
      const Body a(*m, leaf);
      const Body b(mesh, 4);
      // A sum of 576 tetrahedra placed in W: rounding only.
      EXPECT_NEAR(fast(a, X, b, X).volume, V, 1e-12 * V);
      EXPECT_NEAR(fast(b, X, a, X).volume, V, 1e-12 * V);
    }
  }
}

// Vertices exactly on a face: an octahedron whose four equator vertices lie in the box's top
// face plane (z = 0.01) and whose lower apex is inside: V = half the octahedron, (2/3) a³.
// Then the apex alone touching the face: V = 0.
TEST(FastMeshMesh, VertexExactlyOnAFace) {
  const Body box(geometry::tessellateBox(Vector3d(0.02, 0.02, 0.02)));
  const double a = 0.005;
  const Body half(test::octahedron(Vector3d(0.0031, -0.0027, 0.01), a));
  for (bool swap : {false, true}) {
    SCOPED_TRACE(swap);
    const Isometry3d I = Isometry3d::Identity();
    const ContactVolume f = swap ? fast(box, I, half, I) : fast(half, I, box, I);
    const ContactVolume c = swap ? cgalMeshMeshContact(box.mesh(), I, half.mesh(), I).aggregate
                                 : cgalMeshMeshContact(half.mesh(), I, box.mesh(), I).aggregate;
    expectFinite(f);
    EXPECT_NEAR(f.volume, 2.0 / 3.0 * a * a * a, 1e-12 * f.volume);  // polyhedral: rounding
    EXPECT_NEAR(f.volume, c.volume, kVolumeTol * c.volume);
    EXPECT_LE((f.p_WC - c.p_WC).norm(), kMomentTol * std::cbrt(c.volume));
    EXPECT_LE(test::relativeDifference(f.J_v, c.J_v), kMomentTol);
    // n from area vectors of faces in axis planes: exact up to their sums' rounding.
    EXPECT_LE((f.n_W - (swap ? -1.0 : 1.0) * Vector3d::UnitZ()).norm(), 1e-12);
  }
  const Body apex(test::octahedron(Vector3d(0.0031, -0.0027, 0.01 + a), a));
  for (bool swap : {false, true}) {
    const Isometry3d I = Isometry3d::Identity();
    const ContactVolume f = swap ? fast(box, I, apex, I) : fast(apex, I, box, I);
    expectFinite(f);
    EXPECT_EQ(f.volume, 0.0);
  }
}

// The dispatcher: two meshes default to fast; fast refuses a half-space, naming both shapes.
TEST(FastMeshMesh, Dispatcher) {
  const geometry::Shape s = geometry::Mesh{
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(0.01, 32, 17)),
      "ball"};
  const Isometry3d X_WA = pose({1, 2, 0}, 0.3, {0.0013, -0.0007, 0.0198});
  EXPECT_EQ(defaultMethod(s, s), Method::kFast);
  const ContactVolume d = computeContact(s, X_WA, s, Isometry3d::Identity()).aggregate;
  const Body body(*std::get<geometry::Mesh>(s).mesh);
  const ContactVolume f = fast(body, X_WA, body, Isometry3d::Identity());
  EXPECT_EQ(d.method, Method::kFast);
  ASSERT_GT(f.volume, 0.0);
  EXPECT_EQ(d.volume, f.volume);
  const std::string msg = test::inputErrorMessage([&] {
    computeContact(s, X_WA, geometry::HalfSpace{}, Isometry3d::Identity(), {Method::kFast});
  });
  EXPECT_NE(msg.find("ball"), std::string::npos) << msg;
  EXPECT_NE(msg.find("volume method fast"), std::string::npos) << msg;
}

}  // namespace
}  // namespace vcontact::volume
