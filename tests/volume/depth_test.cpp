// `depth` is the deepest penetration along the patch normal, max over the plate of δ(s)
// (MODEL.md §1), for every method: closed forms first (a box face pressed into a wall, a
// sphere cap, a cube corner, a peg pressed sideways into its hole's wall, a key's flank in a
// hub), each through every method that takes the pair.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/contact.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume_fixtures.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::Shape;

/// The exact methods (fast, cgal, halfspace, analytic) against a closed form of the same
/// polyhedron: they round the vertices placed in W (|p| < 1 m: ~1e-16 m) and the crossing
/// points, and take each column's span over a reach of 1e-12 of the coordinates
/// (depth/deepest_column.cpp), which moves no flat or vertical face. 1e-9 of d (≥ 1e-4 m here) is
/// 1e-13 m: a thousand times the rounding, far below any faceting.
constexpr double kExact = 1e-9;

Shape meshShape(geometry::TriangleMesh m, const std::string& name) {
  return geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(std::move(m)), name};
}

/// A plate whose top face is z = 0 of its frame (0.2 m square, 0.05 m thick).
Shape plateMesh() {
  geometry::TriangleMesh m = geometry::tessellateBox(Vector3d(0.2, 0.2, 0.05));
  m.vertices.col(2).array() -= 0.025;
  return meshShape(std::move(m), "plate");
}

/// Every method that takes (a, plate as a mesh) or (a, plate as a half-space), with its
/// name; `primitive` (if given) is a's closed-form twin for the analytic method.
struct MethodRun {
  std::string name;
  ContactPatches contact;
  double cellSize;  ///< the columns' line spacing (0 for the others)
};

std::vector<MethodRun> everyMethod(const Shape& a, const Shape* primitive, const Isometry3d& X_WA,
                                   const Isometry3d& X_WH) {
  const Shape plate = plateMesh();
  const Shape half = geometry::HalfSpace{};
  std::vector<MethodRun> runs;
  for (const Method m : {Method::kFast, Method::kCgal, Method::kColumns}) {
    DepthField field;
    ContactPatches c = computeContact(a, X_WA, plate, X_WH, {m, 0, DepthMode::kDeepest},
                                      m == Method::kColumns ? &field : nullptr);
    runs.push_back({methodName(m) + " vs plate mesh", c, std::sqrt(field.cell_area)});
  }
  for (const Method m : {Method::kHalfspace, Method::kCgal, Method::kColumns}) {
    DepthField field;
    ContactPatches c = computeContact(a, X_WA, half, X_WH, {m, 0, DepthMode::kDeepest},
                                      m == Method::kColumns ? &field : nullptr);
    runs.push_back({methodName(m) + " vs half-space", c, std::sqrt(field.cell_area)});
  }
  if (primitive) {
    runs.push_back({"analytic", computeContact(*primitive, X_WA, half, X_WH), 0.0});
  }
  return runs;
}

/// The columns' depth runs along its own normal n, which its axis passes estimate (against a
/// mesh) off the true n_ref by α. Between two faces d apart along n_ref and tilted from the
/// plate by β (tan β ≤ slope), a line at α from n_ref is d cos β / cos(β ± α) long:
/// d / (cos α ∓ slope · sin α) bounds it above (sign −1) and below (+1).
double tilted(const ContactVolume& cv, const Vector3d& n_ref, double d, double slope, int sign) {
  const double c = std::min(1.0, std::abs(cv.n_W.dot(n_ref)));
  return d / (c + sign * slope * std::sqrt(1.0 - c * c));
}

