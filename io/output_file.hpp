#pragma once
// One way to write a file: whole or not at all. The text goes to a temporary file beside the
// target (same folder, so the final rename is atomic on POSIX file systems); every write and
// the close are checked; only a complete file is renamed onto the target. A failure deletes
// the temporary and throws, naming the target and the system's reason ("No space left on
// device", "File too large"), so a command never reports success over a half-written file.
//
// A target that exists and is neither a regular file nor a folder (a device such as /dev/null
// or /dev/full, a pipe) is written in place, still with every write checked.

#include <deque>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace vcontact::io {

class OutputFile {
 public:
  /// Opens a temporary file beside `path`.
  /// @throws InputError naming `path`: "is a folder", "folder does not exist", or the reason
  ///         the folder refuses a new file (permission, read-only file system)
  explicit OutputFile(std::string path, std::ios::openmode mode = std::ios::out);
  /// Deletes the temporary unless commit() succeeded.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;

  /// The stream to write to; call check() (or commit()) to learn whether the writes held.
  std::ostream& stream() { return out_; }
  /// @throws InputError naming the target when a write so far failed (the temporary is deleted)
  void check();
  /// Flushes and closes the temporary, checking both; the file is then whole but not yet in
  /// place (commit() renames it). Does nothing when already closed.
  /// @throws InputError naming the target when a write or the close failed
  void close();
  /// close(), then renames onto the target.
  /// @throws InputError naming the target when a write, the close or the rename failed
  void commit();
  const std::string& path() const { return path_; }
  /// Whether the target is written in place (a device or pipe): no temporary, no rename.
  bool inPlace() const { return in_place_; }

 private:
  [[noreturn]] void fail(const std::string& what);
  void discard() noexcept;

  std::string path_;  ///< the target
  std::string temp_;  ///< the temporary beside it; empty when writing in place or committed
  std::ofstream out_;
  bool in_place_ = false;
};

/// Several files that belong together (a command's outputs): all appear, or none. Each is an
/// OutputFile; commit() first closes every one, checking its writes, and only when all are
/// whole renames them onto their names. A failure before the renames deletes every temporary
/// and leaves every target as it was. A rename that fails after others succeeded (the folder
/// vanished or changed under the run) deletes the files already renamed, so that no partial
/// set is left, and throws naming the file that failed.
class OutputSet {
 public:
  OutputSet() = default;
  /// A set of files in the folder `dir`, created (with its parents) when missing; a set that
  /// fails removes the folders it created again (those left empty). Temporaries in `dir` of
  /// processes that no longer run (a run killed by SIGKILL) are deleted
  /// (io/output_folder.hpp, removeDeadTemporaries).
  /// @throws InputError naming `dir` when it cannot be created or is a file
  explicit OutputSet(const std::string& dir);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Opens the next file's temporary (OutputFile's constructor and its errors).
  std::ostream& open(const std::string& path, std::ios::openmode mode = std::ios::out);
  /// Writes what `fill` puts on a new file's stream.
  void add(const std::string& path, const std::function<void(std::ostream&)>& fill,
           std::ios::openmode mode = std::ios::out);
  /// @throws InputError naming the first file whose write failed so far; the whole set is
  ///         given up then (every temporary deleted)
  void check();
  /// @throws InputError naming the first file whose write, close or rename failed; nothing of
  ///         the set is left then
  void commit();

 private:
  std::deque<OutputFile> files_;      ///< a deque: the streams open() returned stay where they are
  std::vector<std::string> created_;  ///< folders the constructor made, the deepest last
  bool committed_ = false;
};

/// Writes what `fill` puts on the stream to `path` through an OutputFile.
/// @throws InputError naming `path` on any failure; `path` is then as it was before
void writeFile(const std::string& path, const std::function<void(std::ostream&)>& fill,
               std::ios::openmode mode = std::ios::out);

/// Creates the output folder `dir` and its parents when missing.
/// @throws InputError naming `dir` when it cannot be created or is a file
void makeOutputFolder(const std::string& dir);

/// Size-limited output (RLIMIT_FSIZE) must end in an error message, not in SIGXFSZ killing the
/// process: call once at start-up; writes beyond the limit then fail with EFBIG.
void ignoreFileSizeSignal();

}  // namespace vcontact::io
