// vcontact: volumetric contact engine, command-line front end.

#include <iostream>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "io/output_file.hpp"

namespace {

constexpr int kBadInputExitCode = 2;  // simulate_command.cpp uses 3 for a stopped run

/// A command line CLI11 cannot parse (a value of the wrong type or out of a set, a missing or
/// extra argument, a missing subcommand) is bad input like any other: exit 2, not CLI11's
/// 104-114. Help, version and a subcommand's own exit code pass through.
int exitCode(const CLI::App& app, const CLI::ParseError& e) {
  using CLI::ExitCodes;
  const int code = app.exit(e);
  switch (static_cast<ExitCodes>(code)) {
    case ExitCodes::ConversionError:
    case ExitCodes::ValidationError:
    case ExitCodes::RequiredError:
    case ExitCodes::RequiresError:
    case ExitCodes::ExcludesError:
    case ExitCodes::ExtrasError:
    case ExitCodes::ArgumentMismatch:
      return kBadInputExitCode;
    default:
      return code;
  }
}

/// A first word that is no command (a typo such as "simulat") gets CLI11's "A subcommand is
/// required", which does not name it; this names it and the commands there are.
bool unknownCommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string word = argv[1];
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == word) return false;
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  std::cerr << "vcontact: error: '" << word << "' is not a command; expected one of: " << names
            << "\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  vcontact::io::ignoreFileSizeSignal();
  CLI::App app{
      "vcontact: volumetric contact between rigid bodies (Gonthier-McPhee model).\n"
      "Shapes: sphere:R | cylinder:R,L | box:X,Y,Z | halfspace | MESHFILE[@SCALE] (metres;\n"
      "SCALE a number or m, cm, mm, um, in, ft).\n"
      "Poses: x,y,z | x,y,z,roll,pitch,yaw (degrees) | x,y,z,qw,qx,qy,qz."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vcontact 0.1.0");
  vcontact::cli::addVolumeCommand(app);
  vcontact::cli::addMeshInfoCommand(app);
  vcontact::cli::addSurfacesCommand(app);
  vcontact::cli::addMeshRepairCommand(app);
  vcontact::cli::addTessellateCommand(app);
  vcontact::cli::addSimulateCommand(app);
  vcontact::cli::addValidationCommands(app);
  vcontact::cli::addFrictionMapCommand(app);
  vcontact::cli::addViewCommand(app);
  vcontact::cli::addStudyCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (unknownCommand(app, argc, argv)) return kBadInputExitCode;
    return exitCode(app, e);
  } catch (const vcontact::InputError& e) {
    std::cerr << "vcontact: error: " << e.what() << '\n';
    return kBadInputExitCode;
  } catch (const std::exception& e) {
    std::cerr << "vcontact: internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
