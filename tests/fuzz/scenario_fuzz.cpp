// libFuzzer harness: a scenario file (formats/scenario_file) read as the simulate command
// reads it, JSON layer included. Meshes it names resolve in the scratch folder (none exist).

#include "formats/scenario_file.hpp"
#include "fuzz_support.hpp"
#include "geometry/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = vcontact::fuzz::writeInput("scene.json", data, size);
  try {
    vcontact::formats::readScenarioFile(path);
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
