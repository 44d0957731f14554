#pragma once
// Model files (docs/DATASET.md "Model files"):
//
//   {"format": "vcontact.model/1",
//    "effects": {"stiffness": {"kv": 5.17e12}, "coulomb": {"mu": 0.2}, "spin": {}},
//    "fixed": ["stiffness.kv"],
//    "settings": {"v_eps": 1e-5}}          // optional: model settings, not fitted
//
// An effect entry {"kind": "expression", ...} is a user-defined expression effect
// (formats/expression_entry.hpp, docs/EXTENDING.md). Parameters left out take their defaults.
// Errors name the file, the JSON place
// ("effects.coulomb.mu") and what was expected.

#include <nlohmann/json.hpp>
#include <string>

#include "dynamics/model.hpp"

namespace vcontact::formats {

/// @param source file name for messages; `place` prefixes JSON places (e.g. "pairs[0].model")
/// @throws InputError on unknown effects or parameters, non-numbers, out-of-bounds values,
///         missing required effects
dynamics::Model modelFromJson(const nlohmann::json& j, const std::string& source,
                              const std::string& place = "");
dynamics::Model readModelFile(const std::string& path);

nlohmann::json modelToJson(const dynamics::Model& model);

}  // namespace vcontact::formats
