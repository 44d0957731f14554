// The force model as named parameters in, wrench out: parameters, requirements, the pair-state
// layout and the state handling of MODEL.md §3. Each effect's closed forms are in
// tests/dynamics/effects/<id>_test.cpp.

#include "dynamics/model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dynamics/effects/registry.hpp"
#include "effects/effect_fixtures.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics::test {
namespace {

TEST(Model, ParameterNamesFollowEffectStageOrderAndRoundTrip) {
  Model m = Model::withEffects({"coulomb", "stiffness", "damping", "bristle"});
  const std::vector<std::string> expected = {"stiffness.kv",   "damping.a",  "bristle.sigma0",
                                             "bristle.sigma1", "coulomb.mu", "coulomb.v_s"};
  EXPECT_EQ(m.parameterNames(), expected);
  const std::vector<double> values = {1e12, 2.5, 1000.0, 50.0, 0.3, 2e-3};
  m.setParameters(values);
  EXPECT_EQ(m.parameters(), values);
  EXPECT_EQ(m.parameter("coulomb.mu"), 0.3);
}

// A model answers what its effects do by stage, without their names: the normal force and its
// damping here, no relaxation.
TEST(Model, SaysWhichStagesItsEffectsRunAt) {
  const Model m = Model::withEffects({"coulomb", "stiffness", "damping"});
  EXPECT_TRUE(m.hasStage(Stage::kNormalForce));
  EXPECT_TRUE(m.hasStage(Stage::kNormalDamping));
  EXPECT_TRUE(m.hasStage(Stage::kFriction));
  EXPECT_FALSE(m.hasStage(Stage::kNormalRelaxation));
  EXPECT_FALSE(m.hasStage(Stage::kNormalLaw));
}

TEST(Model, RejectsOutOfBoundsNonFiniteAndUnknown) {
  Model m = Model::withEffects({"stiffness", "coulomb"});
  EXPECT_THROW(m.setParameter("coulomb.mu", -0.1), InputError);
  EXPECT_THROW(m.setParameter("coulomb.mu", std::nan("")), InputError);
  EXPECT_THROW(m.setParameter("coulomb.nu", 0.1), InputError);
  EXPECT_THROW(m.setParameters(std::vector<double>{1.0}), InputError);
  EXPECT_THROW(Model::withEffects({"stiffness", "glue"}), InputError);
  EXPECT_THROW(Model::withEffects({"coulomb"}), InputError);  // needs stiffness
  EXPECT_THROW(Model::withEffects({"stiffness", "stiffness"}), InputError);
}

TEST(Model, EveryRegisteredEffectHasBoundedDefaults) {
  for (const auto& id : registeredEffectIds()) {
    const auto e = createEffect(id);
    ASSERT_NE(e, nullptr) << id;
    EXPECT_EQ(e->id(), id);
    for (const auto& p : e->parameterSpecs()) {
      EXPECT_LE(p.lower, p.default_value) << id << "." << p.name;
      EXPECT_GE(p.upper, p.default_value) << id << "." << p.name;
      EXPECT_FALSE(p.unit.empty()) << id << "." << p.name;
    }
    for (const auto& s : e->stateSlots()) EXPECT_FALSE(s.unit.empty()) << id << "." << s.name;
  }
}

// The simulation CSV's state columns and the integrator's state count come from this layout:
// every registered effect's slots in registration order, whatever effects a model holds.
TEST(Model, StateLayoutIsEveryRegisteredSlotInRegistrationOrder) {
  StateLayout expected;
  for (const auto& id : registeredEffectIds()) expected.add(id, createEffect(id)->stateSlots());
  const Model bare = Model::withEffects({"stiffness"});
  const Model full = Model::withEffects({"stiffness", "coulomb", "stribeck", "bristle", "dwell"});
  EXPECT_EQ(bare.stateLayout().valueNames(), expected.valueNames());
  EXPECT_EQ(full.stateLayout().valueNames(), expected.valueNames());
  for (std::size_t i = 0; i < full.effectCount(); ++i) {
    const Effect& e = full.effect(i);
    if (e.stateSlots().empty()) continue;
    EXPECT_EQ(e.stateOffset(), expected.offsetOf(std::string(e.id()))) << e.id();
  }
}

// Today's simulation CSV columns of the bristle and dwell states.
TEST(StateLayout, NamesPlaneVectorComponentsByAxis) {
  StateLayout layout;
  layout.add("stiffness", createEffect("stiffness")->stateSlots());
  layout.add("bristle", createEffect("bristle")->stateSlots());
  layout.add("dwell", createEffect("dwell")->stateSlots());
  const std::vector<std::string> expected = {"zx", "zy", "zz", "theta_n", "s_dw"};
  EXPECT_EQ(layout.valueNames(), expected);
  EXPECT_EQ(layout.size(), 5);
  EXPECT_EQ(layout.offsetOf("bristle"), 0);
  EXPECT_EQ(layout.offsetOf("dwell"), 4);
  EXPECT_EQ(layout.offsetOf("stiffness"), -1);
  EXPECT_EQ(layout.describe(2), "bristle state zz");
  EXPECT_EQ(layout.describe(4), "dwell state s_dw");
}

TEST(StateLayout, RefusesMoreStatesThanAPairStateHolds) {
  StateLayout layout;
  const StateSlot vector{"v", StateSlot::Kind::kPlaneVector, "m", "a plane vector"};
  for (int i = 0; i + 3 <= PairState::kCapacity; i += 3)
    layout.add("e" + std::to_string(i), {vector});
  EXPECT_THROW(layout.add("one_too_many", {vector}), std::length_error);
}

TEST(Model, NoContactGivesNothing) {
  const Model m = Model::withEffects({"stiffness", "damping", "coulomb", "bristle", "spin"});
  const int z = stateOffset(m, "bristle");
  PairState state;
  state.vector(z) = Eigen::Vector3d(1e-6, 0, 0);
  const ContactResult r = m.evaluate(volume::ContactVolume{}, RelativeMotion{}, state);
  EXPECT_EQ(r.wrench.f_W, Eigen::Vector3d::Zero());
  EXPECT_EQ(Eigen::Vector3d(r.rates.vector(z)), Eigen::Vector3d::Zero());
}

TEST(Model, SettleProjectsAndResets) {
  const Model m = Model::withEffects({"stiffness", "coulomb", "stribeck", "bristle", "dwell"});
  const volume::ContactVolume cv = sphereContact();
  const int z = stateOffset(m, "bristle"), s_dw = stateOffset(m, "dwell");
  PairState state;
  state.vector(z) = 1e-5 * tangent(cv.n_W) + 2e-6 * cv.n_W;
  state[s_dw] = 0.9;
  RelativeMotion slide;
  slide.v_c_W = 0.01 * tangent(cv.n_W);  // s ≈ 0 < s_dw: bonds break at once
  EXPECT_TRUE(m.settle(cv, slide, state));
  EXPECT_NEAR(state.vector(z).dot(cv.n_W), 0.0, 1e-20);  // 1e-5 m times round-off
  EXPECT_LT(state[s_dw], 1e-30);
  EXPECT_TRUE(m.settle(volume::ContactVolume{}, slide, state));
  EXPECT_EQ(Eigen::Vector3d(state.vector(z)), Eigen::Vector3d::Zero());
  EXPECT_EQ(state[s_dw], 0.0);
}

TEST(Model, DistributedFrictionNeedsAnIntegratingEffect) {
  try {
    Model::withEffects({"stiffness"}).checkDistributedFriction();
    FAIL() << "a model without coulomb expected to throw";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(),
              "distributed friction integrates coulomb's friction pointwise; add the coulomb "
              "effect");
  }
  EXPECT_NO_THROW(Model::withEffects({"stiffness", "coulomb", "spin"}).checkDistributedFriction());
}

}  // namespace
}  // namespace vcontact::dynamics::test
