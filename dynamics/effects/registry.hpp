#pragma once
// The effects a model can name (MODEL.md §3), by id. Each effect lives in its own file in this
// folder and is registered by its id in the effect list of dynamics/CMakeLists.txt.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dynamics/effect.hpp"
#include "dynamics/pair_state.hpp"

namespace vcontact::dynamics {

/// A new effect with default parameters, or nullptr for an unknown id.
std::unique_ptr<Effect> createEffect(std::string_view id);

/// Every registered id, in registration order.
std::vector<std::string> registeredEffectIds();

/// The state slots of every registered effect, in registration order (Model::stateLayout).
const StateLayout& registeredStateLayout();

}  // namespace vcontact::dynamics
