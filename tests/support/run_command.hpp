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

/// `command` run by bash with the files it writes limited to `limitKiB` KiB (`ulimit -f`, so
/// a write past it fails with EFBIG); `command` as it is for 0. `command` holds no single quote.
inline std::string withFileSizeLimit(const std::string& command, int limitKiB) {
  if (limitKiB <= 0) return command;
  return "bash -c 'ulimit -f " + std::to_string(limitKiB) + "; exec " + command + "'";
}

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
