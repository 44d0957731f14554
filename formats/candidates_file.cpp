#include "formats/candidates_file.hpp"

#include <cmath>
#include <sstream>

#include "dynamics/effects/registry.hpp"
#include "formats/expression_entry.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"

namespace vcontact::formats {
namespace {

constexpr const char* kFormat = "vcontact.candidates/1";

std::string joined(const std::vector<std::string>& items) {
  std::ostringstream s;
  for (std::size_t i = 0; i < items.size(); ++i) s << (i ? ", " : "") << items[i];
  return s.str();
}

// Sets the starting values a built-in candidate's entry gives, each within its bounds.
void readStartValues(dynamics::Effect& effect, const nlohmann::json& params,
                     const std::string& source, const std::string& place) {
  if (!params.is_object()) {
    throw InputError(source, place + ": expected an object of starting values ({} for defaults)");
  }
  const auto& specs = effect.parameterSpecs();
  for (const auto& [name, value] : params.items()) {
    const std::string where = place + "." + name;
    std::size_t i = 0;
    while (i < specs.size() && specs[i].name != name) ++i;
    if (i == specs.size()) {
      std::vector<std::string> names;
      for (const auto& p : specs) names.push_back(p.name);
      throw InputError(source, where + ": unknown parameter; expected one of: " +
                                   (names.empty() ? std::string("(none)") : joined(names)));
    }
    const double v = value.is_number() ? value.get<double>() : NAN;
    if (!(v >= specs[i].lower && v <= specs[i].upper)) {
      std::ostringstream s;
      s << where << ": expected a number in [" << specs[i].lower << ", " << specs[i].upper << "] "
        << specs[i].unit;
      throw InputError(source, s.str());
    }
    effect.setParameter(i, v);
  }
}

// Each effect a candidate requires is another candidate or a registered effect: diagnose
// would otherwise stop later with an error that does not name the file.
void checkRequirements(const validation::CandidateSet& set, const std::string& source) {
  for (const std::string& id : set.ids()) {
    for (const std::string_view required : set.create(id)->requiredEffects()) {
      if (set.create(required)) continue;
      throw InputError(source, "candidates." + id + ".requires: unknown effect '" +
                                   std::string(required) + "'; expected a candidate or one of: " +
                                   joined(dynamics::registeredEffectIds()));
    }
  }
}

}  // namespace

validation::CandidateSet candidatesFromJson(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, "top level: expected a candidates object");
  for (const auto& [key, value] : j.items()) {
    if (key != "format" && key != "candidates")
      throw InputError(source, key + ": unknown key; expected format, candidates");
  }
  if (!j.contains("format") || j["format"] != kFormat)
    throw InputError(source, std::string("format: expected \"") + kFormat + "\"");
  if (!j.contains("candidates") || !j["candidates"].is_object() || j["candidates"].empty()) {
    throw InputError(source, "candidates: expected a non-empty object of effects");
  }
  validation::CandidateSet set;
  for (const auto& [id, entry] : j["candidates"].items()) {
    const std::string place = "candidates." + id;
    if (isExpressionEntry(entry)) {
      set.add(expressionEffectFromJson(id, entry, source, place));
      continue;
    }
    auto effect = dynamics::createEffect(id);
    if (!effect) {
      throw InputError(source, place + ": unknown effect; expected one of: " +
                                   joined(dynamics::registeredEffectIds()) +
                                   ", or an expression effect {\"kind\": \"expression\", ...}");
    }
    readStartValues(*effect, entry, source, place);
    set.add(std::move(effect));
  }
  checkRequirements(set, source);
  return set;
}

validation::CandidateSet readCandidatesFile(const std::string& path) {
  return candidatesFromJson(io::readJsonFile(path), path);
}

}  // namespace vcontact::formats
