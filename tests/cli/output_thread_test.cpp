// `vcontact simulate --output-thread on|off` (report/async_simulation_csv.hpp): the writer
// thread writes what the stepping thread writes, byte for byte, for a complete run, a run that
// stops, and a run whose writes fail (the same message, exit code and leftovers).

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::test::CommandResult;
using vcontact::test::inQuotes;
using vcontact::test::readAll;
using vcontact::test::ScratchDir;

const std::string kBinary = VCONTACT_BINARY;
const std::string kAssets = VCONTACT_ASSETS_DIR;
const char* const kModes[] = {"on", "off"};

// What a run left: each file under the folder `out` (links not followed) and its bytes.
using Files = std::map<std::string, std::string>;

Files filesUnder(const fs::path& out) {
  Files files;
  if (!fs::is_directory(out)) return files;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const std::string name = e.path().lexically_relative(out).string();
    files[name] = e.is_symlink() ? "-> " + fs::read_symlink(e.path()).string() : readAll(e.path());
  }
  return files;
}

// summary.json without the figures that measure the machine (wall time, real-time factor).
nlohmann::json summaryWithoutTimes(const std::string& text) {
  nlohmann::json j = nlohmann::json::parse(text);
  j.erase("wall_time_s");
  j.erase("real_time_factor");
  return j;
}

struct SimulateRun {
  CommandResult result;
  Files files;
};

// `simulate SCENARIO --out DIR/out-MODE --output-thread MODE` in a child whose files may not
// exceed `limitKiB` (0: no limit); `prepare` may put things in the output folder first.
SimulateRun simulate(const std::string& scenario, const fs::path& dir, const std::string& mode,
                     int limitKiB = 0) {
  const fs::path out = dir / ("out-" + mode);
  const std::string command = vcontact::test::withFileSizeLimit(
      inQuotes(kBinary) + " simulate " + inQuotes(scenario) + " --out " + inQuotes(out) +
          " --quiet --output-thread " + mode,
      limitKiB);
  SimulateRun run{vcontact::test::runCommand(command, dir / ("stderr-" + mode + ".txt")), {}};
  run.files = filesUnder(out);
  return run;
}

// The two modes' files are the same, summary.json but for its times; returns the files of
// `on` without summary.json.
Files expectSameFiles(SimulateRun& on, SimulateRun& off) {
  EXPECT_EQ(on.result.exitCode, off.result.exitCode) << on.result.err << off.result.err;
  for (SimulateRun* r : {&on, &off}) {
    if (!r->files.count("summary.json")) continue;
    r->files["summary.json"] = summaryWithoutTimes(r->files["summary.json"]).dump(2);
  }
  EXPECT_EQ(on.files.size(), off.files.size());
  for (const auto& [name, bytes] : off.files) {
    EXPECT_TRUE(on.files.count(name) && on.files[name] == bytes)
        << name << " is missing or differs between the modes";
  }
  Files csvs = on.files;
  csvs.erase("summary.json");
  return csvs;
}

// The lines of `text` whose time (first field) is at most `t`, the header excepted.
long rowsUpTo(const std::string& text, double t) {
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  long n = 0;
  while (std::getline(lines, line)) n += std::stod(line) <= t ? 1 : 0;
  return n;
}

TEST(OutputThread, BallDropFilesAreTheSameInBothModes) {
  const ScratchDir scratch{"output_thread_ball"};
  const std::string scenario = kAssets + "/scenarios/ball_drop.json";
  SimulateRun on = simulate(scenario, scratch.path(), "on"),
              off = simulate(scenario, scratch.path(), "off");
  EXPECT_EQ(on.result.exitCode, 0) << on.result.err;
  const Files csvs = expectSameFiles(on, off);
  EXPECT_EQ(csvs.size(), 2u);                                // bodies.csv, pair_ball-plate.csv
  EXPECT_EQ(rowsUpTo(csvs.at("bodies.csv"), 1.0), 2 * 601);  // 2 bodies, 0.3 s at 2 kHz
}

// A mesh pair with contact patches and a load: bodies.csv, loads.csv, the pair's file and its
// patch file.
TEST(OutputThread, PegInsertionFilesAreTheSameInBothModes) {
  const ScratchDir scratch{"output_thread_peg"};
  const std::string scenario = kAssets + "/scenarios/peg_insertion.json";
  SimulateRun on = simulate(scenario, scratch.path(), "on"),
              off = simulate(scenario, scratch.path(), "off");
  EXPECT_EQ(on.result.exitCode, 0) << on.result.err;
  const Files csvs = expectSameFiles(on, off);
  ASSERT_EQ(csvs.size(), 4u);
  EXPECT_EQ(rowsUpTo(csvs.at("loads.csv"), 1.0), 121);  // 0.12 s at 1 kHz
  // the peg touches the chamfer at about 10 ms and stays in contact: a patch row per output
  EXPECT_GT(rowsUpTo(csvs.at("pair_peg-block_patches.csv"), 1.0), 90);
}

