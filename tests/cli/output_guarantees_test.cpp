// What the commands promise about their output (README "Exit codes and output"): a failed
// write exits 2 naming the file and leaves nothing behind; a refused resource exits 2 with
// the number before anything is written; a stopped simulation exits 3 and keeps complete,
// parseable CSVs up to the stop, its summary saying where and why.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

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

CommandResult vcontact(const std::string& args, const fs::path& dir) {
  return vcontact::test::runCommand('"' + kBinary + "\" " + args, dir / "stderr.txt");
}

// The names in `dir`, but the test's own stderr.txt and inputs (*.json given as `keep`).
std::vector<std::string> leftovers(const fs::path& dir, const std::vector<std::string>& keep) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "stderr.txt" || std::count(keep.begin(), keep.end(), name)) continue;
    if (e.is_directory()) continue;
    names.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void expectBadOutput(const CommandResult& r, const std::string& file, const std::string& why) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("vcontact: error: " + file + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
}

// ---- failed writes -------------------------------------------------------------------------

// /dev/full accepts the open and fails every write with ENOSPC: the full-disk case.
TEST(OutputGuarantees, WriteToDevFullExitsTwoNamingTheFile) {
  const ScratchDir scratch{"output_devfull"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact("tessellate sphere:0.01 --out /dev/full", dir);
  expectBadOutput(r, "/dev/full", "No space left on device");
  EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
}

// RLIMIT_FSIZE set by the shell in the child before exec (ulimit -f counts 1024-byte blocks):
// writes past 16 KiB fail with EFBIG instead of killing the process with SIGXFSZ. The ball
// drop writes ~150 KiB of bodies.csv, so the run fails while writing; nothing is left.
TEST(OutputGuarantees, SizeLimitedSimulationExitsTwoAndLeavesNoFiles) {
  const ScratchDir scratch{"output_fsize"};
  const fs::path& dir = scratch.path();
  const std::string command = vcontact::test::withFileSizeLimit(
      inQuotes(kBinary) + " simulate " + inQuotes(kAssets + "/scenarios/ball_drop.json") +
          " --out " + inQuotes(dir / "out"),
      16);
  const CommandResult r = vcontact::test::runCommand(command, dir / "stderr.txt");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir / "out").string() + "/"), std::string::npos) << r.err;
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

// The same limit on a single-file writer (a 64-segment sphere is 200 KiB of STL).
TEST(OutputGuarantees, SizeLimitedMeshWriteLeavesNoFile) {
  const ScratchDir scratch{"output_fsize_mesh"};
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "ball.stl";
  const std::string command = vcontact::test::withFileSizeLimit(
      inQuotes(kBinary) + " tessellate sphere:0.01 --out " + inQuotes(out), 16);
  const CommandResult r = vcontact::test::runCommand(command, dir / "stderr.txt");
  expectBadOutput(r, out.string(), "File too large");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

// A failed write replaces nothing: the file that was there stays as it was.
TEST(OutputGuarantees, FailedWriteKeepsThePreviousFile) {
  const ScratchDir scratch{"output_keep"};
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "ball.stl";
  std::ofstream(out) << "previous";
  const std::string command = vcontact::test::withFileSizeLimit(
      inQuotes(kBinary) + " tessellate sphere:0.01 --out " + inQuotes(out), 16);
  const CommandResult r = vcontact::test::runCommand(command, dir / "stderr.txt");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(readAll(out), "previous");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{"ball.stl"});
}

