#pragma once
// What every harness shares: the fuzzer's bytes as a file in a private folder, since the
// readers take paths (as the command line does).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace vcontact::fuzz {

/// A folder of this process, made once and reused for every input.
inline const std::filesystem::path& scratchFolder() {
  static const std::filesystem::path folder = [] {
    auto p = std::filesystem::temp_directory_path() /
             ("vcontact-fuzz-" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(p);
    return p;
  }();
  return folder;
}

/// Writes the bytes to `name` in the scratch folder and returns its path.
inline std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = (scratchFolder() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace vcontact::fuzz
