// io::OutputFile: a file appears whole under its name or not at all.

#include "io/output_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/error.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::InputError;
using vcontact::io::OutputFile;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("vcontact_output_file_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readAll(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), {}));
}

// The message of the InputError `f` throws, or "" (and a failure) when it throws none.
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(OutputFile, NothingUnderTheNameUntilCommitted) {
  const fs::path dir = scratch("commit");
  const fs::path path = dir / "a.txt";
  OutputFile f(path.string());
  f.stream() << "hello\n";
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(entries(dir), 1u);  // the temporary
  f.commit();
  EXPECT_EQ(readAll(path), "hello\n");
  EXPECT_EQ(entries(dir), 1u);  // the file, no temporary left
  fs::remove_all(dir);
}

TEST(OutputFile, AbandonedFileLeavesNothingAndKeepsThePreviousContent) {
  const fs::path dir = scratch("abandon");
  const fs::path path = dir / "a.txt";
  std::ofstream(path) << "before";
  {
    OutputFile f(path.string());
    f.stream() << "half";
  }
  EXPECT_EQ(readAll(path), "before");
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}

TEST(OutputFile, WriteFileReplacesTheFileWhole) {
  const fs::path dir = scratch("replace");
  const fs::path path = dir / "a.txt";
  std::ofstream(path) << "before";
  vcontact::io::writeFile(path.string(), [](std::ostream& o) { o << "after"; });
  EXPECT_EQ(readAll(path), "after");
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}

// /dev/full is written in place (a device), and the failure is found at the latest on commit.
TEST(OutputFile, DevFullFailsWithTheReason) {
  const std::string message = errorOf([] {
    OutputFile f("/dev/full");
    f.stream() << "x";
    f.commit();
  });
  EXPECT_EQ(message, "/dev/full: write failed (No space left on device)");
}

TEST(OutputFile, DevNullIsWrittenInPlace) {
  OutputFile f("/dev/null");
  f.stream() << "x";
  EXPECT_NO_THROW(f.commit());
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(OutputFile, FolderAsTargetIsRefused) {
  const fs::path dir = scratch("folder");
  EXPECT_EQ(errorOf([&] { OutputFile f(dir.string()); }),
            dir.string() + ": is a folder; expected a file path");
  fs::remove_all(dir);
}

TEST(OutputFile, MissingFolderIsRefused) {
  const fs::path dir = scratch("missing");
  const fs::path path = dir / "no" / "a.txt";
  EXPECT_EQ(
      errorOf([&] { OutputFile f(path.string()); }),
      path.string() + ": cannot write: folder '" + (dir / "no").string() + "' does not exist");
  fs::remove_all(dir);
}

TEST(OutputFile, OutputFolderThatIsAFileIsRefused) {
  const fs::path dir = scratch("notfolder");
  std::ofstream(dir / "f") << "x";
  EXPECT_EQ(errorOf([&] { vcontact::io::makeOutputFolder((dir / "f").string()); }),
            (dir / "f").string() + ": is a file; expected an output folder");
  EXPECT_EQ(errorOf([&] {
              vcontact::io::makeOutputFolder((dir / "f" / "sub").string());
            }).rfind((dir / "f" / "sub").string() + ": cannot create the output folder (", 0),
            0u);
  fs::remove_all(dir);
}

}  // namespace
