#include "dynamics/effects/registry.hpp"

#include "dynamics/effects/effect_list.hpp"

namespace vcontact::dynamics {

std::unique_ptr<Effect> createEffect(std::string_view id) {
  for (EffectFactory make : effectFactories()) {
    auto effect = make();
    if (effect->id() == id) return effect;
  }
  return nullptr;
}

std::vector<std::string> registeredEffectIds() {
  std::vector<std::string> ids;
  for (EffectFactory make : effectFactories()) ids.emplace_back(make()->id());
  return ids;
}

const StateLayout& registeredStateLayout() {
  static const StateLayout layout = [] {
    StateLayout l;
    for (EffectFactory make : effectFactories()) {
      const auto effect = make();
      l.add(std::string(effect->id()), effect->stateSlots());
    }
    return l;
  }();
  return layout;
}

}  // namespace vcontact::dynamics
