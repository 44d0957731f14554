// io::OutputFile: a file appears whole under its name or not at all.

#include "io/output_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/error.hpp"
#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::InputError;
using vcontact::io::OutputFile;
using vcontact::test::readAll;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("vcontact_output_file_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
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

// ---- OutputSet: a command's files appear together or not at all ----------------------------

TEST(OutputSet, EveryFileAppearsOnCommitAndNoneBefore) {
  const fs::path dir = scratch("set");
  vcontact::io::OutputSet set;
  set.open((dir / "a.txt").string()) << "a\n";
  set.add((dir / "b.txt").string(), [](std::ostream& out) { out << "b\n"; });
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  EXPECT_FALSE(fs::exists(dir / "b.txt"));
  set.commit();
  EXPECT_EQ(readAll(dir / "a.txt"), "a\n");
  EXPECT_EQ(readAll(dir / "b.txt"), "b\n");
  EXPECT_EQ(entries(dir), 2u);
  fs::remove_all(dir);
}

// /dev/full takes the open and fails the flush on closing (ENOSPC): the files before and after
// it in the set are given up too, and a.txt keeps its earlier content.
TEST(OutputSet, OneFailedFileGivesUpTheWholeSet) {
  const fs::path dir = scratch("set_fail");
  std::ofstream(dir / "a.txt") << "before";
  vcontact::io::OutputSet set;
  set.open((dir / "a.txt").string()) << "new a\n";
  set.open("/dev/full") << "x\n";
  set.open((dir / "b.txt").string()) << "b\n";
  const std::string message = errorOf([&] { set.commit(); });
  EXPECT_EQ(message.rfind("/dev/full: write failed", 0), 0u) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  EXPECT_EQ(readAll(dir / "a.txt"), "before");
  EXPECT_FALSE(fs::exists(dir / "b.txt"));
  EXPECT_EQ(entries(dir), 1u);  // a.txt only: no temporary left
  fs::remove_all(dir);
}

// A rename that fails after an earlier one succeeded (b.txt became a non-empty folder while
// the set was written): a.txt, already in place, is removed so that no partial set remains.
TEST(OutputSet, FailedRenameRemovesTheFilesAlreadyRenamed) {
  const fs::path dir = scratch("set_rename");
  vcontact::io::OutputSet set;
  set.open((dir / "a.txt").string()) << "a\n";
  set.open((dir / "b.txt").string()) << "b\n";
  fs::create_directories(dir / "b.txt" / "inside");
  const std::string message = errorOf([&] { set.commit(); });
  EXPECT_EQ(message.rfind((dir / "b.txt").string() + ": cannot replace the file", 0), 0u)
      << message;
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  EXPECT_EQ(entries(dir), 1u);  // the folder b.txt only
  fs::remove_all(dir);
}

}  // namespace
