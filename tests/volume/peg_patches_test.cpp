// The patches of the bundled peg-in-hole (assets/scenarios/peg_jam.json: a 64-gon peg tilted
// 5° in a 64-gon hole) at poses of its run: fast, cgal and columns count the same patches. fast and
// cgal also see specks, real for the polyhedra (a corner of the peg through a facet of the hole,
// within the facets' sagitta), which the dispatcher leaves out (kPatchVolumeFloor).

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "columns/columns_agreement.hpp"
#include "io/mesh_io.hpp"
#include "scenario_mesh.hpp"
#include "volume/cgal/corefinement.hpp"
#include "volume/contact.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/speck_floor.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

struct PegPose {
  double t;  ///< s, in the bundled run
  Vector3d p;
  Quaterniond q;
  int patches;  ///< bearing patches: the tip on one wall, then the shank on the other too
};

/// The peg's pose (block at the origin) at some output times of `vcontact simulate
/// assets/scenarios/peg_jam.json`: first contact, the second patch forming, jammed.
const std::vector<PegPose>& pegPoses() {
  static const std::vector<PegPose> poses = {
      {0.0095,
       {0.0, -0.001204810798351416, 0.012562245095595842},
       Quaterniond(0.9990026234096686, 0.04465152204124483, 0.0, 0.0),
       1},
      {0.01,
       {0.0, -0.0012044513478443617, 0.012469091717112668},
       Quaterniond(0.9990029719871303, 0.04464372252490711, 0.0, 0.0),
       2},
      {0.0195,
       {0.0, -0.0010965063293192515, 0.01200264061426943},
       Quaterniond(0.9991511020000233, 0.041195574666935596, 0.0, 0.0),
       2},
      {0.021,
       {0.0, -0.0010936879585314594, 0.012002743575543097},
       Quaterniond(0.9991559436078984, 0.0410779789304455, 0.0, 0.0),
       2},
      {0.03,
       {0.0, -0.00107728736748571, 0.012002909019629483},
       Quaterniond(0.9991813328016446, 0.04045570640502176, 0.0, 0.0),
       2}};
  return poses;
}

Isometry3d placed(const PegPose& pose) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = pose.q.normalized().toRotationMatrix();
  X.translation() = pose.p;
  return X;
}

// fast and cgal through the dispatcher: the same bearing patches at every pose.
TEST(PegInHolePatches, ExactMethodsCountTheSamePatches) {
  const geometry::Shape peg = vcontact::test::scenarioMesh("peg_d10.stl"),
                        block = vcontact::test::scenarioMesh("block_hole_d10.stl");
  for (const PegPose& pose : pegPoses()) {
    for (const Method m : {Method::kFast, Method::kCgal}) {
      const ContactPatches c =
          computeContact(peg, placed(pose), block, Isometry3d::Identity(), {m});
      EXPECT_EQ(c.patches.size(), std::size_t(pose.patches)) << methodName(m) << " t = " << pose.t;
    }
  }
}

// columns finds the regions from its axis passes and integrates each along its own normal:
// the same patches as fast, each to columns' own accuracy (columns/columns_agreement.hpp). The
// pair's normal of two opposite walls runs nearly along both, so a grid along it alone would see
// them edge-on; and at t = 0.01 s the second, thinner patch is one that no line of the first passes
// meets.
TEST(PegInHolePatches, ColumnsFindsTheSamePatchesAsFast) {
  const geometry::Shape peg = vcontact::test::scenarioMesh("peg_d10.stl"),
                        block = vcontact::test::scenarioMesh("block_hole_d10.stl");
  for (const PegPose& pose : pegPoses()) {
    SCOPED_TRACE(pose.t);
    const ContactPatches fast = computeContact(peg, placed(pose), block, Isometry3d::Identity(),
                                               {Method::kFast, 0, DepthMode::kDeepest});
    const ContactPatches columns =
        computeContact(peg, placed(pose), block, Isometry3d::Identity(), {Method::kColumns});
    test::expectColumnsAgree(fast, columns, 0.01);
  }
}

// Before the floor: fast's extra patches are cgal's too, volume for volume (1e-9, two exact
// methods on one polyhedron, fast_intersection_patches_test), and each is below the floor's share.
TEST(PegInHolePatches, SpecksAreRealAndBelowTheFloor) {
  const geometry::Shape peg = vcontact::test::scenarioMesh("peg_d10.stl"),
                        block = vcontact::test::scenarioMesh("block_hole_d10.stl");
  const auto& meshP = *std::get<geometry::Mesh>(peg).mesh;
  const auto& meshB = *std::get<geometry::Mesh>(block).mesh;
  int specks = 0;
  for (const PegPose& pose : pegPoses()) {
    const ContactPatches fast =
        computeContact(peg, placed(pose), block, Isometry3d::Identity(), {Method::kFast});
    const ContactPatches rawFast =
        fastContact(peg, placed(pose), block, Isometry3d::Identity(), nullptr);
    const ContactPatches rawCgal =
        cgalMeshMeshContact(meshP, placed(pose), meshB, Isometry3d::Identity());
    ASSERT_EQ(rawFast.patches.size(), rawCgal.patches.size()) << "t = " << pose.t;
    double total = 0.0;
    for (const ContactVolume& p : rawFast.patches) total += p.volume;
    for (std::size_t k = 0; k < rawFast.patches.size(); ++k) {
      const double V = rawFast.patches[k].volume;
      EXPECT_NEAR(V, rawCgal.patches[k].volume, 1e-9 * V) << "t = " << pose.t;
      if (k >= fast.patches.size()) {
        ++specks;
        EXPECT_LT(V, kPatchVolumeFloor * total);
      }
    }
  }
  EXPECT_GT(specks, 0);  // the poses do show them
}

}  // namespace
}  // namespace vcontact::volume
