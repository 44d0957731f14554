#pragma once
// Scenario files: bodies, contact pairs with their models and volume methods, gravity,
// duration, output rate, outputs and integration tolerances. The format is documented in
// docs/SCENARIO.md. Relative paths (meshes, model files) are relative to the scenario file.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dynamics/scenario.hpp"

namespace vcontact::formats {

/// Which CSV files and columns a simulation writes.
struct OutputSelection {
  bool bodies = true;  ///< bodies.csv
  bool pairs = true;   ///< pair_<name>.csv: volume, centroid, normal, wrench, states
  bool shares = true;  ///< each effect's share of the wrench in pair_<name>.csv
  bool loads = true;   ///< loads.csv, when the scenario has loads or springs
};

struct ScenarioFile {
  dynamics::Scenario scenario;
  OutputSelection outputs;
  std::vector<std::string> warnings;  ///< mesh repairs
};

/// @param base_dir directory that relative paths are resolved against
/// @throws InputError naming `source`, the JSON place and what was expected
ScenarioFile scenarioFromJson(const nlohmann::json& j, const std::string& source,
                              const std::string& base_dir);
ScenarioFile readScenarioFile(const std::string& path);

}  // namespace vcontact::formats
