// Model files (DATASET.md "Model files"): a valid file builds the model; every kind of bad
// input stops with a message naming the file, the place and what was expected.

#include "formats/model_file.hpp"

#include <gtest/gtest.h>

#include "geometry/error.hpp"

namespace vcontact::formats {
namespace {

const char* kSource = "steel.model.json";

nlohmann::json valid() {
  return nlohmann::json::parse(R"({
    "format": "vcontact.model/1",
    "effects": {"stiffness": {"kv": 5.17e12}, "coulomb": {"mu": 0.2},
                "bristle": {"sigma0": 4500, "sigma1": 300}},
    "fixed": ["stiffness.kv"]})");
}

// The message of the InputError `j` raises, or "" when it reads.
std::string errorOf(const nlohmann::json& j) {
  try {
    modelFromJson(j, kSource);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelFile, ReadsTheDatasetExample) {
  const dynamics::Model m = modelFromJson(valid(), kSource);
  EXPECT_EQ(m.parameter("stiffness.kv"), 5.17e12);
  EXPECT_EQ(m.parameter("bristle.sigma1"), 300.0);
  EXPECT_EQ(m.parameter("coulomb.v_s"), 1e-3);  // default
  EXPECT_EQ(m.fixed(), std::vector<std::string>{"stiffness.kv"});
  const dynamics::Model again = modelFromJson(modelToJson(m), kSource);
  EXPECT_EQ(again.parameters(), m.parameters());
}

struct BadCase {
  const char* what;
  const char* json_pointer;
  nlohmann::json value;
  const char* expected_fragment;
};

TEST(ModelFile, NamesFilePlaceAndExpectation) {
  const std::vector<BadCase> cases = {
      {"unknown effect", "/effects/glue", nlohmann::json::object(),
       "steel.model.json: effects.glue: unknown effect; expected one of: stiffness"},
      {"unknown parameter", "/effects/coulomb/nu", 0.1,
       "effects.coulomb.nu: unknown parameter of 'coulomb'; expected one of: mu, v_s"},
      {"non-number", "/effects/coulomb/mu", "0.2", "effects.coulomb.mu: expected a number"},
      {"out of bounds", "/effects/coulomb/mu", -0.2,
       "effects.coulomb.mu: coulomb.mu = -0.2 is outside its physical range"},
      {"wrong format", "/format", "vcontact.model/2", "format: expected \"vcontact.model/1\""},
      {"bad fixed", "/fixed/0", "stiffness.k", "fixed: no parameter 'stiffness.k'"},
      {"unknown key", "/extra", 1, "extra: unknown key"},
  };
  for (const auto& c : cases) {
    nlohmann::json j = valid();
    j[nlohmann::json::json_pointer(c.json_pointer)] = c.value;
    const std::string message = errorOf(j);
    EXPECT_NE(message.find(c.expected_fragment), std::string::npos)
        << c.what << ": got \"" << message << "\"";
    EXPECT_EQ(message.rfind(kSource, 0), 0u) << c.what;
  }
}

TEST(ModelFile, MissingRequiredEffectAndStribeckBelowCoulomb) {
  nlohmann::json j = valid();
  j["effects"].erase("coulomb");
  EXPECT_NE(errorOf(j).find("effect 'bristle' needs effect 'coulomb'"), std::string::npos);
  j = valid();
  j["effects"]["stribeck"] = {{"mu_s", 0.1}};
  EXPECT_NE(errorOf(j).find("stribeck.mu_s = 0.1 must be >= coulomb.mu"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::formats
