// vcontact: volumetric contact engine, command-line front end.

#include <iostream>

#include "cli/commands.hpp"
#include "geometry/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "vcontact: volumetric contact between rigid bodies (Gonthier-McPhee model).\n"
      "Shapes: sphere:R | cylinder:R,L | box:X,Y,Z | halfspace | MESHFILE[@SCALE] (metres).\n"
      "Poses: x,y,z | x,y,z,roll,pitch,yaw (degrees) | x,y,z,qw,qx,qy,qz."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vcontact 0.1.0");
  vcontact::cli::addVolumeCommand(app);
  vcontact::cli::addMeshInfoCommand(app);
  vcontact::cli::addTessellateCommand(app);
  vcontact::cli::addSimulateCommand(app);
  vcontact::cli::addValidationCommands(app);
  vcontact::cli::addFrictionMapCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const vcontact::InputError& e) {
    std::cerr << "vcontact: error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "vcontact: internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
