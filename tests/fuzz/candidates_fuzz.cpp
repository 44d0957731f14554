// libFuzzer harness: a candidates file (formats/candidates_file), JSON layer and expression
// entries included; every candidate read is then created, as diagnose does.

#include "formats/candidates_file.hpp"
#include "fuzz_support.hpp"
#include "geometry/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = vcontact::fuzz::writeInput("candidates.json", data, size);
  try {
    const vcontact::validation::CandidateSet set = vcontact::formats::readCandidatesFile(path);
    for (const std::string& id : set.ids()) set.create(id);
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
