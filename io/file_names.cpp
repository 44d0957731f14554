#include "io/file_names.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace vcontact::io {

std::string fileSafe(const std::string& name) {
  std::string s = name;
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return s;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool hasExtension(const std::string& path, const std::string& ext) {
  return lowerExtension(path) == ext;
}

}  // namespace vcontact::io