/// Each run has one patch of depth d: the exact methods to kExact; columns, which sample δ
/// on lines spaced h apart, at most `slope`·h/√2 below (the nearest line is within h/√2 of
/// the deepest column and δ falls at most `slope` per unit across the plate), and off by its
/// normal's tilt (tilted).
void expectDepth(const std::vector<MethodRun>& runs, double d, double slope,
                 const Vector3d& n_ref) {
  for (const MethodRun& r : runs) {
    ASSERT_EQ(r.contact.patches.size(), 1u) << r.name;
    const ContactVolume& p = r.contact.patches[0];
    EXPECT_EQ(p.depth, r.contact.aggregate.depth) << r.name;
    const double depth = p.depth;
    if (r.cellSize > 0.0) {
      EXPECT_LE(depth, tilted(p, n_ref, d, slope, -1) * (1 + kExact)) << r.name;
      EXPECT_GE(depth,
                tilted(p, n_ref, d, slope, +1) - slope * r.cellSize / std::sqrt(2.0) - kExact * d)
          << r.name;
    } else {
      EXPECT_NEAR(depth, d, kExact * d) << r.name;
    }
  }
}

// A 10 mm thick box with a 21 × 17 mm face pressed 0.1 mm into a wall: depth 0.1 mm, the
// slab's thickness, whatever the box's own extent. Every column has δ = d, so columns is
// exact too (slope 0).
TEST(Depth, BoxFacePressedIntoAWall) {
  const Vector3d size(0.0213, 0.0171, 0.0103);
  const double d = 1e-4;
  const Shape box = meshShape(geometry::tessellateBox(size), "box");
  const Shape primitive = geometry::Box{size};
  const Isometry3d X_WH = test::randomPose(41);
  const Isometry3d X_WA = X_WH * test::translation({0.0031, -0.0017, 0.5 * size.z() - d});
  expectDepth(everyMethod(box, &primitive, X_WA, X_WH), d, 0.0, X_WH.linear().col(2));
}

// A UV sphere pole down, its lowest vertex d under the plane: the spherical cap's depth is d
// (MODEL.md §5), for the polyhedron as for the sphere (the pole is on both). Near the pole
// the facets rise at tan(π/48) per unit (24 rings: the first ring is π/24 up the sphere).
TEST(Depth, SphereCap) {
  const double R = 0.0103, d = 0.0011;
  const Shape sphere = meshShape(geometry::tessellateSphere(R, 48, 24), "sphere");
  const Shape primitive = geometry::Sphere{R};
  const Isometry3d X_WH = test::randomPose(42);
  const Isometry3d X_WA = X_WH * test::translation({-0.0023, 0.0041, R - d});
  expectDepth(everyMethod(sphere, &primitive, X_WA, X_WH), d, std::tan(std::numbers::pi / 48),
              X_WH.linear().col(2));
}

// A cube corner down, its body diagonal along n, d under the plane: V = (√3/2) d³ (MODEL.md
// §5) and depth d at the corner's column. Its faces rise at tan(acos(1/√3)) = √2 per unit.
TEST(Depth, CubeCornerDown) {
  const double s = 0.0171, d = 0.0013;
  const Shape cube = meshShape(geometry::tessellateBox(Vector3d::Constant(s)), "cube");
  const Shape primitive = geometry::Box{Vector3d::Constant(s)};
  // the diagonal (−1, −1, −1)/√3 turned onto −z
  const Isometry3d tilt(Eigen::Quaterniond::FromTwoVectors(-Vector3d::Ones(), -Vector3d::UnitZ()));
  const Isometry3d X_WH = test::randomPose(43);
  const Isometry3d X_WA = X_WH * test::translation({0.0, 0.0, 0.5 * std::sqrt(3.0) * s - d}) * tilt;
  const std::vector<MethodRun> runs = everyMethod(cube, &primitive, X_WA, X_WH);
  expectDepth(runs, d, std::sqrt(2.0), X_WH.linear().col(2));
  const double V = 0.5 * std::sqrt(3.0) * d * d * d;
  EXPECT_NEAR(runs[0].contact.aggregate.volume, V, 1e-9 * V);  // the pose is the intended one
}

