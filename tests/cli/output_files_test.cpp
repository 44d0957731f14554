// The files a command finds in its output place and the names it writes (issue 36): an input is
// never overwritten by an output, a mesh is written in the format its extension names in any
// case, a simulation into the folder of an earlier one leaves none of that run's files, the
// temporaries a killed run left are cleaned, a file name that is not UTF-8 is written into JSON
// safely, and an output folder that cannot be made is bad input (exit 2), not an internal error.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
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

const fs::path kAssets = VCONTACT_ASSETS_DIR;

CommandResult vcontact(const std::string& args, const fs::path& dir) {
  return vcontact::test::runCommand(std::string("\"") + VCONTACT_BINARY + "\" " + args,
                                    dir / "stderr.txt");
}

void expectExitTwo(const CommandResult& r, const std::string& message) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

// A steel ball above a plate; pair `pair` ("ball-plate" when empty).
std::string ballScenario(const std::string& pair) {
  const std::string name = pair.empty() ? "" : R"("name": ")" + pair + R"(", )";
  return R"({"format": "vcontact.scenario/1", "duration": 0.002, "output_rate": 1000,
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.0105"}],
    "pairs": [{)" +
         name +
         R"("a": "ball", "b": "plate", "method": "analytic",
               "model": {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e12}}}}]})";
}

