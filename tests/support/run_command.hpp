#pragma once
// Runs a command as a user would, capturing its exit code, standard output and standard
// error. Each caller names its own stderr file: CTest runs tests as parallel processes.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace vcontact::test {

struct CommandResult {
  int exitCode = -1;
  std::string out, err;
};

/// `p` in double quotes, as one word of a shell command (the tests' paths hold no '"', '$' or '`').
inline std::string inQuotes(const std::filesystem::path& p) { return '"' + p.string() + '"'; }

inline CommandResult runCommand(const std::string& command, const std::filesystem::path& errFile) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>" + errFile.string()).c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(errFile);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  return r;
}

}  // namespace vcontact::test
