#include "io/output_folder.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <filesystem>

#include "geometry/error.hpp"

namespace vcontact::io {
namespace fs = std::filesystem;

void checkOutputFolder(const std::string& dir) {
  std::error_code ec;
  fs::path p = fs::path(dir).lexically_normal();
  if (p.empty()) p = ".";
  // The nearest part of the path that exists (or that cannot be looked at: its reason).
  for (;;) {
    const fs::file_status s = fs::status(p, ec);
    if (ec && ec != std::errc::no_such_file_or_directory) {
      throw InputError(dir,
                       "cannot be made the output folder: '" + p.string() + "': " + ec.message());
    }
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) {
        throw InputError(dir,
                         p.string() == fs::path(dir).lexically_normal().string()
                             ? "is a file; expected an output folder"
                             : "cannot be made the output folder: '" + p.string() + "' is a file");
      }
      break;
    }
    if (!p.has_parent_path() || p.parent_path() == p) {
      p = ".";
      break;
    }
    p = p.parent_path();
  }
  if (::access(p.c_str(), W_OK | X_OK) != 0) {
    const int err = errno;
    throw InputError(dir, "cannot be made or written as the output folder: '" + p.string() +
                              "': " + std::error_code(err, std::generic_category()).message());
  }
}

void refuseOverwritingInputs(const std::vector<std::string>& outputs,
                             const std::vector<InputFile>& inputs, const std::string& option) {
  for (const std::string& out : outputs) {
    std::error_code ec;
    if (!fs::exists(out, ec)) continue;
    for (const InputFile& in : inputs) {
      if (in.path.empty() || !fs::equivalent(out, in.path, ec)) continue;
      throw InputError(option, "would overwrite " + out + ", which is " + in.role + " (" + in.path +
                                   ") of this command; write to another place");
    }
  }
}

bool isTemporaryName(const std::string& name, long& pid) {
  const auto tmp = name.rfind(".tmp-");
  if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos || tmp < 2) return false;
  const char* first = name.data() + tmp + 5;
  const char* last = name.data() + name.size();
  const auto [dash, e1] = std::from_chars(first, last, pid);
  if (e1 != std::errc() || dash == last || *dash != '-' || pid <= 0) return false;
  long n = 0;
  const auto [end, e2] = std::from_chars(dash + 1, last, n);
  return e2 == std::errc() && end == last && dash + 1 != last;
}

namespace {

// kill(pid, 0) probes without signalling: ESRCH means no such process; EPERM one of another
// user's, which is alive.
bool processRuns(long pid) {
  if (pid == static_cast<long>(::getpid())) return true;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

}  // namespace

std::vector<std::string> removeDeadTemporaries(const std::string& dir) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    long pid = 0;
    if (!isTemporaryName(name, pid) || processRuns(pid)) continue;
    std::error_code rec;
    if (it->is_regular_file(rec) && fs::remove(it->path(), rec)) removed.push_back(name);
  }
  return removed;
}

}  // namespace vcontact::io
