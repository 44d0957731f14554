#pragma once
// The entry of an expression effect in a model file or a candidates file (docs/EXTENDING.md):
//
//   "mu_load": {"kind": "expression",
//               "parameters": {"b": {"value": 1e-3, "unit": "1/N", "lower": 0, "upper": 1}},
//               "tangential": "-(mu_C + b*f_n)*f_n",     // and/or "normal", "spin"
//               "requires": ["stiffness", "coulomb"]}    // optional
//
// Errors name the file, the JSON place ("effects.mu_load.tangential") and, for a formula that
// does not compile, muparser's reason and the character where it stopped.

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "dynamics/effect.hpp"

namespace vcontact::formats {

/// Is this effect entry an expression effect (an object with "kind")?
bool isExpressionEntry(const nlohmann::json& entry);

/// @param place the entry's JSON place, e.g. "effects.mu_load"
/// @throws InputError (source `source`) on a bad key, parameter or formula; or when `id` is
///         the id of a built-in effect
std::unique_ptr<dynamics::Effect> expressionEffectFromJson(const std::string& id,
                                                           const nlohmann::json& entry,
                                                           const std::string& source,
                                                           const std::string& place);

/// The entry of an expression effect with its current parameter values as "value".
/// @pre dynamics::expressionDefinition(effect) is not null
nlohmann::json expressionEffectToJson(const dynamics::Effect& effect);

}  // namespace vcontact::formats
