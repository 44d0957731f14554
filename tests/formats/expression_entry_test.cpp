// Expression effects in model files and candidates files (docs/EXTENDING.md): a valid entry
// builds an effect that round-trips through modelToJson; a formula that does not compile stops
// the read with the file, the JSON place and muparser's position.

#include "formats/expression_entry.hpp"

#include <gtest/gtest.h>

#include "dynamics/effects/expression.hpp"
#include "formats/candidates_file.hpp"
#include "formats/model_file.hpp"
#include "support/test_support.hpp"

namespace vcontact::formats {
namespace {

const char* kSource = "load.model.json";

nlohmann::json model() {
  return nlohmann::json::parse(R"({
    "format": "vcontact.model/1",
    "effects": {
      "stiffness": {"kv": 5e12}, "coulomb": {"mu": 0.2},
      "mu_load": {"kind": "expression",
                  "parameters": {"b": {"value": 0.01, "unit": "1/N", "lower": 0, "upper": 1,
                                       "description": "load growth of mu"}},
                  "tangential": "-b*f_n^2", "requires": ["stiffness"]}}})");
}

std::string modelError(const nlohmann::json& j) {
  return test::inputErrorMessage([&] { modelFromJson(j, kSource); });
}

TEST(ExpressionEntry, AModelFileEntryBuildsTheEffectAndRoundTrips) {
  const dynamics::Model m = modelFromJson(model(), kSource);
  EXPECT_TRUE(m.has("mu_load"));
  EXPECT_EQ(m.parameter("mu_load.b"), 0.01);
  const auto specs = m.parameterSpecs();
  EXPECT_EQ(specs.back().name, "mu_load.b");
  EXPECT_EQ(specs.back().unit, "1/N");
  EXPECT_EQ(specs.back().upper, 1.0);
  dynamics::Model fitted = m;
  fitted.setParameter("mu_load.b", 0.25);
  const nlohmann::json written = modelToJson(fitted);
  EXPECT_EQ(written["effects"]["mu_load"]["parameters"]["b"]["value"], 0.25);
  EXPECT_EQ(written["effects"]["mu_load"]["tangential"], "-b*f_n^2");
  const dynamics::Model again = modelFromJson(written, kSource);
  EXPECT_EQ(again.parameters(), fitted.parameters());
}

TEST(ExpressionEntry, ABadFormulaNamesFileKeyAndCharacter) {
  nlohmann::json j = model();
  j["effects"]["mu_load"]["tangential"] = "-b*f_n^";
  const std::string msg = modelError(j);
  EXPECT_NE(msg.find("load.model.json: effects.mu_load.tangential: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("muparser, at character"), std::string::npos) << msg;
  j["effects"]["mu_load"]["tangential"] = "-b*load";
  const std::string unknown = modelError(j);
  // "load" starts at index 3, character 4.
  EXPECT_NE(unknown.find("at character 4 of \"-b*load\""), std::string::npos) << unknown;
}

TEST(ExpressionEntry, BadEntriesAreRefusedWithTheirPlace) {
  struct Case {
    const char* pointer;
    nlohmann::json value;
    const char* fragment;
  };
  const Case cases[] = {
      {"/effects/mu_load/kind", "formula", "effects.mu_load.kind: expected \"expression\""},
      {"/effects/mu_load/parameters/b/lower", 0.5, "effects.mu_load.parameters.b: expected lower"},
      {"/effects/mu_load/parameters/b/unit", 3, "effects.mu_load.parameters.b.unit"},
      {"/effects/mu_load/tangential", "", "expected at least one of normal, tangential, spin"},
      {"/effects/mu_load/torque", "-b", "effects.mu_load.torque: unknown key"},
      {"/effects/mu_load/parameters/v_t",
       nlohmann::json::parse(R"({"value": 0, "unit": "-", "lower": 0, "upper": 1})"),
       "effects.mu_load.parameters: parameter 'v_t' is named like a variable"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = model();
    j[nlohmann::json::json_pointer(c.pointer)] = c.value;
    EXPECT_NE(modelError(j).find(c.fragment), std::string::npos)
        << c.pointer << ": " << modelError(j);
  }
  nlohmann::json builtin = model();
  builtin["effects"]["viscous"] = builtin["effects"]["mu_load"];
  EXPECT_NE(modelError(builtin).find("effects.viscous: 'viscous' is a built-in effect"),
            std::string::npos);
}

TEST(CandidatesFile, ReadsBuiltinsWithStartValuesAndExpressions) {
  nlohmann::json j = {{"format", "vcontact.candidates/1"},
                      {"candidates",
                       {{"viscous", nlohmann::json::object()},
                        {"stribeck", {{"mu_s", 0.3}}},
                        {"mu_load", model()["effects"]["mu_load"]}}}};
  const validation::CandidateSet set = candidatesFromJson(j, "c.json");
  EXPECT_EQ(set.ids(), (std::vector<std::string>{"mu_load", "stribeck", "viscous"}));
  EXPECT_NE(dynamics::expressionDefinition(*set.create("mu_load")), nullptr);
  EXPECT_EQ(set.create("stribeck")->parameter(0), 0.3);  // mu_s, its only parameter
  EXPECT_NE(set.create("coulomb"), nullptr);             // a requirement from the library
  j["candidates"]["stribeck"] = {{"mu_s", 20.0}};
  EXPECT_NE(test::inputErrorMessage([&] {
              candidatesFromJson(j, "c.json");
            }).find("c.json: candidates.stribeck.mu_s: expected a number in [0, 10]"),
            std::string::npos);
  j["candidates"] = {{"grip", nlohmann::json::object()}};
  EXPECT_NE(test::inputErrorMessage([&] {
              candidatesFromJson(j, "c.json");
            }).find("c.json: candidates.grip: unknown effect"),
            std::string::npos);
}

}  // namespace
}  // namespace vcontact::formats
