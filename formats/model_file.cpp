#include "formats/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dynamics/effects/expression.hpp"
#include "dynamics/effects/registry.hpp"
#include "formats/expression_entry.hpp"
#include "formats/scenario_reader.hpp"
#include "geometry/error.hpp"
#include "io/json_file.hpp"

namespace vcontact::formats {
namespace {

constexpr const char* kFormat = "vcontact.model/1";

std::string at(const std::string& place, const std::string& key) {
  return place.empty() ? key : place + "." + key;
}

std::string joined(const std::vector<std::string>& items) {
  std::ostringstream s;
  for (std::size_t i = 0; i < items.size(); ++i) s << (i ? ", " : "") << items[i];
  return s.str();
}

std::vector<std::string> parameterNamesOf(const dynamics::Effect& e) {
  std::vector<std::string> names;
  for (const auto& p : e.parameterSpecs()) names.push_back(p.name);
  return names;
}

// Reads the parameters of one effect into it; bounds are checked by Model::setParameter.
void readParameters(dynamics::Model& model, const dynamics::Effect& effect,
                    const nlohmann::json& params, const std::string& source,
                    const std::string& place) {
  if (!params.is_object()) {
    throw InputError(source, place + ": expected an object of parameters ({} for none)");
  }
  const std::string id(effect.id());
  for (const auto& [name, value] : params.items()) {
    const std::string where = at(place, name);
    const auto names = parameterNamesOf(effect);
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw InputError(source, where + ": unknown parameter of '" + id + "'; expected one of: " +
                                   (names.empty() ? std::string("(none)") : joined(names)));
    }
    if (!value.is_number()) throw InputError(source, where + ": expected a number");
    try {
      model.setParameter(id + "." + name, value.get<double>());
    } catch (const InputError& e) {
      throw InputError(source, where + ": " + e.message());
    }
  }
}

void readSettings(dynamics::Model& model, const nlohmann::json& j, const std::string& source,
                  const std::string& place) {
  if (!j.is_object()) throw InputError(source, place + ": expected an object");
  for (const auto& [key, value] : j.items()) {
    if (key != "v_eps") {
      throw InputError(source, at(place, key) + ": unknown setting; expected: v_eps");
    }
    if (!value.is_number() || !(value.get<double>() > 0.0)) {
      throw InputError(source, at(place, key) + ": expected a positive number (m/s)");
    }
    model.settings.v_eps = value.get<double>();
  }
}

void readFixed(dynamics::Model& model, const nlohmann::json& j, const std::string& source,
               const std::string& place) {
  const std::string expected = ": expected an array of parameter names (\"effect.parameter\")";
  if (!j.is_array()) throw InputError(source, place + expected);
  std::vector<std::string> names;
  for (const auto& item : j) {
    if (!item.is_string()) throw InputError(source, place + expected);
    names.push_back(item.get<std::string>());
  }
  try {
    model.setFixed(std::move(names));
  } catch (const InputError& e) {
    throw InputError(source, place + ": " + e.message() +
                                 "; expected one of: " + joined(model.parameterNames()));
  }
}

}  // namespace

dynamics::Model modelFromJson(const nlohmann::json& j, const std::string& source,
                              const std::string& place) {
  if (!j.is_object())
    throw InputError(source, (place.empty() ? "top level" : place) + ": expected a model object");
  for (const auto& [key, value] : j.items()) {
    if (key != "format" && key != "effects" && key != "fixed" && key != "settings") {
      throw InputError(source,
                       at(place, key) + ": unknown key; expected format, effects, fixed, settings");
    }
  }
  if (!j.contains("format") || j["format"] != kFormat) {
    throw InputError(source, at(place, "format") + ": expected \"" + kFormat + "\"");
  }
  if (!j.contains("effects") || !j["effects"].is_object()) {
    throw InputError(source, at(place, "effects") + ": expected an object of effects");
  }
  dynamics::Model model;
  for (const auto& [id, params] : j["effects"].items()) {
    // an effect id names the CSV columns of its share (id.fx, ...)
    if (const std::string why = detail::csvNameProblem(id); !why.empty()) {
      throw InputError(source, at(place, "effects") + ": effect id: " + why);
    }
    if (isExpressionEntry(params)) {
      model.add(expressionEffectFromJson(id, params, source, at(place, "effects." + id)));
      continue;
    }
    auto effect = dynamics::createEffect(id);
    if (!effect) {
      throw InputError(source, at(place, "effects." + id) + ": unknown effect; expected one of: " +
                                   joined(dynamics::registeredEffectIds()) +
                                   ", or an expression effect {\"kind\": \"expression\", ...}");
    }
    const dynamics::Effect& ref = *effect;
    model.add(std::move(effect));
    readParameters(model, ref, params, source, at(place, "effects." + id));
  }
  if (j.contains("settings")) readSettings(model, j["settings"], source, at(place, "settings"));
  try {
    model.validate();
  } catch (const InputError& e) {
    throw InputError(source,
                     (place.empty() ? "effects" : at(place, "effects")) + ": " + e.message());
  }
  if (j.contains("fixed")) readFixed(model, j["fixed"], source, at(place, "fixed"));
  return model;
}

dynamics::Model readModelFile(const std::string& path) {
  const nlohmann::json j = io::readJsonFile(path);
  return modelFromJson(j, path);
}

nlohmann::json modelToJson(const dynamics::Model& model) {
  nlohmann::json effects = nlohmann::json::object();
  for (std::size_t i = 0; i < model.effectCount(); ++i) {
    const dynamics::Effect& e = model.effect(i);
    if (dynamics::expressionDefinition(e)) {
      effects[std::string(e.id())] = expressionEffectToJson(e);
      continue;
    }
    nlohmann::json params = nlohmann::json::object();
    const auto& specs = e.parameterSpecs();
    for (std::size_t k = 0; k < specs.size(); ++k) params[specs[k].name] = e.parameter(k);
    effects[std::string(e.id())] = params;
  }
  return {{"format", kFormat},
          {"effects", effects},
          {"fixed", model.fixed()},
          {"settings", {{"v_eps", model.settings.v_eps}}}};
}

}  // namespace vcontact::formats
