#pragma once
// Each subcommand registers itself on the application; main() only dispatches.

#include <CLI/CLI.hpp>

namespace vcontact::cli {

void addVolumeCommand(CLI::App& app);
void addMeshInfoCommand(CLI::App& app);
void addTessellateCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);
/// compare, fit, diagnose and synth (validation/, issue #5).
void addValidationCommands(CLI::App& app);
/// friction-map: lumped vs distributed friction over v/(omega R) (issue 4).
void addFrictionMapCommand(CLI::App& app);

/// Prints warnings to standard error, one per line, prefixed "vcontact: warning: ".
void printWarnings(const std::vector<std::string>& warnings);

}  // namespace vcontact::cli
