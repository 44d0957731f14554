#include "io/output_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <utility>

#include "geometry/error.hpp"
#include "io/output_folder.hpp"

namespace vcontact::io {
namespace fs = std::filesystem;
namespace {

// "(No space left on device)" from the errno of the failed call, empty when it left none.
std::string reason(int err) {
  if (err == 0) return "";
  return std::string(" (") + std::strerror(err) + ")";
}

// The folder a new file at `target` goes into ("." for a bare name).
fs::path folderOf(const fs::path& target) {
  const fs::path parent = target.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// ".NAME.tmp-PID-N" in the target's folder: hidden, and unique among this process's writers
// and other processes.
std::string temporaryBeside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name(1, '.');
  name += target.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return (folderOf(target) / name).string();
}

// Whether `path` exists and is a device, pipe or socket: written in place.
bool isSpecialFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status s = fs::status(path, ec);
  return !ec && fs::exists(s) && !fs::is_regular_file(s) && !fs::is_directory(s);
}

}  // namespace

OutputFile::OutputFile(std::string path, std::ios::openmode mode) : path_(std::move(path)) {
  const fs::path target(path_);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw InputError(path_, "is a folder; expected a file path");
  if (isSpecialFile(target)) {
    in_place_ = true;
    errno = 0;
    out_.open(path_, mode | std::ios::out | std::ios::trunc);
    if (!out_) throw InputError(path_, "cannot open for writing" + reason(errno));
    return;
  }
  const fs::path folder = folderOf(target);
  if (!fs::is_directory(folder, ec)) {
    throw InputError(path_, "cannot write: folder '" + folder.string() + "' does not exist");
  }
  temp_ = temporaryBeside(target);
  errno = 0;
  out_.open(temp_, mode | std::ios::out | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    temp_.clear();
    throw InputError(path_,
                     "cannot create a file in folder '" + folder.string() + "'" + reason(err));
  }
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)),
      temp_(std::exchange(other.temp_, std::string())),
      out_(std::move(other.out_)),
      in_place_(other.in_place_) {}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
  if (temp_.empty()) return;
  out_.close();
  std::error_code ec;
  fs::remove(temp_, ec);
  temp_.clear();
}

void OutputFile::fail(const std::string& what) {
  const int err = errno;
  discard();
  throw InputError(path_, what + reason(err));
}

void OutputFile::check() {
  if (!out_) fail("write failed");
}

void OutputFile::close() {
  if (!out_.is_open()) return;
  check();  // a write that failed already: its errno is still the reason
  errno = 0;
  out_.flush();
  check();
  errno = 0;
  out_.close();
  if (out_.fail()) fail("write failed on closing the file");
}

void OutputFile::commit() {
  close();
  if (temp_.empty()) return;  // written in place, or committed already
  std::error_code ec;
  fs::rename(temp_, path_, ec);
  if (ec) {
    errno = ec.value();
    fail("cannot replace the file with the finished temporary");
  }
  temp_.clear();
}

OutputSet::OutputSet(const std::string& dir) {
  std::error_code ec;
  for (fs::path p(dir); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_.insert(created_.begin(), p.string());
    if (p == p.parent_path()) break;
  }
  makeOutputFolder(dir);
  removeDeadTemporaries(dir);  // what a killed run into this folder left (output_folder.hpp)
}

// An uncommitted set (a failure, an exception while its content was built) leaves no folder
// it made; fs::remove takes only empty ones, so a file someone else put there stays.
OutputSet::~OutputSet() {
  if (committed_) return;
  files_.clear();
  std::error_code ec;
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ec);
}

std::ostream& OutputSet::open(const std::string& path, std::ios::openmode mode) {
  files_.emplace_back(path, mode);
  return files_.back().stream();
}

void OutputSet::add(const std::string& path, const std::function<void(std::ostream&)>& fill,
                    std::ios::openmode mode) {
  fill(open(path, mode));
  check();  // a failed write gives up the set now, not after the rest is built
}

void OutputSet::check() {
  for (OutputFile& f : files_) {
    if (f.stream()) continue;
    try {
      f.check();
    } catch (...) {
      files_.clear();
      throw;
    }
  }
}

void OutputSet::commit() {
  try {
    for (OutputFile& f : files_) f.close();
  } catch (...) {
    files_.clear();  // the temporaries go with them
    throw;
  }
  for (std::size_t i = 0; i < files_.size(); ++i) {
    try {
      files_[i].commit();
    } catch (...) {
      std::error_code ec;
      for (std::size_t j = 0; j < i; ++j) {
        if (!files_[j].inPlace()) fs::remove(files_[j].path(), ec);
      }
      files_.clear();
      throw;
    }
  }
  files_.clear();
  committed_ = true;
}

void writeFile(const std::string& path, const std::function<void(std::ostream&)>& fill,
               std::ios::openmode mode) {
  OutputFile file(path, mode);
  fill(file.stream());
  file.commit();
}

void makeOutputFolder(const std::string& dir) {
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  if (fs::exists(dir, ec)) throw InputError(dir, "is a file; expected an output folder");
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the output folder (" + ec.message() + ")");
}

void ignoreFileSizeSignal() { std::signal(SIGXFSZ, SIG_IGN); }

}  // namespace vcontact::io
