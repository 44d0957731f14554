#include "formats/expression_entry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dynamics/effects/expression.hpp"
#include "dynamics/effects/registry.hpp"
#include "geometry/error.hpp"

namespace vcontact::formats {
namespace {

using dynamics::ExpressionDefinition;

// The widest bound a parameter may have. Any physical coefficient in SI units lies well within
// 1e±100, and fit scales a parameter by its range: ±1e308 overflowed that range to infinity and
// the fit's first step to NaN ("b = -nan is outside its physical range").
constexpr double kMaxBound = 1e100;

constexpr const char* kTermKeys[] = {"normal", "tangential", "spin"};

double number(const nlohmann::json& j, const char* key, const std::string& source,
              const std::string& place) {
  if (!j.contains(key) || !j[key].is_number() || !std::isfinite(j[key].get<double>()))
    throw InputError(source, place + "." + key + ": expected a finite number");
  return j[key].get<double>();
}

dynamics::ParameterSpec readParameter(const std::string& name, const nlohmann::json& j,
                                      const std::string& source, const std::string& place) {
  if (!j.is_object()) {
    throw InputError(source, place + ": expected {\"value\", \"unit\", \"lower\", \"upper\"}");
  }
  for (const auto& [key, value] : j.items()) {
    if (key != "value" && key != "unit" && key != "lower" && key != "upper" && key != "description")
      throw InputError(
          source,
          place + "." + key + ": unknown key; expected value, unit, lower, upper, description");
  }
  if (!j.contains("unit") || !j["unit"].is_string())
    throw InputError(source, place + ".unit: expected a string (\"-\" for none)");
  dynamics::ParameterSpec p;
  p.name = name;
  p.unit = j["unit"].get<std::string>();
  p.default_value = number(j, "value", source, place);
  p.lower = number(j, "lower", source, place);
  p.upper = number(j, "upper", source, place);
  if (j.contains("description")) {
    if (!j["description"].is_string())
      throw InputError(source, place + ".description: expected a string");
    p.description = j["description"].get<std::string>();
  }
  if (!(std::abs(p.lower) <= kMaxBound && std::abs(p.upper) <= kMaxBound)) {
    std::ostringstream s;
    s << place << ": expected bounds within +-" << kMaxBound << ", got [" << p.lower << ", "
      << p.upper << "] (give the parameter a unit in which its range is finite)";
    throw InputError(source, s.str());
  }
  if (!(p.lower <= p.default_value && p.default_value <= p.upper)) {
    std::ostringstream s;
    s << place << ": expected lower <= value <= upper, got " << p.lower << " <= " << p.default_value
      << " <= " << p.upper;
    throw InputError(source, s.str());
  }
  return p;
}

std::vector<std::string> readRequires(const nlohmann::json& j, const std::string& source,
                                      const std::string& place) {
  const std::string expected = ": expected an array of effect ids";
  if (!j.is_array()) throw InputError(source, place + expected);
  std::vector<std::string> ids;
  for (const auto& item : j) {
    if (!item.is_string()) throw InputError(source, place + expected);
    ids.push_back(item.get<std::string>());
  }
  return ids;
}

ExpressionDefinition readDefinition(const std::string& id, const nlohmann::json& entry,
                                    const std::string& source, const std::string& place) {
  ExpressionDefinition def;
  def.id = id;
  bool any_term = false;
  for (const auto& [key, value] : entry.items()) {
    const std::string where = place + "." + key;
    if (key == "kind") {
      if (value != "expression") throw InputError(source, where + ": expected \"expression\"");
    } else if (key == "parameters") {
      if (!value.is_object()) throw InputError(source, where + ": expected an object");
      for (const auto& [name, p] : value.items())
        def.parameters.push_back(readParameter(name, p, source, where + "." + name));
    } else if (key == "requires") {
      def.requires_list = readRequires(value, source, where);
    } else if (key == "normal" || key == "tangential" || key == "spin") {
      if (!value.is_string()) throw InputError(source, where + ": expected a formula (string)");
      (key == "normal"       ? def.normal
       : key == "tangential" ? def.tangential
                             : def.spin) = value.get<std::string>();
      any_term = any_term || !value.get<std::string>().empty();
    } else {
      throw InputError(source, where +
                                   ": unknown key; expected kind, parameters, normal, tangential, "
                                   "spin, requires");
    }
  }
  if (!any_term)
    throw InputError(source, place + ": expected at least one of normal, tangential, spin");
  return def;
}

std::string termText(const ExpressionDefinition& def, const std::string& term) {
  return term == "normal" ? def.normal : term == "tangential" ? def.tangential : def.spin;
}

// The formula around a 0-based position: at most kExcerptSide characters either side, with
// "..." where cut (a formula can be 5,000 characters), never inside a UTF-8 sequence.
std::string excerpt(const std::string& text, int position) {
  constexpr std::size_t kExcerptSide = 30;
  const std::size_t at = std::min(static_cast<std::size_t>(std::max(position, 0)), text.size());
  std::size_t begin = at > kExcerptSide ? at - kExcerptSide : 0;
  std::size_t end = std::min(text.size(), at + kExcerptSide);
  const auto continuation = [&](std::size_t i) {
    return i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
  };
  while (begin > 0 && continuation(begin)) --begin;
  while (continuation(end)) ++end;
  return (begin > 0 ? "..." : "") + text.substr(begin, end - begin) +
         (end < text.size() ? "..." : "");
}

std::string syntaxMessage(const dynamics::ExpressionSyntaxError& e, const std::string& text,
                          const std::string& place) {
  std::ostringstream s;
  s << place << "." << e.term() << ": " << e.reason();
  if (e.position() >= 0) {
    s << " (at character " << e.position() + 1 << " of \"" << excerpt(text, e.position()) << "\")";
  }
  return s.str();
}

}  // namespace

bool isExpressionEntry(const nlohmann::json& entry) {
  return entry.is_object() && entry.contains("kind");
}

std::unique_ptr<dynamics::Effect> expressionEffectFromJson(const std::string& id,
                                                           const nlohmann::json& entry,
                                                           const std::string& source,
                                                           const std::string& place) {
  if (!dynamics::isExpressionName(id)) {
    throw InputError(source, place +
                                 ": expected an effect id of letters, digits and '_' that "
                                 "does not start with a digit, got '" +
                                 excerpt(id, 0) + "'");
  }
  if (dynamics::createEffect(id)) {
    throw InputError(source, place + ": '" + id +
                                 "' is a built-in effect; give the expression effect a new name");
  }
  auto def = std::make_shared<const ExpressionDefinition>(readDefinition(id, entry, source, place));
  try {
    return dynamics::makeExpressionEffect(def);
  } catch (const dynamics::ExpressionSyntaxError& e) {
    if (e.term().empty()) throw InputError(source, place + ".parameters: " + e.reason());
    throw InputError(source, syntaxMessage(e, termText(*def, e.term()), place));
  }
}

nlohmann::json expressionEffectToJson(const dynamics::Effect& effect) {
  const ExpressionDefinition* def = dynamics::expressionDefinition(effect);
  nlohmann::json params = nlohmann::json::object();
  for (std::size_t i = 0; i < def->parameters.size(); ++i) {
    const auto& p = def->parameters[i];
    params[p.name] = {
        {"value", effect.parameter(i)}, {"unit", p.unit}, {"lower", p.lower}, {"upper", p.upper}};
    if (!p.description.empty()) params[p.name]["description"] = p.description;
  }
  nlohmann::json j = {{"kind", "expression"}, {"parameters", params}};
  for (const char* term : kTermKeys) {
    const std::string text = termText(*def, term);
    if (!text.empty()) j[term] = text;
  }
  if (!def->requires_list.empty()) j["requires"] = def->requires_list;
  return j;
}

}  // namespace vcontact::formats
