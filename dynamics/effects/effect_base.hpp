#pragma once
// The base class of the effects in this folder: id, parameter specs, stage, states and clone
// from static members of the derived class (CRTP), so that an effect file holds only its
// physics. Register the effect by adding its id to the effect list in dynamics/CMakeLists.txt.

#include <memory>
#include <vector>

#include "dynamics/effect.hpp"

namespace vcontact::dynamics {

/// Derived provides kId, kStage and specs(); an effect with states also states(), the
/// StateSlots it owns.
template <class Derived>
class EffectBase : public Effect {
 public:
  EffectBase() { initialiseParameters(Derived::specs()); }
  std::string_view id() const override { return Derived::kId; }
  const std::vector<ParameterSpec>& parameterSpecs() const override { return Derived::specs(); }
  Stage stage() const override { return Derived::kStage; }
  const std::vector<StateSlot>& stateSlots() const override {
    if constexpr (requires { Derived::states(); }) {
      return Derived::states();
    } else {
      return Effect::stateSlots();
    }
  }
  std::unique_ptr<Effect> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
};

}  // namespace vcontact::dynamics
