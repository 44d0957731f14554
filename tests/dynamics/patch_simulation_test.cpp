// Contact patches in simulation (docs/SCENARIO.md, "Contact patches"): the model runs once
// per patch, each patch's wrench acts at its own centroid, and each patch keeps its friction
// states as it is followed from step to step.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynamics/simulator.hpp"
#include "dynamics_fixtures.hpp"
#include "geometry/error.hpp"
#include "patch_meshes.hpp"

namespace vcontact::test {
namespace {

using dynamics::PairOutput;
using dynamics::PatchOutput;
using Eigen::Vector3d;

constexpr double kMm = 1e-3;

dynamics::Model frictionModel() {
  return dynamics::Model::withEffects({"stiffness", "damping", "coulomb", "bristle"});
}

dynamics::RigidBody fixedBody(const std::string& name, geometry::Shape shape,
                              const Eigen::Isometry3d& X_WB) {
  dynamics::RigidBody b;
  b.name = name;
  b.shape = std::move(shape);
  b.motion = dynamics::BodyMotion::kFixed;
  b.X_WB0 = X_WB;
  return b;
}

// Payload `a` held at X_WA (prescribed, moving at v_W) against the fixed body `b`, by `method`.
dynamics::Scenario heldPair(geometry::Shape a, const Eigen::Isometry3d& X_WA, geometry::Shape b,
                            volume::Method method, const Vector3d& v_W = Vector3d::Zero()) {
  dynamics::Scenario s;
  s.bodies = {fixedBody("hub", std::move(b), Eigen::Isometry3d::Identity()),
              fixedBody("part", std::move(a), X_WA)};
  s.bodies[1].motion = dynamics::BodyMotion::kPrescribed;
  s.bodies[1].prescribed.v_W = v_W;
  s.pairs.push_back({"part-hub", 1, 0, frictionModel(), method});
  s.settings.duration = 1e-3;
  return s;
}

// The pair's output at t = 0.
PairOutput atStart(const dynamics::Scenario& s) { return run(s).front().pairs.front(); }

Vector3d totalForce(const PairOutput& p) {
  Vector3d f = Vector3d::Zero();
  for (const PatchOutput& patch : p.patches) f += patch.result.wrench.f_W;
  return f;
}

TEST(PatchSimulation, TiltedPegInARoundHoleIsHeldByACouple) {
  // Peg R 5 mm in a 10 mm thick ring of inner radius 5.05 mm (64-gons), tilted 0.02 rad about x:
  // its axis leans 0.1 mm at either face of the ring against 0.05 mm of clearance, so it
  // touches the wall near the top on one side and near the bottom on the other.
  const double tilt = 0.02;
  const auto hole = meshShape(ring(5.05 * kMm, 10 * kMm, 10 * kMm, 64), "ring");
  const auto peg = meshShape(geometry::tessellateCylinder(5 * kMm, 20 * kMm, 64), "peg");
  const PairOutput p = atStart(heldPair(
      peg, placed(Vector3d::Zero(), Eigen::AngleAxisd(tilt, Vector3d::UnitX()).toRotationMatrix()),
      hole, volume::Method::kFast));
  ASSERT_EQ(p.patches.size(), 2u);
  const PatchOutput &p0 = p.patches[0], &p1 = p.patches[1];
  EXPECT_EQ(p0.slot, 0);
  EXPECT_EQ(p1.slot, 1);
  // opposite walls, normals across the axis and opposite
  EXPECT_LT(p0.cv.p_WC.z() * p1.cv.p_WC.z(), 0.0);
  EXPECT_LT(p0.cv.p_WC.y() * p1.cv.p_WC.y(), 0.0);
  EXPECT_LT(p0.cv.n_W.dot(p1.cv.n_W), -0.99);
  for (const PatchOutput& q : p.patches) {
    EXPECT_GT(std::abs(q.cv.n_W.y()), 0.99) << "normal in the plane across the axis";
    // at rest the normal force is the stiffness alone: kv V per patch
    EXPECT_NEAR(q.result.f_n, q.result.f_n > 0 ? 5.17e12 * q.cv.volume : 0.0, 1e-12 * q.result.f_n);
  }
  // The pose is symmetric under a half-turn about x, which swaps the patches: their forces
  // cancel to round-off (1e-9 of one patch's force bounds the mesh coordinates' round-off).
  const double f0 = p0.result.wrench.f_W.norm();
  EXPECT_GT(f0, 0.0);
  EXPECT_LT(totalForce(p).norm(), 1e-9 * f0);
  EXPECT_LT(p.result.wrench.f_W.norm(), 1e-9 * f0);
  // ... and leave a couple about x: f times the patches' separation across the force
  const Vector3d arm = p0.cv.p_WC - p1.cv.p_WC;
  const double couple = arm.cross(p0.result.wrench.f_W).x();
  EXPECT_NEAR(p.result.wrench.tau_W.x(), couple, 1e-6 * std::abs(couple));
  EXPECT_GT(std::abs(couple), 4 * kMm * f0) << "the patches are ~8 mm apart along the axis";
}

// The force evaluations skip the exact depth (QueryOptions::depth); an output sample carries
// it all the same, for the aggregate and each patch: the depth of a direct query at the
// sample's pose (the same code on the same pose, so to the bit).
TEST(PatchSimulation, OutputSamplesCarryTheExactDepth) {
  const auto hole = meshShape(ring(5.05 * kMm, 10 * kMm, 10 * kMm, 64), "ring");
  const auto peg = meshShape(geometry::tessellateCylinder(5 * kMm, 20 * kMm, 64), "peg");
  const Eigen::Isometry3d X_WA =
      placed(Vector3d::Zero(), Eigen::AngleAxisd(0.02, Vector3d::UnitX()).toRotationMatrix());
  const PairOutput p = atStart(heldPair(peg, X_WA, hole, volume::Method::kFast));
  const volume::ContactPatches direct =
      volume::computeContact(peg, X_WA, hole, Eigen::Isometry3d::Identity(),
                             {volume::Method::kFast, 0, volume::DepthMode::kDeepest});
  ASSERT_EQ(p.patches.size(), 2u);
  ASSERT_EQ(direct.patches.size(), 2u);
  EXPECT_GT(p.cv.depth, 0.0);
  EXPECT_EQ(p.cv.depth, direct.aggregate.depth);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(p.patches[i].cv.volume, direct.patches[i].volume) << "the same pose";
    EXPECT_EQ(p.patches[i].cv.depth, direct.patches[i].depth);
  }
}

// The discrete stepper's step that lands on an output time asks for the depth in its one query
// (instead of a second query for the output): each output's depths are those of a direct
// query at its pose, to the bit, while the peg slides along the hole.
TEST(PatchSimulation, DiscreteOutputsCarryTheExactDepth) {
  const auto hole = meshShape(ring(5.05 * kMm, 10 * kMm, 10 * kMm, 64), "ring");
  const auto peg = meshShape(geometry::tessellateCylinder(5 * kMm, 20 * kMm, 64), "peg");
  const Eigen::Isometry3d X_WA =
      placed(Vector3d::Zero(), Eigen::AngleAxisd(0.02, Vector3d::UnitX()).toRotationMatrix());
  dynamics::Scenario s =
      heldPair(peg, X_WA, hole, volume::Method::kFast, Vector3d(0.0, 0.0, 0.1));  // 0.1 m/s
  s.settings.integrator = dynamics::Integrator::kDiscrete;
  s.settings.step = 1e-3;
  s.settings.output_rate_hz = 1000.0;
  s.settings.duration = 3e-3;
  const std::vector<dynamics::Snapshot> outputs = run(s);
  ASSERT_EQ(outputs.size(), 4u);
  for (const dynamics::Snapshot& o : outputs) {
    const PairOutput& p = o.pairs.front();
    const volume::ContactPatches direct =
        volume::computeContact(peg, o.bodies[1].X_WB, hole, Eigen::Isometry3d::Identity(),
                               {volume::Method::kFast, 0, volume::DepthMode::kDeepest});
    ASSERT_EQ(p.patches.size(), 2u) << "t = " << o.t;
    ASSERT_EQ(direct.patches.size(), 2u);
    EXPECT_GT(p.cv.depth, 0.0);
    EXPECT_EQ(p.cv.depth, direct.aggregate.depth) << "t = " << o.t;
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(p.patches[i].cv.volume, direct.patches[i].volume) << "the same pose";
      EXPECT_EQ(p.patches[i].cv.depth, direct.patches[i].depth) << "t = " << o.t;
    }
  }
}

