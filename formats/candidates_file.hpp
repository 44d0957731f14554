#pragma once
// Candidates files (docs/EXTENDING.md "Candidates files"): the effects that
// `vcontact diagnose --candidates FILE` tries, instead of the whole library.
//
//   {"format": "vcontact.candidates/1",
//    "candidates": {"viscous": {},                      // a built-in effect, defaults
//                   "stribeck": {"mu_S": 0.3},          // ... starting from these values
//                   "mu_load": {"kind": "expression", ...}}}   // formats/expression_entry.hpp
//
// Errors name the file, the JSON place ("candidates.stribeck.mu_S") and what was expected.

#include <nlohmann/json.hpp>
#include <string>

#include "validation/candidates.hpp"

namespace vcontact::formats {

/// @throws InputError on a wrong format, an unknown effect or parameter, a value outside its
///         bounds, a bad expression effect, or no candidate at all
validation::CandidateSet candidatesFromJson(const nlohmann::json& j, const std::string& source);
validation::CandidateSet readCandidatesFile(const std::string& path);

}  // namespace vcontact::formats
