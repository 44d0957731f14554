// libFuzzer harness: io::readMesh on any bytes, as STL, OBJ, OFF or PLY (the first byte picks
// the extension, the rest is the file). Bad input must end in InputError; any other exception,
// a crash, a leak or undefined behaviour is a finding.

#include <array>

#include "fuzz_support.hpp"
#include "geometry/error.hpp"
#include "io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::array<const char*, 4> kNames = {"part.stl", "part.obj", "part.off", "part.ply"};
  const std::string path = vcontact::fuzz::writeInput(kNames[data[0] % 4], data + 1, size - 1);
  try {
    vcontact::io::readMesh(path);
  } catch (const vcontact::InputError&) {
    // the expected answer to a bad file
  }
  return 0;
}