// A caller that writes no depth turns the output's depth query off: the outputs after t = 0
// then carry the force evaluation's NaN; the one at t = 0 (which the blow-up guard reads) and
// everything else are as with it on, with both integrators that use the shortcut.
TEST(PatchSimulation, OutputDepthsOffLeaveDepthOutAndNothingElse) {
  const auto hole = meshShape(ring(5.05 * kMm, 10 * kMm, 10 * kMm, 64), "ring");
  const auto peg = meshShape(geometry::tessellateCylinder(5 * kMm, 20 * kMm, 64), "peg");
  const Eigen::Isometry3d X_WA =
      placed(Vector3d::Zero(), Eigen::AngleAxisd(0.02, Vector3d::UnitX()).toRotationMatrix());
  for (const auto integrator : {dynamics::Integrator::kDopri5, dynamics::Integrator::kDiscrete}) {
    dynamics::Scenario s = heldPair(peg, X_WA, hole, volume::Method::kFast, Vector3d(0, 0, 0.1));
    s.settings.integrator = integrator;
    s.settings.duration = 2e-3;
    const std::vector<dynamics::Snapshot> with = run(s);
    dynamics::Simulator sim(s);
    sim.setOutputDepths(false);
    std::vector<dynamics::Snapshot> without;
    dynamics::SimulationSummary summary;
    sim.run([&](const dynamics::Snapshot& o) { without.push_back(o); }, [](double) {}, summary);
    ASSERT_EQ(without.size(), 3u);
    ASSERT_EQ(with.size(), 3u);
    EXPECT_EQ(without[0].pairs.front().cv.depth, with[0].pairs.front().cv.depth);
    for (std::size_t j = 0; j < 3; ++j) {
      const PairOutput &a = with[j].pairs.front(), &b = without[j].pairs.front();
      EXPECT_GT(a.cv.depth, 0.0);
      EXPECT_EQ(std::isnan(b.cv.depth), j > 0) << "t = " << with[j].t << ": only t = 0 has it";
      EXPECT_EQ(b.cv.volume, a.cv.volume);
      EXPECT_EQ(b.result.wrench.f_W, a.result.wrench.f_W);
      EXPECT_EQ(b.state.vector(0), a.state.vector(0));
    }
  }
}

