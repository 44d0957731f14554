// Every command that writes several files writes all of them or none (io::OutputSet, README
// "Exit codes and output"). Two failures per command: the first file it writes exceeds a
// size limit (RLIMIT_FSIZE, set by the shell in the child), and the last file it writes is a
// link to /dev/full, so that every file before it was written whole when the set fails. Each
// must exit 2 naming the file and the system's reason, and leave no file of the set behind.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::test::CommandResult;
using vcontact::test::inQuotes;
using vcontact::test::ScratchDir;

const std::string kBinary = VCONTACT_BINARY;
const std::string kAssets = VCONTACT_ASSETS_DIR;

// `args` run in a child whose files may not exceed `limitKiB` (0: no limit).
CommandResult vcontact(const std::string& args, const fs::path& dir, int limitKiB = 0) {
  // the arguments use double quotes only, as withFileSizeLimit needs
  return vcontact::test::runCommand(
      vcontact::test::withFileSizeLimit(inQuotes(kBinary) + " " + args, limitKiB),
      dir / "stderr.txt");
}

// Every file under `dir` but the test's own (stderr.txt, the inputs named in `keep`).
std::vector<std::string> leftovers(const fs::path& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().lexically_relative(dir).string();  // links not followed
    if (name == "stderr.txt" || std::count(keep.begin(), keep.end(), name)) continue;
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void expectRefused(const CommandResult& r, const std::string& file, const std::string& why) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("vcontact: error: " + file + ": write failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
}

constexpr const char* kNoSpace = "No space left on device";  // ENOSPC, /dev/full
constexpr const char* kTooLarge = "File too large";          // EFBIG, RLIMIT_FSIZE
// 16 KiB: less than the first file of each command below (a 1200-row residuals.csv is
// ~100 KiB, a 2000-sample dataset CSV ~500 KiB, a ball-drop bodies.csv ~150 KiB, the δ map of
// the 10 mm ball's mesh 0.5 mm deep ~270 KiB), far more than nothing
constexpr int kLimitKiB = 16;

// A dataset of the repository (1200 samples) and the model that made it; one Ceres iteration
// and no extra starts keep fit and diagnose to a second or two.
std::string validationArgs(const std::string& command, const fs::path& out) {
  std::string args = command + " " + inQuotes(kAssets + "/datasets/loading.json") + " --model " +
                     inQuotes(kAssets + "/datasets/models/loading-truth.model.json") + " --out " +
                     inQuotes(out);
  if (command != "compare") args += " --starts 0 --max-iterations 1";
  return args;
}

struct ValidationCase {
  const char* command;
  const char* first;  ///< the file it writes first
  const char* last;   ///< the file it writes last
};

const ValidationCase kValidation[] = {{"compare", "residuals.csv", "report.html"},
                                      {"fit", "model.json", "report.html"},
                                      {"diagnose", "diagnosis.json", "report.html"}};

TEST(AllOrNothing, ValidationCommandsLeaveNoFileWhenTheFirstExceedsTheSizeLimit) {
  for (const ValidationCase& c : kValidation) {
    SCOPED_TRACE(c.command);
    const ScratchDir scratch{"aon_limit_" + std::string(c.command)};
    const fs::path& dir = scratch.path();
    const fs::path out = dir / "out";
    const CommandResult r = vcontact(validationArgs(c.command, out), dir, kLimitKiB);
    // the first file past 16 KiB fails: for compare its first, for fit and diagnose the
    // residuals (their JSON files are smaller); none is left, nor the folder the run made
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("vcontact: error: " + out.string() + "/"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(kTooLarge), std::string::npos) << r.err;
    EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
  }
}

TEST(AllOrNothing, ValidationCommandsLeaveNoFileWhenTheLastCannotBeWritten) {
  for (const ValidationCase& c : kValidation) {
    SCOPED_TRACE(c.command);
    const ScratchDir scratch{"aon_full_" + std::string(c.command)};
    const fs::path& dir = scratch.path();
    const fs::path out = dir / "out";
    fs::create_directories(out);
    fs::create_symlink("/dev/full", out / c.last);
    const CommandResult r = vcontact(validationArgs(c.command, out), dir);
    expectRefused(r, (out / c.last).string(), kNoSpace);
    EXPECT_FALSE(fs::exists(out / c.first));
    EXPECT_EQ(leftovers(dir, {}), (std::vector<std::string>{"out", "out/" + std::string(c.last)}));
  }
}

std::string synthArgs(const fs::path& sidecar) {
  return "synth --profile loading --samples 2000 --model " +
         inQuotes(kAssets + "/datasets/models/loading-truth.model.json") + " --out " +
         inQuotes(sidecar);
}

// synth writes NAME.csv, then NAME.json (the sidecar naming it).
TEST(AllOrNothing, SynthLeavesNeitherFileWhenTheTableExceedsTheSizeLimit) {
  const ScratchDir scratch{"aon_synth_limit"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact(synthArgs(dir / "d.json"), dir, kLimitKiB);
  expectRefused(r, (dir / "d.csv").string(), kTooLarge);
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

TEST(AllOrNothing, SynthLeavesNoTableWhenTheSidecarCannotBeWritten) {
  const ScratchDir scratch{"aon_synth_full"};
  const fs::path& dir = scratch.path();
  fs::create_symlink("/dev/full", dir / "d.json");
  const CommandResult r = vcontact(synthArgs(dir / "d.json"), dir);
  expectRefused(r, (dir / "d.json").string(), kNoSpace);
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{"d.json"});
}

// volume --field F --out J: the δ map first, then the JSON.
std::string volumeArgs(const fs::path& field, const std::string& json) {
  return "volume " + inQuotes(kAssets + "/meshes/ball_r10mm.stl") +
         " halfspace --pose-a 0,0,0.0095 --method columns --field " + inQuotes(field) + " --out " +
         json;
}

TEST(AllOrNothing, VolumeLeavesNoDepthMapWhenTheJsonCannotBeWritten) {
  const ScratchDir scratch{"aon_volume_full"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact(volumeArgs(dir / "field.csv", "/dev/full"), dir);
  expectRefused(r, "/dev/full", kNoSpace);
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

TEST(AllOrNothing, VolumeLeavesNoJsonWhenTheDepthMapExceedsTheSizeLimit) {
  const ScratchDir scratch{"aon_volume_limit"};
  const fs::path& dir = scratch.path();
  const CommandResult r =
      vcontact(volumeArgs(dir / "field.csv", inQuotes(dir / "v.json")), dir, kLimitKiB);
  expectRefused(r, (dir / "field.csv").string(), kTooLarge);
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

// simulate commits its CSVs with summary.json: a summary that cannot be written takes them.
TEST(AllOrNothing, SimulateLeavesNoCsvWhenTheSummaryCannotBeWritten) {
  const ScratchDir scratch{"aon_simulate_full"};
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::create_symlink("/dev/full", out / "summary.json");
  const CommandResult r = vcontact(
      "simulate " + inQuotes(kAssets + "/scenarios/ball_drop.json") + " --out " + inQuotes(out),
      dir);
  expectRefused(r, (out / "summary.json").string(), kNoSpace);
  EXPECT_EQ(leftovers(dir, {}), (std::vector<std::string>{"out", "out/summary.json"}));
}

// The folder a failed run created is removed again; one that was there stays.
TEST(AllOrNothing, FailedSimulationRemovesTheOutputFolderItCreated) {
  const ScratchDir scratch{"aon_simulate_folder"};
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "new" / "out";
  const CommandResult r = vcontact(
      "simulate " + inQuotes(kAssets + "/scenarios/ball_drop.json") + " --out " + inQuotes(out),
      dir, kLimitKiB);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(kTooLarge), std::string::npos) << r.err;
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

}  // namespace