// A round peg pressed sideways into its hole's wall, axes parallel: the peg (radius r, centre
// e off the hole's axis towards a vertex row of both polygons) overlaps the wall (radius R)
// in a crescent that wraps ±70° round the hole, 7 mm across along n. Along n (−x, out of the
// wall) the two polygons' first facets have the same slope tan(π/N), so δ = e + r − R on the
// whole crest: the faceted depth equals the round one, 0.1 mm. Fast, cgal and columns (a line
// on the 1.9 mm wide crest) give it.
TEST(Depth, PegPressedIntoTheHoleWall) {
  const double r = 0.0099, R = 0.00995, e = 0.00015, d = e + r - R;
  const Shape hole = meshShape(test::tube(0.0203, R, 0.0151, 64), "hole");
  const Shape peg = meshShape(geometry::tessellateCylinder(r, 0.0407, 64), "peg");
  const Isometry3d X_WH = test::randomPose(44);
  const Isometry3d X_WP = X_WH * test::translation({e, 0.0, 0.0});
  const Vector3d n_ref = -X_WH.linear().col(0);
  for (const Method m : {Method::kFast, Method::kCgal, Method::kColumns}) {
    const ContactPatches c = computeContact(peg, X_WP, hole, X_WH, {m, 0, DepthMode::kDeepest});
    ASSERT_EQ(c.patches.size(), 1u) << methodName(m);
    const ContactVolume& p = c.patches[0];
    if (m == Method::kColumns) {  // its normal from sampled axis passes; a line on the crest
      const double slope = std::tan(std::numbers::pi / 64);
      EXPECT_LE(p.depth, tilted(p, n_ref, d, slope, -1) * (1 + kExact));
      EXPECT_GE(p.depth, tilted(p, n_ref, d, slope, +1) * (1 - kExact));
      EXPECT_LT((p.n_W - n_ref).norm(), 1e-2);
    } else {
      EXPECT_NEAR(p.depth, d, kExact * d) << methodName(m);
      EXPECT_LT((p.n_W - n_ref).norm(), 1e-12) << methodName(m);
    }
    EXPECT_GT(p.area, 0.0);
  }
}

// A key's flank turned by φ against a hub block: the region is a prism over a right triangle
// whose hypotenuse is the flank, and n is the flank's normal (the boundary's area vectors, the
// block's two faces against the flank). The deepest column is the triangle's altitude onto
// the flank, (x_f − x_1) sin φ: x_f the block's far end, x_1 where the flank meets the block's
// face y = a + gap.
TEST(Depth, KeyFlankInAHubBlock) {
  const double a = 0.0041, L = 0.0149, gap = 0.0002, phi = 0.03;
  const Shape shaft = meshShape(test::keyedShaft(a, L, 0.0203), "shaft");
  geometry::TriangleMesh block = geometry::tessellateBox(Vector3d(0.0071, 0.0051, 0.0121));
  block.vertices.rowwise() += Eigen::RowVector3d(0.0101, a + gap + 0.00255, 0.0);
  const Shape hub = meshShape(std::move(block), "block");
  const Isometry3d X_WH = test::randomPose(45);
  const Isometry3d X_WS = X_WH * Isometry3d(Eigen::AngleAxisd(phi, Vector3d::UnitZ()));
  // the flank point R_φ (t, a) on y = a + gap
  const double t = (a + gap - a * std::cos(phi)) / std::sin(phi);
  const double x1 = t * std::cos(phi) - a * std::sin(phi), xf = 0.0101 + 0.00355;
  const double d = (xf - x1) * std::sin(phi);
  for (const Method m : {Method::kFast, Method::kCgal}) {
    const ContactPatches c = computeContact(shaft, X_WS, hub, X_WH, {m, 0, DepthMode::kDeepest});
    ASSERT_EQ(c.patches.size(), 1u) << methodName(m);
    EXPECT_NEAR(c.patches[0].depth, d, kExact * d) << methodName(m);
  }
}

/// Every field but depth the same to the bit; depth NaN in `skip` and set in `deep`.
void expectOnlyDepthLeftOut(const ContactVolume& skip, const ContactVolume& deep) {
  EXPECT_EQ(skip.volume, deep.volume);
  EXPECT_EQ(skip.p_WC, deep.p_WC);
  EXPECT_EQ(skip.n_W, deep.n_W);
  EXPECT_EQ(skip.J_v, deep.J_v);
  EXPECT_EQ(skip.J_s, deep.J_s);
  EXPECT_EQ(skip.area, deep.area);
  EXPECT_EQ(skip.r_gyr, deep.r_gyr);
  EXPECT_EQ(skip.method, deep.method);
  EXPECT_TRUE(std::isnan(skip.depth));
  EXPECT_GT(deep.depth, 0.0);
}