TEST(PatchSimulation, TurnedKeyedShaftGetsATorqueAboutItsAxisAndNoForceAcross) {
  // A square shaft (circumradius 9.9 mm) turned 1° in a square hole (10 mm): each of its four
  // edges presses into the wall ahead of it, 0.05 mm deep.
  const double turn = std::numbers::pi / 180.0;
  const auto hub = meshShape(ring(10 * kMm, 20 * kMm, 10 * kMm, 4), "hub");
  const auto shaft = meshShape(geometry::tessellateCylinder(9.9 * kMm, 20 * kMm, 4), "shaft");
  const PairOutput p = atStart(heldPair(
      shaft,
      placed(Vector3d::Zero(), Eigen::AngleAxisd(turn, Vector3d::UnitZ()).toRotationMatrix()), hub,
      volume::Method::kFast));
  ASSERT_EQ(p.patches.size(), 4u);
  double torque = 0.0, f_patch = 0.0;
  for (const PatchOutput& q : p.patches) {
    EXPECT_GE(q.slot, 0);
    EXPECT_LT(std::abs(q.cv.n_W.z()), 1e-9) << "the walls are parallel to the axis";
    torque += (q.cv.p_WC.cross(q.result.wrench.f_W) + q.result.wrench.tau_W).z();
    f_patch = std::max(f_patch, q.result.wrench.f_W.norm());
  }
  EXPECT_LT(torque, 0.0) << "the hub turns the shaft back";
  // Bound: the pose is symmetric under quarter turns about z, which permute the patches, so
  // the force across the axis cancels to round-off: below 1e-9 of one patch's force, while
  // the torque is four times that force on a lever of ~7 mm.
  const Vector3d f = totalForce(p);
  EXPECT_LT(f.norm(), 1e-9 * f_patch);
  EXPECT_LT(f.norm() * 10 * kMm, 1e-8 * std::abs(torque));
  EXPECT_GT(std::abs(torque), 4 * 5 * kMm * f_patch * 0.9);
}

