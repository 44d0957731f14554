// libFuzzer harness: a rig dataset (formats/dataset_file). The bytes before the first NUL are
// the JSON sidecar, the rest the CSV it names (rig.csv): a seed is a sidecar, a NUL and a CSV.

#include <algorithm>

#include "formats/dataset_file.hpp"
#include "fuzz_support.hpp"
#include "geometry/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::uint8_t* end = data + size;
  const std::uint8_t* nul = std::find(data, end, std::uint8_t{0});
  const std::string sidecar =
      vcontact::fuzz::writeInput("rig.json", data, static_cast<std::size_t>(nul - data));
  const std::uint8_t* csv = nul == end ? end : nul + 1;
  vcontact::fuzz::writeInput("rig.csv", csv, static_cast<std::size_t>(end - csv));
  try {
    vcontact::formats::readDataset(sidecar);
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