// kv = 1e3 N/m³ cannot hold the 32 g ball: the run stops (exit 3) once it sinks beyond a tenth
// of its size, and keeps its rows up to then, the same in both modes.
TEST(OutputThread, AStoppedRunKeepsTheSameRowsInBothModes) {
  const ScratchDir scratch{"output_thread_stop"};
  const fs::path scenario = scratch / "s.json";
  std::ofstream(scenario) << R"({"format": "vcontact.scenario/1", "duration": 0.05,
    "output_rate": 1000,
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.0105"}],
    "pairs": [{"a": "ball", "b": "plate", "method": "analytic",
               "model": {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e3}}}}]})";
  SimulateRun on = simulate(scenario.string(), scratch.path(), "on");
  SimulateRun off = simulate(scenario.string(), scratch.path(), "off");
  EXPECT_EQ(on.result.exitCode, 3) << on.result.err;
  const Files csvs = expectSameFiles(on, off);
  EXPECT_EQ(summaryWithoutTimes(readAll(scratch / "out-on" / "summary.json")).at("stop_cause"),
            "penetration_beyond_bound");
  // the ball touches at sqrt(2 · 0.5 mm / g) = 10.1 ms: rows at 1 kHz until then at least
  EXPECT_GE(rowsUpTo(csvs.at("bodies.csv"), 1.0), 2 * 11);
}

// The standard error line that carries the error, from "vcontact: error:".
std::string errorLine(const std::string& err) {
  const std::size_t at = err.find("vcontact: error:");
  if (at == std::string::npos) return "";
  return err.substr(at, err.find('\n', at) - at);
}

// The error line with the mode's folder name put back to "out-MODE".
std::string neutral(std::string line, const std::string& mode) {
  const std::string folder = "out-" + mode;
  for (std::size_t at; (at = line.find(folder)) != std::string::npos;)
    line.replace(at, folder.size(), "out-MODE");
  return line;
}

// Writes beyond 16 KiB fail (RLIMIT_FSIZE, EFBIG): in the middle of bodies.csv (~150 KiB), on
// the writer thread with `on`. Exit 2, the same message, nothing left, in both modes.
TEST(OutputThread, AFileSizeLimitFailsTheSameInBothModes) {
  const ScratchDir scratch{"output_thread_fsize"};
  const std::string scenario = kAssets + "/scenarios/ball_drop.json";
  std::vector<std::string> lines;
  for (const char* mode : kModes) {
    const SimulateRun run = simulate(scenario, scratch.path(), mode, 16);
    EXPECT_EQ(run.result.exitCode, 2) << run.result.err;
    EXPECT_TRUE(run.files.empty());
    lines.push_back(neutral(errorLine(run.result.err), mode));
  }
  EXPECT_NE(lines[0].find("File too large"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[0], lines[1]);
}

// pair_ball-plate.csv is a link to /dev/full (ENOSPC at its first flush, mid-run): the link
// alone is left.
TEST(OutputThread, AFullDiskFailsTheSameInBothModes) {
  const ScratchDir scratch{"output_thread_full"};
  const std::string scenario = kAssets + "/scenarios/ball_drop.json";
  std::vector<std::string> lines;
  for (const char* mode : kModes) {
    const fs::path out = scratch / ("out-" + std::string(mode));
    fs::create_directories(out);
    fs::create_symlink("/dev/full", out / "pair_ball-plate.csv");
    const SimulateRun run = simulate(scenario, scratch.path(), mode);
    EXPECT_EQ(run.result.exitCode, 2) << run.result.err;
    EXPECT_EQ(run.files, (Files{{"pair_ball-plate.csv", "-> /dev/full"}}));
    lines.push_back(neutral(errorLine(run.result.err), mode));
  }
  EXPECT_EQ(lines[0], "vcontact: error: " + (scratch / "out-MODE").string() +
                          "/pair_ball-plate.csv: write failed (No space left on device)");
  EXPECT_EQ(lines[0], lines[1]);
}

// An output folder that is a file: the writer thread's set-up fails, reported as the
// synchronous constructor reports it.
TEST(OutputThread, AnOutputFolderThatIsAFileFailsTheSameInBothModes) {
  const ScratchDir scratch{"output_thread_file"};
  const std::string scenario = kAssets + "/scenarios/ball_drop.json";
  std::vector<std::string> lines;
  for (const char* mode : kModes) {
    std::ofstream(scratch / ("out-" + std::string(mode))) << "not a folder\n";
    const SimulateRun run = simulate(scenario, scratch.path(), mode);
    EXPECT_EQ(run.result.exitCode, 2) << run.result.err;
    lines.push_back(neutral(errorLine(run.result.err), mode));
  }
  EXPECT_NE(lines[0].find("is a file; expected an output folder"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[0], lines[1]);
}

TEST(OutputThread, AnUnknownModeIsRefused) {
  const ScratchDir scratch{"output_thread_bad"};
  const SimulateRun run = simulate(kAssets + "/scenarios/ball_drop.json", scratch.path(), "maybe");
  EXPECT_EQ(run.result.exitCode, 2) << run.result.err;
  EXPECT_NE(run.result.err.find("--output-thread"), std::string::npos) << run.result.err;
  EXPECT_TRUE(run.files.empty());
}

}  // namespace