TEST(PatchSimulation, PartOnTwoFeetHasOnePatchPerFoot) {
  // Two 10 mm cube feet 40 mm apart (one mesh, two shells) pressed 10 um into a half-space:
  // each patch is its foot's 10 × 10 × 0.01 mm³ slab.
  const double d = 10e-6;
  const geometry::TriangleMesh foot = geometry::tessellateBox(Vector3d::Constant(10 * kMm));
  const auto part = meshShape(
      merged({{foot, placed({-20 * kMm, 0, 0})}, {foot, placed({20 * kMm, 0, 0})}}), "two feet");
  const PairOutput p = atStart(heldPair(part, placed({0, 0, 5 * kMm - d}), geometry::HalfSpace{},
                                        volume::Method::kHalfspace));
  ASSERT_EQ(p.patches.size(), 2u);
  const double V = 1e-4 * d;
  for (const PatchOutput& q : p.patches) {
    // clip of an axis-aligned box: exact up to the round-off of the pose (1e-9 relative)
    EXPECT_NEAR(q.cv.volume, V, 1e-9 * V);
    EXPECT_NEAR(std::abs(q.cv.p_WC.x()), 20 * kMm, 1e-9);
    EXPECT_NEAR(q.result.f_n, 5.17e12 * q.cv.volume, 1e-12 * q.result.f_n);
  }
  EXPECT_LT(p.patches[0].cv.p_WC.x() * p.patches[1].cv.p_WC.x(), 0.0);
  EXPECT_NEAR(p.result.f_n, 2 * 5.17e12 * V, 1e-9 * p.result.f_n);
  EXPECT_NEAR(p.cv.volume, 2 * V, 1e-9 * V) << "the aggregate is the sum";
  EXPECT_EQ(p.patch_count, 2);
  EXPECT_EQ(p.without_slot, 0);
}

TEST(PatchSimulation, OneSlotLumpsThePatchesIntoTheAggregate) {
  const double d = 10e-6;
  const geometry::TriangleMesh foot = geometry::tessellateBox(Vector3d::Constant(10 * kMm));
  const auto part = meshShape(
      merged({{foot, placed({-20 * kMm, 0, 0})}, {foot, placed({20 * kMm, 0, 0})}}), "two feet");
  dynamics::Scenario s = heldPair(part, placed({0, 0, 5 * kMm - d}), geometry::HalfSpace{},
                                  volume::Method::kHalfspace);
  s.pairs[0].max_patches = 1;
  EXPECT_EQ(dynamics::patchSlots(s, s.pairs[0]), 1);
  const PairOutput p = atStart(s);
  EXPECT_TRUE(p.patches.empty());
  EXPECT_EQ(p.patch_count, 2);
  EXPECT_EQ(p.without_slot, 1);
  EXPECT_NEAR(p.result.f_n, 5.17e12 * p.cv.volume, 1e-12 * p.result.f_n);
}

TEST(PatchSimulation, ConvexPairsAndDistributedFrictionUseOneSlot) {
  dynamics::Scenario s =
      heldPair(meshShape(geometry::tessellateBox(Vector3d::Constant(0.01)), "box"),
               placed({0, 0, 0.005}), geometry::HalfSpace{}, volume::Method::kHalfspace);
  EXPECT_EQ(dynamics::patchSlots(s, s.pairs[0]), 1) << "a convex mesh on a half-space";
  s.bodies[1].shape = meshShape(ring(0.01, 0.02, 0.01, 16), "ring");
  EXPECT_EQ(dynamics::patchSlots(s, s.pairs[0]), dynamics::kDefaultMaxPatches);
  s.pairs[0].max_patches = 0;
  EXPECT_THROW(dynamics::patchSlots(s, s.pairs[0]), InputError);
}

// A 6 mm cube slid at 0.1 m/s, 10 um deep, across a 2 mm gap between two plates (one mesh of
// two shells): one patch, then two while it spans the gap (t ∈ (0.06, 0.1) s), then one.
class BlockAcrossAGap : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const geometry::TriangleMesh slab = geometry::tessellateBox(Vector3d(20, 20, 10) * kMm);
    const auto plate = meshShape(merged({{slab, placed(Vector3d(-11, 0, -5) * kMm)},
                                         {slab, placed(Vector3d(11, 0, -5) * kMm)}}),
                                 "plate with a gap");
    const auto block = meshShape(geometry::tessellateBox(Vector3d::Constant(6 * kMm)), "block");
    dynamics::Scenario s = heldPair(block, placed({-8 * kMm, 0, 3 * kMm - 10e-6}), plate,
                                    volume::Method::kFast, Vector3d(0.1, 0, 0));
    s.settings.duration = 0.16;
    out_ = run(s, &summary_);
  }
  static std::vector<dynamics::Snapshot> out_;
  static dynamics::SimulationSummary summary_;
};
std::vector<dynamics::Snapshot> BlockAcrossAGap::out_;
dynamics::SimulationSummary BlockAcrossAGap::summary_;

