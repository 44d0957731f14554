// io/output_folder.hpp: the output folder checked before any work, inputs never overwritten,
// and the temporaries of dead processes (only those) cleaned.

#include "io/output_folder.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "geometry/error.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_support.hpp"

namespace vcontact::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::ScratchDir;

TEST(OutputFolder, TemporaryNamesAreThoseOfOutputFile) {
  long pid = 0;
  EXPECT_TRUE(isTemporaryName(".bodies.csv.tmp-1234-0", pid));
  EXPECT_EQ(pid, 1234);
  EXPECT_TRUE(isTemporaryName(".pair_a.tmp-b.csv.tmp-77-12", pid));  // the last ".tmp-" counts
  EXPECT_EQ(pid, 77);
  for (const char* name : {"bodies.csv.tmp-1234-0", ".bodies.csv.tmp-1234", ".x.tmp--1-0",
                           ".x.tmp-12-", ".x.tmp-12-3a", ".x.tmp-a-1", ".tmp-1-1", ".x.tmp-0-1"}) {
    EXPECT_FALSE(isTemporaryName(name, pid)) << name;
  }
}

TEST(OutputFolder, OnlyTemporariesOfDeadProcessesAreRemoved) {
  const ScratchDir scratch{"output_folder_temps"};
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);
  const std::string dead = ".a.csv.tmp-" + std::to_string(child) + "-0";
  const std::string live = ".a.csv.tmp-" + std::to_string(::getpid()) + "-0";
  const std::string init = ".a.csv.tmp-1-0";  // PID 1 always runs
  for (const std::string& name : {dead, live, init, std::string("a.csv")}) {
    std::ofstream(scratch / name) << "x";
  }
  EXPECT_EQ(removeDeadTemporaries(scratch.path().string()), std::vector<std::string>{dead});
  EXPECT_TRUE(fs::exists(scratch / live));
  EXPECT_TRUE(fs::exists(scratch / init));
  EXPECT_TRUE(fs::exists(scratch / "a.csv"));
}

TEST(OutputFolder, AnInputIsNeverAnOutput) {
  const ScratchDir scratch{"output_folder_inputs"};
  std::ofstream(scratch / "data.csv") << "t\n";
  fs::create_symlink(scratch / "data.csv", scratch / "link.csv");
  const std::string msg = inputErrorMessage([&] {
    refuseOverwritingInputs({(scratch / "out.csv").string(), (scratch / "link.csv").string()},
                            {{(scratch / "data.csv").string(), "the data"}}, "--out");
  });
  EXPECT_EQ(msg, "--out: would overwrite " + (scratch / "link.csv").string() +
                     ", which is the data (" + (scratch / "data.csv").string() +
                     ") of this command; write to another place");
  EXPECT_NO_THROW(refuseOverwritingInputs({(scratch / "other.csv").string()},
                                          {{(scratch / "data.csv").string(), "the data"}, {"", ""}},
                                          "--out"));
}

// Paths that fail for root too: through a regular file (ENOTDIR), through a link loop (ELOOP).
TEST(OutputFolder, AFolderThatCannotBeMadeIsNamedWithTheReason) {
  const ScratchDir scratch{"output_folder_check"};
  std::ofstream(scratch / "file") << "x";
  fs::create_symlink(scratch / "loop", scratch / "loop");
  const std::string through = (scratch / "file" / "sub").string();
  EXPECT_EQ(inputErrorMessage([&] { checkOutputFolder(through); }),
            through + ": cannot be made the output folder: '" + through + "': Not a directory");
  const std::string looped = (scratch / "loop" / "a" / "b").string();
  EXPECT_NE(inputErrorMessage([&] {
              checkOutputFolder(looped);
            }).find("Too many levels of symbolic links"),
            std::string::npos);
  const std::string file = (scratch / "file").string();
  EXPECT_EQ(inputErrorMessage([&] { checkOutputFolder(file); }),
            file + ": is a file; expected an output folder");
  EXPECT_NO_THROW(checkOutputFolder((scratch / "new" / "deeper").string()));
  EXPECT_NO_THROW(checkOutputFolder(scratch.path().string()));
  EXPECT_FALSE(fs::exists(scratch / "new"));  // checked, not made
}

}  // namespace
}  // namespace vcontact::io
