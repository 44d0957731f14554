#pragma once
// Each subcommand registers itself on the application; main() only dispatches.

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <vector>

#include "geometry/error.hpp"

namespace vcontact::cli {

void addVolumeCommand(CLI::App& app);
void addMeshInfoCommand(CLI::App& app);
void addSurfacesCommand(CLI::App& app);
void addMeshRepairCommand(CLI::App& app);
void addTessellateCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);
/// compare, fit, diagnose and synth (validation/, issue #5).
void addValidationCommands(CLI::App& app);
/// friction-map: lumped vs distributed friction over v/(omega R) (issue 4).
void addFrictionMapCommand(CLI::App& app);
/// view: a 3D playback page of a simulation output folder (issue 19).
void addViewCommand(CLI::App& app);
/// study: many runs of a scenario on Dask, by the Python package (docs/STUDY.md, issue 35).
void addStudyCommand(CLI::App& app);

/// Prints warnings to standard error, one per line, prefixed "vcontact: warning: ".
void printWarnings(const std::vector<std::string>& warnings);

/// Returns `run()`. The layers below name the quantity in their errors ("robust loss"); an
/// InputError whose source is a key of `optionOf` is re-thrown with the option that sets it
/// ("--loss"), so that the message names what the user typed.
template <class Run>
auto namingOptions(const std::map<std::string, std::string>& optionOf, Run run) -> decltype(run()) {
  try {
    return run();
  } catch (const InputError& e) {
    const auto it = optionOf.find(e.source());
    if (it == optionOf.end()) throw;
    throw e.withSource(it->second);
  }
}

}  // namespace vcontact::cli