// The patch of `p` on the plate at x < 0 (left) or x > 0 (right), or null.
const PatchOutput* patchOn(const PairOutput& p, bool right) {
  for (const PatchOutput& q : p.patches) {
    if ((q.cv.p_WC.x() > 0) == right) return &q;
  }
  return nullptr;
}

double bristleZ(const PatchOutput& q) { return q.state.vector(0).norm(); }

TEST_F(BlockAcrossAGap, PatchCountGoesOneTwoOne) {
  std::vector<int> runs;
  for (const auto& s : out_) {
    const int n = static_cast<int>(s.pairs[0].patches.size());
    if (runs.empty() || runs.back() != n) runs.push_back(n);
  }
  EXPECT_EQ(runs, (std::vector<int>{1, 2, 1}));
  EXPECT_EQ(summary_.patches_max, 2);
  EXPECT_EQ(summary_.patches_without_slot, 0);
  EXPECT_GT(summary_.patches_mean, 1.0);
  EXPECT_LT(summary_.patches_mean, 2.0);
}

TEST_F(BlockAcrossAGap, NoForceJumpBeyondThePatchThatAppearsOrVanishes) {
  // Between outputs the force changes smoothly (the overlap moves 0.1 mm per output); where
  // the patch count changes, the change may differ from the previous one by at most the force
  // of the patch that appeared (after) or vanished (before), with 1 % of that for the smooth
  // part's own change of rate.
  for (std::size_t k = 2; k < out_.size(); ++k) {
    const PairOutput &a = out_[k - 2].pairs[0], &b = out_[k - 1].pairs[0], &c = out_[k].pairs[0];
    if (b.patches.size() == c.patches.size()) continue;
    const PairOutput& more = b.patches.size() > c.patches.size() ? b : c;
    double f_small = std::numeric_limits<double>::infinity();
    for (const PatchOutput& q : more.patches) {
      f_small = std::min(f_small, q.result.wrench.f_W.norm());
    }
    const Vector3d jump =
        (c.result.wrench.f_W - b.result.wrench.f_W) - (b.result.wrench.f_W - a.result.wrench.f_W);
    EXPECT_LE(jump.norm(), 1.01 * f_small + 1e-6 * c.result.wrench.f_W.norm())
        << "at t = " << out_[k].t << " s";
  }
}

TEST_F(BlockAcrossAGap, EachPatchKeepsItsBristleState) {
  bool split_seen = false, vanish_seen = false;
  for (std::size_t k = 1; k < out_.size(); ++k) {
    const PairOutput &b = out_[k - 1].pairs[0], &c = out_[k].pairs[0];
    if (b.patches.size() == 1 && c.patches.size() == 2) {  // the right patch appears
      split_seen = true;
      const PatchOutput *left0 = patchOn(b, false), *left1 = patchOn(c, false);
      const PatchOutput* right = patchOn(c, true);
      ASSERT_TRUE(left0 && left1 && right);
      EXPECT_EQ(left1->slot, left0->slot);
      EXPECT_NE(right->slot, left0->slot);
      // z keeps growing towards its steady value C_v μ/σ0 (time constant σ1/σ0 = 67 ms):
      // within 3 % over one 1 ms output; the new patch starts from rest and gains at most
      // one output's worth, μ/σ1 × 1 ms = 6.7e-7 m
      EXPECT_NEAR(bristleZ(*left1), bristleZ(*left0), 0.03 * bristleZ(*left0));
      EXPECT_GT(bristleZ(*left0), 1e-5);
      EXPECT_LT(bristleZ(*right), 1e-6);
    }
    if (b.patches.size() == 2 && c.patches.size() == 1) {  // the left patch vanishes
      vanish_seen = true;
      const PatchOutput *right0 = patchOn(b, true), *right1 = patchOn(c, true);
      ASSERT_TRUE(right0 && right1);
      EXPECT_EQ(right1->slot, right0->slot);
      EXPECT_NEAR(bristleZ(*right1), bristleZ(*right0), 0.03 * bristleZ(*right0));
      EXPECT_GT(bristleZ(*right0), 1e-5);
    }
  }
  EXPECT_TRUE(split_seen);
  EXPECT_TRUE(vanish_seen);
}

}  // namespace
}  // namespace vcontact::test
