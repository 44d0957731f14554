#pragma once
// The effects a model can name (MODEL.md §3), by id. Each effect lives in its own file in this
// folder and is registered by one line in registry.cpp.

#include <memory>
#include <string>
#include <vector>

#include "dynamics/effect.hpp"

namespace vcontact::dynamics {

/// A new effect with default parameters, or nullptr for an unknown id.
std::unique_ptr<Effect> createEffect(std::string_view id);

/// Every registered id, in registration order.
std::vector<std::string> registeredEffectIds();

}  // namespace vcontact::dynamics
