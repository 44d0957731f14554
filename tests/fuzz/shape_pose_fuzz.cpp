// libFuzzer harness: the text forms of shapes and poses (io/shape_spec). A text that names no
// primitive would be read as a mesh path; only primitives are parsed, so that the harness
// never opens files of the machine it runs on.

#include <string>

#include "geometry/error.hpp"
#include "io/shape_spec.hpp"

namespace {

bool namesPrimitive(const std::string& text) {
  for (const char* prefix : {"sphere:", "cylinder:", "box:"}) {
    if (text.rfind(prefix, 0) == 0) return true;
  }
  return text == "halfspace";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    vcontact::io::parsePose(text, "pose");
  } catch (const vcontact::InputError&) {
  }
  try {
    if (namesPrimitive(text)) vcontact::io::parseShape(text, "shape");
    vcontact::io::splitMeshScale(text);
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