std::vector<std::string> names(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// ---- inputs are not outputs ---------------------------------------------------------------

// Issue 36: `compare --out` into the dataset's own folder overwrote a dataset CSV named
// residuals.csv. Every validation command refuses, before any work, and the CSV is unchanged.
TEST(OutputFiles, ValidationCommandsRefuseToOverwriteTheirInput) {
  const ScratchDir scratch{"output_files_inputs"};
  const fs::path model = kAssets / "datasets/models/loading-truth.model.json";
  const CommandResult synth =
      vcontact("synth --profile loading --samples 300 --model " + inQuotes(model) + " --out " +
                   inQuotes(scratch / "residuals.json"),
               scratch.path());
  ASSERT_EQ(synth.exitCode, 0) << synth.err;
  const std::string csv = readAll(scratch / "residuals.csv");
  for (const std::string command : {"compare", "fit", "diagnose"}) {
    SCOPED_TRACE(command);
    const CommandResult r =
        vcontact(command + " " + inQuotes(scratch / "residuals.json") + " --model " +
                     inQuotes(model) + " --out " + inQuotes(scratch.path()),
                 scratch.path());
    expectExitTwo(r, "--out: would overwrite " + (scratch / "residuals.csv").string() +
                         ", which is the dataset's CSV");
    EXPECT_EQ(readAll(scratch / "residuals.csv"), csv);
  }
  // the model file as an output of fit: model.json in the folder is the model read
  fs::copy_file(model, scratch / "model.json");
  const CommandResult fit =
      vcontact("fit " + inQuotes(scratch / "residuals.json") + " --model " +
                   inQuotes(scratch / "model.json") + " --out " + inQuotes(scratch.path()),
               scratch.path());
  expectExitTwo(fit, "which is the model file");
  // mesh-repair onto its own input
  const CommandResult tess =
      vcontact("tessellate box:0.1,0.1,0.1 --out " + inQuotes(scratch / "box.stl"), scratch.path());
  ASSERT_EQ(tess.exitCode, 0) << tess.err;
  const CommandResult repair = vcontact(
      "mesh-repair " + inQuotes(scratch / "box.stl") + " --out " + inQuotes(scratch / "box.stl"),
      scratch.path());
  expectExitTwo(repair, "which is the mesh to repair");
}

// ---- extensions in any case ---------------------------------------------------------------

// Issue 36: `--out X.OBJ` wrote a binary STL the reader then refused. An extension is matched
// in any case, and one that names no format vcontact writes is refused.
TEST(OutputFiles, MeshExtensionsAreMatchedInAnyCase) {
  const ScratchDir scratch{"output_files_ext"};
  for (const std::string name : {"box.OBJ", "box.Obj", "box.STL"}) {
    SCOPED_TRACE(name);
    const CommandResult w =
        vcontact("tessellate box:0.1,0.2,0.3 --out " + inQuotes(scratch / name), scratch.path());
    ASSERT_EQ(w.exitCode, 0) << w.err;
    const bool obj = name.find("bj") != std::string::npos || name.find("BJ") != std::string::npos;
    EXPECT_EQ(readAll(scratch / name).rfind(obj ? "# vcontact mesh" : "vcontact binary STL", 0),
              0u);
    const CommandResult r = vcontact("mesh-info " + inQuotes(scratch / name), scratch.path());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const CommandResult rep = vcontact(
        "mesh-repair " + inQuotes(scratch / name) + " --out " + inQuotes(scratch / ("re_" + name)),
        scratch.path());
    EXPECT_EQ(rep.exitCode, 0) << rep.err;
  }
  const CommandResult ply =
      vcontact("tessellate box:0.1,0.2,0.3 --out " + inQuotes(scratch / "box.ply"), scratch.path());
  expectExitTwo(ply, "cannot write a mesh to '.ply'; expected a file name ending in .stl");
  EXPECT_FALSE(fs::exists(scratch / "box.ply"));
}

// ---- what an earlier run left -------------------------------------------------------------

// Issue 36: a simulation into the folder of an earlier one left that run's pair files, and
// `view` showed the old forces on the new motion. The files of the earlier run that this one
// does not write go; files vcontact did not write stay.
TEST(OutputFiles, SimulationRemovesTheStaleFilesOfAnEarlierRun) {
  const ScratchDir scratch{"output_files_stale"};
  const fs::path out = scratch / "out";
  std::ofstream(scratch / "first.json") << ballScenario("first");
  std::ofstream(scratch / "second.json") << ballScenario("second");
  ASSERT_EQ(vcontact("simulate " + inQuotes(scratch / "first.json") + " --out " + inQuotes(out),
                     scratch.path())
                .exitCode,
            0);
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(out / "pair_mine.csv") << "a,b\n1,2\n";  // not a header vcontact writes
  const CommandResult r = vcontact(
      "simulate " + inQuotes(scratch / "second.json") + " --out " + inQuotes(out), scratch.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(names(out), (std::vector<std::string>{"bodies.csv", "notes.txt", "pair_mine.csv",
                                                  "pair_second.csv", "summary.json"}));
}

// A run killed with SIGKILL (or a second Ctrl-C) leaves its hidden temporaries; the next run
// into the folder deletes those of processes that no longer run, and nothing else.
TEST(OutputFiles, TemporariesOfADeadRunAreCleaned) {
  const ScratchDir scratch{"output_files_temps"};
  const fs::path out = scratch / "out";
  fs::create_directories(out);
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // a PID that no longer runs
  const std::string dead = ".bodies.csv.tmp-" + std::to_string(child) + "-0";
  const std::string live = ".bodies.csv.tmp-" + std::to_string(::getpid()) + "-3";
  for (const std::string& name : {dead, live, std::string(".notes.tmp-x-1")}) {
    std::ofstream(out / name) << "partial";
  }
  std::ofstream(scratch / "s.json") << ballScenario("");
  const CommandResult r = vcontact(
      "simulate " + inQuotes(scratch / "s.json") + " --out " + inQuotes(out), scratch.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / dead));
  EXPECT_TRUE(fs::exists(out / live));              // this test's process runs
  EXPECT_TRUE(fs::exists(out / ".notes.tmp-x-1"));  // not vcontact's pattern
}

// ---- file names that are not UTF-8 --------------------------------------------------------

// Issue 36: a byte of another encoding in a file name made the JSON writer throw: an internal
// error after the whole run of `simulate`, with nothing written. Such a byte is written as
// U+FFFD (the replacement character) and the JSON stays valid.
TEST(OutputFiles, FileNamesThatAreNotUtf8AreWrittenIntoJsonSafely) {
  const ScratchDir scratch{"output_files_utf8"};
  const std::string latin1 = "caf\xe9";  // "café" in ISO 8859-1: not UTF-8
  const fs::path scenario = scratch / (latin1 + ".json");
  std::ofstream(scenario) << ballScenario("");
  const fs::path out = scratch / "out";
  const CommandResult sim =
      vcontact("simulate " + inQuotes(scenario) + " --out " + inQuotes(out), scratch.path());
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  const nlohmann::json summary = nlohmann::json::parse(readAll(out / "summary.json"));
  EXPECT_NE(summary.at("scenario").get<std::string>().find("caf\xef\xbf\xbd.json"),
            std::string::npos);
  const CommandResult view =
      vcontact("view " + inQuotes(out) + " --scenario " + inQuotes(scenario) + " --out " +
                   inQuotes(scratch / "view.html"),
               scratch.path());
  EXPECT_EQ(view.exitCode, 0) << view.err;
  const fs::path mesh = scratch / (latin1 + ".stl");
  ASSERT_EQ(vcontact("tessellate sphere:0.01 --out " + inQuotes(mesh), scratch.path()).exitCode, 0);
  for (const std::string& args :
       {"mesh-info " + inQuotes(mesh) + " --json",
        "volume " + inQuotes(mesh) + " halfspace --pose-a 0,0,0.0095 --json",
        "surfaces " + inQuotes(mesh) + " --json"}) {
    SCOPED_TRACE(args);
    const CommandResult r = vcontact(args, scratch.path());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NO_THROW((void)nlohmann::json::parse(r.out)) << r.out;
  }
  const fs::path model = kAssets / "datasets/models/loading-truth.model.json";
  const CommandResult synth =
      vcontact("synth --profile loading --samples 300 --model " + inQuotes(model) + " --payload " +
                   inQuotes(mesh) + " --out " + inQuotes(scratch / (latin1 + "_d.json")),
               scratch.path());
  EXPECT_EQ(synth.exitCode, 0) << synth.err;
}

// ---- output folders that cannot be made ---------------------------------------------------

// Issue 36: `--out` under a folder the user cannot enter gave "internal error: filesystem
// error: ... Permission denied" for compare, fit and diagnose. Paths that fail for root too: one
// through a regular file (ENOTDIR) and one through a symbolic-link loop (ELOOP).
TEST(OutputFiles, OutputFolderThatCannotBeMadeExitsTwo) {
  const ScratchDir scratch{"output_files_folder"};
  std::ofstream(scratch / "file") << "x";
  fs::create_symlink(scratch / "loop", scratch / "loop");
  const fs::path dataset = kAssets / "datasets/loading.json";
  const fs::path model = kAssets / "datasets/models/loading-truth.model.json";
  for (const std::string command : {"compare", "fit", "diagnose"}) {
    for (const auto& [out, why] :
         {std::pair{scratch / "file" / "sub", std::string("Not a directory")},
          std::pair{scratch / "loop" / "sub", std::string("Too many levels of symbolic links")}}) {
      SCOPED_TRACE(command + " " + out.string());
      const CommandResult r = vcontact(command + " " + inQuotes(dataset) + " --model " +
                                           inQuotes(model) + " --out " + inQuotes(out),
                                       scratch.path());
      expectExitTwo(
          r, "vcontact: error: --out: " + out.string() + ": cannot be made the output folder");
      EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
      EXPECT_EQ(r.out.find("chi"), std::string::npos) << "refused before any work: " << r.out;
    }
  }
  std::ofstream(scratch / "s.json") << ballScenario("");
  const CommandResult sim = vcontact(
      "simulate " + inQuotes(scratch / "s.json") + " --out " + inQuotes(scratch / "loop" / "out"),
      scratch.path());
  expectExitTwo(sim, "Too many levels of symbolic links");
}

// The same through permission bits, where they apply (not as root).
TEST(OutputFiles, UnenterableFolderExitsTwoWhenNotRoot) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores permission bits";
  const ScratchDir scratch{"output_files_perm"};
  fs::create_directories(scratch / "closed");
  fs::permissions(scratch / "closed", fs::perms::none);
  const fs::path out = scratch / "closed" / "sub";
  for (const std::string command : {"compare", "fit", "diagnose"}) {
    const CommandResult r =
        vcontact(command + " " + inQuotes(kAssets / "datasets/loading.json") + " --model " +
                     inQuotes(kAssets / "datasets/models/loading-truth.model.json") + " --out " +
                     inQuotes(out),
                 scratch.path());
    expectExitTwo(r, "Permission denied");
  }
  fs::permissions(scratch / "closed", fs::perms::owner_all);
}

}  // namespace
