#include "io/json_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/error.hpp"

namespace vcontact::io {

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw InputError(path, std::filesystem::exists(path) ? "cannot be read" : "no such file");
  }
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    std::ostringstream os;
    os << "not valid JSON (byte " << e.byte << "): " << e.what();
    throw InputError(path, os.str());
  }
}

void writeJson(const nlohmann::json& j, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot open for writing");
  out << j.dump(2) << '\n';
}

}  // namespace vcontact::io