// The default query (QueryOptions{}, DepthMode::kSkip; what a library caller gets) spares
// `fast` its depth pass and changes nothing else: on a peg tilted in a round hole (two patches
// on opposite walls), every other field of every patch and of the aggregate is the same to the
// bit (the pass only reads the region), depth is NaN; kDeepest fills it, as cgal (another
// exact method, the same polyhedron) does by default, whose corefinement dwarfs the pass.
TEST(Depth, DefaultLeavesOnlyFastsDepthOut) {
  const Shape hole = meshShape(test::tube(0.0101, 0.00505, 0.0103, 64), "hole");
  const Shape peg = meshShape(geometry::tessellateCylinder(0.005, 0.0207, 64), "peg");
  const Isometry3d X_WH = test::randomPose(46);
  const Isometry3d X_WP = X_WH * Isometry3d(Eigen::AngleAxisd(0.02, Vector3d::UnitX()));
  EXPECT_EQ(QueryOptions{}.depth, DepthMode::kSkip);
  const ContactPatches skip = computeContact(peg, X_WP, hole, X_WH);  // the default method: fast
  const ContactPatches deep =
      computeContact(peg, X_WP, hole, X_WH, {Method::kFast, 0, DepthMode::kDeepest});
  ASSERT_EQ(skip.aggregate.method, Method::kFast);
  ASSERT_EQ(deep.patches.size(), 2u);
  ASSERT_EQ(skip.patches.size(), 2u);
  expectOnlyDepthLeftOut(skip.aggregate, deep.aggregate);
  for (std::size_t i = 0; i < 2; ++i) expectOnlyDepthLeftOut(skip.patches[i], deep.patches[i]);
  const ContactPatches cgal = computeContact(peg, X_WP, hole, X_WH, {Method::kCgal});
  ASSERT_EQ(cgal.patches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(cgal.patches[i].depth, deep.patches[i].depth, kExact * deep.patches[i].depth);
  }
}

// The same through the backend's own entry point: meshMeshContact (and fastContact) leave
// depth out unless `deepest`; asked, it is the closed form of a box face pressed d into a
// plate (the slab's thickness, BoxFacePressedIntoAWall).
TEST(Depth, MeshMeshContactAsksForTheDepth) {
  const Vector3d size(0.0213, 0.0171, 0.0103);
  const double d = 1e-4;
  const geometry::MeshBvh box(geometry::tessellateBox(size));
  geometry::TriangleMesh plate = geometry::tessellateBox(Vector3d(0.2, 0.2, 0.05));
  plate.vertices.col(2).array() -= 0.025;
  const geometry::MeshBvh wall(std::move(plate));
  const geometry::MeshTopology topoBox(box.mesh()), topoWall(wall.mesh());
  const Isometry3d X_WH = test::randomPose(47);
  const Isometry3d X_WA = X_WH * test::translation({0.0031, -0.0017, 0.5 * size.z() - d});
  const ContactPatches skip = meshMeshContact(box, topoBox, X_WA, wall, topoWall, X_WH);
  const ContactPatches deep =
      meshMeshContact(box, topoBox, X_WA, wall, topoWall, X_WH, nullptr, true);
  ASSERT_EQ(deep.patches.size(), 1u);
  ASSERT_EQ(skip.patches.size(), 1u);
  expectOnlyDepthLeftOut(skip.aggregate, deep.aggregate);
  expectOnlyDepthLeftOut(skip.patches[0], deep.patches[0]);
  EXPECT_NEAR(deep.aggregate.depth, d, kExact * d);
  EXPECT_NEAR(skip.aggregate.volume, size.x() * size.y() * d, 1e-9 * size.x() * size.y() * d);
}

}  // namespace
}  // namespace vcontact::volume