// A folder that refuses new files. Permission bits do not stop root (the CI container runs as
// root), so /proc stands for it: no regular file can be created there by anyone.
TEST(OutputGuarantees, UnwritableFolderExitsTwoNamingTheFile) {
  const ScratchDir scratch{"output_unwritable"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact("tessellate sphere:0.01 --out /proc/vcontact-test.stl", dir);
  expectBadOutput(r, "/proc/vcontact-test.stl", "cannot create a file in folder '/proc'");
  EXPECT_FALSE(fs::exists("/proc/vcontact-test.stl"));
}

// The same through permission bits, where they apply (not as root).
TEST(OutputGuarantees, ReadOnlyFolderExitsTwoWhenNotRoot) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores permission bits";
  const ScratchDir scratch{"output_readonly"};
  const fs::path& dir = scratch.path();
  fs::create_directories(dir / "ro");
  fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const CommandResult r =
      vcontact("tessellate sphere:0.01 --out " + inQuotes(dir / "ro" / "b.stl"), dir);
  expectBadOutput(r, (dir / "ro" / "b.stl").string(), "Permission denied");
  fs::permissions(dir / "ro", fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(dir / "ro"));
}

TEST(OutputGuarantees, MissingFolderExitsTwo) {
  const ScratchDir scratch{"output_missing"};
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "no" / "such" / "b.stl";
  const CommandResult r = vcontact("tessellate sphere:0.01 --out " + inQuotes(out), dir);
  expectBadOutput(r, out.string(), "does not exist");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

TEST(OutputGuarantees, OutputPathThatIsAFolderExitsTwo) {
  const ScratchDir scratch{"output_folder"};
  const fs::path& dir = scratch.path();
  fs::create_directories(dir / "b.stl");
  const CommandResult r = vcontact("tessellate sphere:0.01 --out " + inQuotes(dir / "b.stl"), dir);
  expectBadOutput(r, (dir / "b.stl").string(), "is a folder; expected a file path");
  EXPECT_TRUE(fs::is_empty(dir / "b.stl"));
}

// simulate --out names a folder: a file there is refused, and it is left alone.
TEST(OutputGuarantees, OutputFolderThatIsAFileExitsTwo) {
  const ScratchDir scratch{"output_notfolder"};
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "out") << "x";
  const CommandResult r = vcontact(
      "simulate \"" + kAssets + "/scenarios/ball_drop.json\" --out " + inQuotes(dir / "out"), dir);
  // The folder check names the option too (0759d1d).
  expectBadOutput(r, "--out: " + (dir / "out").string(), "is a file; expected an output folder");
  EXPECT_EQ(readAll(dir / "out"), "x");
}

// ---- resource guards -----------------------------------------------------------------------

