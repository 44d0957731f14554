#include "dynamics/effects/registry.hpp"

#include <array>

namespace vcontact::dynamics {

// Factories, each defined in the effect's own file.
std::unique_ptr<Effect> makeStiffness();
std::unique_ptr<Effect> makeDamping();
std::unique_ptr<Effect> makeRollingResistance();
std::unique_ptr<Effect> makeCoulomb();
std::unique_ptr<Effect> makeStribeck();
std::unique_ptr<Effect> makeBristle();
std::unique_ptr<Effect> makeViscous();
std::unique_ptr<Effect> makeSpin();
std::unique_ptr<Effect> makeContensou();
std::unique_ptr<Effect> makeDwell();
std::unique_ptr<Effect> makeMisalignment();

namespace {

using Factory = std::unique_ptr<Effect> (*)();

// The registration list: one entry per effect.
constexpr std::array<Factory, 11> kFactories = {
    &makeStiffness, &makeDamping, &makeRollingResistance, &makeCoulomb,
    &makeStribeck,  &makeBristle, &makeViscous,           &makeSpin,
    &makeContensou, &makeDwell,   &makeMisalignment,
};

}  // namespace

std::unique_ptr<Effect> createEffect(std::string_view id) {
  for (Factory make : kFactories) {
    auto effect = make();
    if (effect->id() == id) return effect;
  }
  return nullptr;
}

std::vector<std::string> registeredEffectIds() {
  std::vector<std::string> ids;
  for (Factory make : kFactories) ids.emplace_back(make()->id());
  return ids;
}

}  // namespace vcontact::dynamics
