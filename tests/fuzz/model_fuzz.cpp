// libFuzzer harness: a model file (formats/model_file), JSON layer included.

#include "formats/model_file.hpp"
#include "fuzz_support.hpp"
#include "geometry/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = vcontact::fuzz::writeInput("model.json", data, size);
  try {
    vcontact::formats::readModelFile(path);
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
