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
  EXPECT_NE(msg.find("tangential: muparser: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("(at character 9 of \"-b*f_n^\")"), std::string::npos) << msg;
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
      // fit scales by the range: ±1e308 overflowed it and printed "b = -nan" (issue 36)
      {"/effects/mu_load/parameters/b/lower", -1e308,
       "effects.mu_load.parameters.b: expected bounds within +-1e+100, got [-1e+308, 1]"},
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

std::string formulaError(const std::string& formula) {
  nlohmann::json j = model();
  j["effects"]["mu_load"]["tangential"] = formula;
  return modelError(j);
}

// muparser syntax docs/EXTENDING.md does not name, which changed a formula's meaning silently
// (issue 36): the comma operator kept the last of "0,001*f_n", '=' wrote the f_n the next
// term read.
TEST(ExpressionEntry, CommaOutsideArgumentsAssignmentAndLeadingZerosAreRefused) {
  struct Case {
    const char* formula;
    const char* fragment;
  };
  const Case cases[] = {
      {"-0,001*f_n",
       "effects.mu_load.tangential: ',' separates a function's arguments only; write decimals "
       "with a point (0.001, not 0,001) (at character 3 of \"-0,001*f_n\")"},
      {"-(0,001)*f_n", "',' separates a function's arguments only"},
      {"-max(0,001*f_n, b)",
       "a number starts with 0 followed by a digit; write decimals with a point (0.001, not "
       "0,001) (at character 8 of \"-max(0,001*f_n, b)\")"},
      {"0*(f_n=1e3)+b*f_n",
       "'=' would assign to a variable, which a formula may not do; compare with '==' (at "
       "character 7 of \"0*(f_n=1e3)+b*f_n\")"},
      {"b+=1", "'=' would assign"},
      {"f_n===1", "'=' would assign"},
  };
  for (const Case& c : cases) {
    EXPECT_NE(formulaError(c.formula).find(c.fragment), std::string::npos)
        << c.formula << ": " << formulaError(c.formula);
  }
}

TEST(ExpressionEntry, DocumentedOperatorsStillCompile) {
  for (const char* formula :
       {"-b*max(f_n, 0.5)", "f_n <= 1 ? -b : 0", "(f_n == 1) + (f_n != 2) + (f_n >= 3)",
        "-b*f_n*1e-3 + 0.5 + .5 + 5. + 0", "-sum(b, 2, 3)*_pi", "f_n > 1 && v_t < 1 || s"}) {
    nlohmann::json j = model();
    j["effects"]["mu_load"]["tangential"] = formula;
    EXPECT_NO_THROW(modelFromJson(j, kSource)) << formula;
  }
}

TEST(ExpressionEntry, ALongFormulaIsRefusedWithAShortExcerpt) {
  std::string sum;
  for (int i = 0; i < 2600; ++i) sum += "b+";  // 5,201 characters with the last "b"
  const std::string tooLong = formulaError(sum + "b");
  EXPECT_NE(tooLong.find("tangential: a formula of 5201 characters; at most 5000"),
            std::string::npos)
      << tooLong.substr(0, 300);
  EXPECT_LT(tooLong.size(), 300u);
  // A mistake at the end of a 4,000-character formula: 30 characters either side are quoted.
  const std::string unknown = formulaError(sum.substr(0, 4000) + "zz");
  EXPECT_NE(unknown.find("(at character 4001 of \"...b+b+b+"), std::string::npos)
      << unknown.substr(0, 400);
  EXPECT_LT(unknown.size(), 300u) << unknown.substr(0, 400);
}

TEST(ExpressionEntry, IdsAndParameterNamesMustBeNames) {
  nlohmann::json empty = model();
  empty["effects"][""] = empty["effects"]["mu_load"];
  empty["effects"].erase("mu_load");
  // The model file's reader refuses an empty id before the expression entry sees it.
  EXPECT_NE(modelError(empty).find("effects: effect id: expected a name, got an empty string"),
            std::string::npos)
      << modelError(empty);
  const nlohmann::json p = {{"value", 0}, {"unit", "-"}, {"lower", 0}, {"upper", 1}};
  for (const char* name : {"_pi", "sin"}) {
    nlohmann::json j = model();
    j["effects"]["mu_load"]["parameters"][name] = p;
    EXPECT_NE(modelError(j).find("effects.mu_load.parameters: parameter '" + std::string(name) +
                                 "' is named like a function or constant of muparser"),
              std::string::npos)
        << modelError(j);
  }
  nlohmann::json j = model();
  j["effects"]["mu_load"]["parameters"]["2b"] = p;
  EXPECT_NE(modelError(j).find("parameter '2b': expected a name of letters, digits and '_'"),
            std::string::npos)
      << modelError(j);
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

// A candidate requiring an effect that is neither a candidate nor in the library: named with
// the file and the place (issue 36: diagnose stopped later, without the file).
TEST(CandidatesFile, AnUnknownRequiredEffectIsNamedWithTheFile) {
  nlohmann::json entry = model()["effects"]["mu_load"];
  entry["requires"] = {"stiffness", "grip"};
  const nlohmann::json j = {{"format", "vcontact.candidates/1"},
                            {"candidates", {{"mu_load", entry}}}};
  const std::string msg = test::inputErrorMessage([&] { candidatesFromJson(j, "c.json"); });
  EXPECT_NE(msg.find("c.json: candidates.mu_load.requires: unknown effect 'grip'; expected a "
                     "candidate or one of: "),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace vcontact::formats
