// The exact depth pass (volume/column_depth.cpp) after its speed-ups against the pass of
// 89ea7e6 (column_depth_reference.hpp), on the boundary segments of real queries: the two must
// give the same depth bit for bit (both take the max of the same candidate values; the new one
// only skips candidates that the exact formulas reject anyway and evaluates shared vertex
// columns once). Cases: cad_tray_drop's tray resting flat on its fixture and the upper tray on
// the tray's rim (thin, wide regions: the case the speed-ups are for), moved by small random
// motions, and two spheres whose lens has its poles in the region.

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "column_depth_reference.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "scenario_mesh.hpp"
#include "volume/column_depth.hpp"
#include "volume/contact.hpp"
#include "volume/mesh_mesh.hpp"
#include "volume/mesh_mesh_intersector.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

Isometry3d pose(const Vector3d& p, const Quaterniond& q) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = p;
  return X;
}

/// A small rigid motion: translation up to `reach` along each axis, rotation up to reach / 0.05
/// rad (a point 50 mm from the origin moves by about `reach`).
Isometry3d jitter(std::mt19937& rng, double reach) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3d axis = Vector3d(u(rng), u(rng), u(rng)).normalized();
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(u(rng) * reach / 0.05, axis).toRotationMatrix();
  X.translation() = reach * Vector3d(u(rng), u(rng), u(rng));
  return X;
}

/// The query's depth pass replayed through the reference and through a fresh ColumnDepth.
void expectSameDepth(const geometry::Shape& a, const Isometry3d& X_WA, const geometry::Shape& b,
                     const Isometry3d& X_WB, const std::string& what) {
  SCOPED_TRACE(what);
  const ContactPatches c = fastContact(a, X_WA, b, X_WB, nullptr, true);
  ASSERT_TRUE(c.aggregate.inContact());
  const ColumnDepth& pass = internal::lastDepthPass();
  ASSERT_FALSE(pass.inputs().empty());
  test::ReferenceColumnDepth reference;
  ColumnDepth fresh;
  for (const ColumnDepth::Input& in : pass.inputs()) {
    reference.add(in.key, in.n_f, in.p, in.q);
    fresh.add(in.key, in.n_f, in.p, in.q);
  }
  const ColumnDepth::Arguments& args = pass.lastArguments();
  const double expected = reference.deepest(args.n, args.o, args.scale);
  EXPECT_GT(expected, 0.0);
  EXPECT_EQ(fresh.deepest(args.n, args.o, args.scale), expected);
  // One patch: the aggregate's depth is that pass's.
  if (c.patches.size() <= 1) {
    EXPECT_EQ(c.aggregate.depth, expected);
  }
}

// Poses from `vcontact simulate` of cad_tray_drop.json with "integrator": "discrete",
// "step": 0.001, "duration": 0.2 (bodies.csv at 0.2 s; the fixture at the origin).
TEST(DepthPass, EqualsTheReferenceOnTheRestingTrays) {
  const geometry::Shape fixture = vcontact::test::scenarioMesh("fixture_10k.stl");
  const geometry::Shape tray = vcontact::test::scenarioMesh("tray_10k.stl");
  const Isometry3d tray0 = pose(
      {-0.00014387366508314872, 6.0918756562598135e-05, -1.8125896664687724e-08},
      {0.9999995904400925, 8.728725639001793e-10, 1.5492801399966383e-07, -0.0009050522766467364});
  const Isometry3d upper0 = pose(
      {0.00022884139704104997, 4.758616037277994e-06, 0.01999974070521958},
      {0.9999998766135039, -6.02758003025285e-08, 3.4593768342127e-05, -0.0004955564998365197});
  expectSameDepth(tray, tray0, fixture, Isometry3d::Identity(), "tray on fixture at rest");
  expectSameDepth(tray, upper0, tray, tray0, "upper tray on tray at rest");
  std::mt19937 rng(18);
  for (int k = 0; k < 4; ++k) {
    // Motions of 0.2 µm (a step's creep at rest) to 20 µm (the landing's steps): the tray
    // stays on the block, sunk by ~0.04 µm more or less, tilted by up to 4e-4 rad.
    const double reach = k % 2 == 0 ? 2e-7 : 2e-6;
    const Isometry3d J = jitter(rng, reach);
    Isometry3d sunk = J * tray0;
    sunk.translation().z() = tray0.translation().z() - 5e-8;
    expectSameDepth(tray, sunk, fixture, Isometry3d::Identity(),
                    "tray on fixture, moved " + std::to_string(k));
    Isometry3d upper = jitter(rng, reach) * upper0;
    upper.translation().z() = upper0.translation().z() - 1e-7;
    expectSameDepth(tray, upper, tray, tray0, "upper tray, moved " + std::to_string(k));
  }
}

// A lens of two 10k spheres (its poles in the region, where slivers of faces meet).
TEST(DepthPass, EqualsTheReferenceOnALens) {
  const geometry::Shape s = geometry::Mesh{
      std::make_shared<const geometry::TriangleMesh>(geometry::tessellateSphere(0.01, 100, 51)),
      "sphere"};
  std::mt19937 rng(7);
  for (const double overlap : {2e-6, 2e-4, 2e-3}) {
    Isometry3d X_WA = Isometry3d::Identity();
    X_WA.translation() = Vector3d(0, 0, 0.02 - overlap);
    expectSameDepth(s, X_WA, s, Isometry3d::Identity(),
                    "poles aligned, overlap " + std::to_string(overlap));
    expectSameDepth(s, jitter(rng, overlap / 4) * X_WA, s, Isometry3d::Identity(),
                    "turned, overlap " + std::to_string(overlap));
  }
}

}  // namespace
}  // namespace vcontact::volume