TEST(OutputGuarantees, TessellationBeyondTheTriangleLimitIsRefused) {
  const ScratchDir scratch{"output_tess"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact(
      "tessellate sphere:0.01 --segments 100000 --rings 100000 --out " + inQuotes(dir / "b.stl"),
      dir);
  // 2 · 100000 · 99999 triangles
  expectBadOutput(r, "--segments/--rings",
                  "19999800000 triangles, more than the limit of 10000000");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

TEST(OutputGuarantees, SynthSamplesBeyondTheLimitAreRefused) {
  const ScratchDir scratch{"output_synth"};
  const fs::path& dir = scratch.path();
  const CommandResult r = vcontact("synth --profile loading --model \"" + kAssets +
                                       "/datasets/models/loading-truth.model.json\" --samples "
                                       "10000000000 --out " +
                                       inQuotes(dir / "big.json"),
                                   dir);
  expectBadOutput(r, "--samples", "expected a sample count in [3, 10000000], got 10000000000");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

// 1 s at 1e9 Hz would be 2e9 rows of two bodies and one pair... refused up front.
TEST(OutputGuarantees, SimulationRowsBeyondTheLimitAreRefused) {
  const ScratchDir scratch{"output_rows"};
  const fs::path& dir = scratch.path();
  const CommandResult r =
      vcontact("simulate \"" + kAssets + "/scenarios/ball_drop.json\" --output-rate 1e9 --out " +
                   inQuotes(dir / "out"),
               dir);
  // 0.3 s · 1e9 Hz + 1 output times, 2 bodies + 1 pair each
  expectBadOutput(r, "--output-rate", "would write 900000003 CSV rows");
  EXPECT_EQ(leftovers(dir, {}), std::vector<std::string>{});
}

// ---- stopped simulations -------------------------------------------------------------------

// A steel ball 0.5 mm above a plate; the contact model's `effects` (JSON object members) and
// the scenario's `extra` keys are the test's.
std::string ballScenarioWith(const std::string& effects, const std::string& extra) {
  return R"({"format": "vcontact.scenario/1", "duration": 0.05, "output_rate": 1000, )" + extra +
         R"(
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.0105"}],
    "pairs": [{"a": "ball", "b": "plate", "method": "analytic",
               "model": {"format": "vcontact.model/1", "effects": {)" +
         effects + "}}}]}";
}

// The same with the stiffness kv (N/m³) alone.
std::string ballScenario(const std::string& kv, const std::string& extra) {
  return ballScenarioWith(R"("stiffness": {"kv": )" + kv + "}", extra);
}

// Every line of `csv` has as many fields as its header, each a finite number (the body name
// column of bodies.csv excepted); returns the last row's time.
double lastCompleteTime(const fs::path& csv) {
  std::istringstream lines(readAll(csv));
  std::string line;
  std::getline(lines, line);
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  const long columns = fields(line);
  double t = -1.0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(fields(line), columns) << csv << ": " << line;
    std::istringstream row(line);
    std::string cell;
    for (int c = 0; std::getline(row, cell, ','); ++c) {
      if (csv.filename() == "bodies.csv" && c == 1) continue;
      std::size_t used = 0;
      const double x = std::stod(cell, &used);
      EXPECT_EQ(used, cell.size()) << csv << ": " << cell;
      EXPECT_TRUE(std::isfinite(x)) << csv << ": " << line;
      if (c == 0) t = x;
    }
  }
  return t;
}

// Runs the scenario, expects exit 3 and the summary's stop: cause, time after the last row,
// and the message (standard error and "status") holding each of `named` (the body, pair...).
void expectStopped(const std::string& name, const std::string& scenario, const std::string& cause,
                   const std::vector<std::string>& named = {}, double touch = 0.010) {
  const ScratchDir scratch{"output_" + name};
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "s.json") << scenario;
  const CommandResult r =
      vcontact("simulate " + inQuotes(dir / "s.json") + " --out " + inQuotes(dir / "out"), dir);
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_NE(r.err.find("simulation stopped: t = "), std::string::npos) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(readAll(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("stop_cause"), cause) << summary.dump();
  const double stopped = summary.at("stopped_at_s").get<double>();
  EXPECT_GT(stopped, 0.0);
  EXPECT_EQ(summary.at("simulated_time_s").get<double>(), stopped);
  for (const std::string& n : named) {
    EXPECT_NE(r.err.find(n), std::string::npos) << r.err;
    EXPECT_NE(summary.at("status").get<std::string>().find(n), std::string::npos) << summary.dump();
  }
  for (const char* csv : {"bodies.csv", "pair_ball-plate.csv"}) {
    const double last = lastCompleteTime(dir / "out" / csv);
    // The ball falls 0.5 mm, touching at sqrt(2 · 0.5 mm / g) = 10.1 ms: rows until then
    // (`touch`, earlier where loose tolerances step into the plate early).
    EXPECT_GE(last, touch) << csv;
    EXPECT_LE(last, stopped) << csv;
  }
  EXPECT_EQ(leftovers(dir / "out", {}),
            (std::vector<std::string>{"bodies.csv", "pair_ball-plate.csv", "summary.json"}));
}

// kv = 1e3 N/m³ cannot hold 32 g: the ball sinks beyond a tenth of its size.
TEST(OutputGuarantees, PenetrationBeyondBoundKeepsCompleteCsvs) {
  expectStopped("penetration", ballScenario("1e3", ""), "penetration_beyond_bound");
}

// kv = 1e15 N/m³ (a few hundred times steel's) with a minimum step of 10 µs: the impact needs
// steps of a few µs, so the step size collapses at the touch.
TEST(OutputGuarantees, StepCollapseFromAbsurdStiffnessKeepsCompleteCsvs) {
  expectStopped("collapse",
                ballScenario("1e15", R"("tolerances": {"min_step": 1e-5, "initial_step": 1e-5},)"),
                "step_size_collapse");
}

// An expression effect a user can write: a damping that grows as the root of the closing speed.
// Its formula has no value once the ball rebounds (sqrt of ddot < 0): NaN in the force, then in
// the state. The run stops at the rebound (after the touch at 10.1 ms), naming the body whose
// state or rate is not finite and, since by then every quantity is NaN, the effect whose force
// had no value first and when.
TEST(OutputGuarantees, NanFromAnExpressionEffectKeepsCompleteCsvs) {
  const std::string effects = R"json("stiffness": {"kv": 5.17e12},
      "root_damping": {"kind": "expression", "normal": "c*sqrt(ddot)",
                       "parameters": {"c": {"value": 1, "unit": "N s^0.5/m^0.5",
                                            "lower": 0, "upper": 1000}}})json";
  for (const char* integrator : {"dopri5", "bdf"}) {
    SCOPED_TRACE(integrator);
    expectStopped(std::string("nan_") + integrator,
                  ballScenarioWith(effects, R"("integrator": ")" + std::string(integrator) + "\","),
                  "non_finite_state",
                  {"body 'ball'",
                   "first non-finite force: pair 'ball-plate', effect 'root_damping' at t = 0.01"});
  }
}

// kv = 1e18 N/m³ (the input limit) with tolerances too loose for it: the ball arrives at
// 0.1 m/s and leaves at metres per second (docs/SCENARIO.md, "Stopped runs"), far more
// than ten times the energy of its 0.5 mm fall. Both integrators; with the default tolerances
// the same impact finishes (OutputGuarantees.AbsurdStiffnessWithDefaultTolerancesFinishes).
// The BDF's steps of a millisecond reach the plate at 9.7 ms, so rows up to 9 ms are kept.
TEST(OutputGuarantees, BlowUpFromAbsurdStiffnessWithLooseTolerancesKeepsCompleteCsvs) {
  const std::string bdf = R"("integrator": "bdf", "tolerances": {"abs": 1e-2, "rel": 1e-2},)";
  expectStopped("blowup_bdf", ballScenario("1e18", bdf), "blow_up", {"body 'ball'"}, 0.009);
  const std::string dopri5 = R"("integrator": "dopri5", "tolerances": {"abs": 1, "rel": 1},)";
  expectStopped("blowup_dopri5", ballScenario("1e18", dopri5), "blow_up", {"body 'ball'"});
}

// The same stiffness with the default tolerances: the adaptive step follows the impact and the
// guard stays silent; with no damping the ball bounces back to the height it fell from,
// z = 10.5 mm, within 2 µm: an apex falls between two outputs 1 ms apart, and the ball is
// then at most ½ g (0.5 ms)² = 1.2 µm below it.
TEST(OutputGuarantees, AbsurdStiffnessWithDefaultTolerancesFinishes) {
  for (const char* integrator : {"dopri5", "bdf"}) {
    SCOPED_TRACE(integrator);
    const ScratchDir scratch{"output_stiff_" + std::string(integrator)};
    const fs::path& dir = scratch.path();
    std::ofstream(dir / "s.json") << ballScenario(
        "1e18", R"("integrator": ")" + std::string(integrator) + "\",");
    const CommandResult r =
        vcontact("simulate " + inQuotes(dir / "s.json") + " --out " + inQuotes(dir / "out"), dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(readAll(dir / "out" / "bodies.csv"));
    std::string line;
    double z_max = 0.0;  // m, after the first impact (10.1 ms)
    while (std::getline(lines, line)) {
      if (line.find(",ball,") == std::string::npos || std::stod(line) < 0.012) continue;
      std::istringstream row(line);
      std::string cell;
      for (int c = 0; c <= 4; ++c) std::getline(row, cell, ',');  // t, body, x, y, z
      z_max = std::max(z_max, std::stod(cell));
    }
    EXPECT_NEAR(z_max, 0.0105, 2e-6);
  }
}

}  // namespace
