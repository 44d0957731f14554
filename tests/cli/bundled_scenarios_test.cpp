// Every bundled scenario of assets/scenarios, shortened, simulated: every CSV it writes has one
// field count per file (the header's), and `vcontact view` accepts the folder (issue 36: a mesh
// pair out of contact at an output time wrote a 25-field row under a 43-column header, and the
// viewer refused nearly every mesh simulation, the README's own screenshot among them).

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
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

const fs::path kAssets = VCONTACT_ASSETS_DIR;

/// The simulated time each scenario is cut to: a few output intervals at least (the rows out of
/// contact at the start and, in most scenarios, the first contact rows), and no more than its
/// own duration. 10 ms keeps the mesh–mesh scenarios to seconds.
constexpr double kShortDuration = 0.01;

// The bundled scenario files (not the model files beside them).
std::vector<fs::path> bundledScenarios() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(kAssets / "scenarios")) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".json" && name.find(".model.") == std::string::npos) {
      out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A copy of `scenario` in dir/scenarios cut to kShortDuration (or its own duration, if
// shorter), beside links to what its relative paths name (meshes/, ../meshes/, model files).
fs::path shortened(const fs::path& scenario, const fs::path& dir) {
  const fs::path copies = dir / "scenarios";
  if (!fs::exists(copies)) {
    fs::create_directories(copies);
    for (const auto& e : fs::directory_iterator(kAssets / "scenarios")) {
      fs::create_directory_symlink(e.path(), copies / e.path().filename());
    }
    fs::create_directory_symlink(kAssets / "meshes", dir / "meshes");
  }
  nlohmann::json j = nlohmann::json::parse(readAll(scenario));
  j["duration"] = std::min(j.at("duration").get<double>(), kShortDuration);
  const fs::path out = copies / ("short_" + scenario.filename().string());
  std::ofstream(out) << j.dump(2);
  return out;
}

// Field counts of each line of a CSV file (quoted fields are not written by vcontact: a comma is
// a separator everywhere).
std::vector<long> fieldCounts(const fs::path& csv) {
  std::istringstream lines(readAll(csv));
  std::vector<long> counts;
  for (std::string line; std::getline(lines, line);) {
    counts.push_back(static_cast<long>(std::count(line.begin(), line.end(), ',')) + 1);
  }
  return counts;
}

CommandResult vcontact(const std::string& args, const fs::path& dir) {
  return vcontact::test::runCommand(std::string("\"") + VCONTACT_BINARY + "\" " + args,
                                    dir / "stderr.txt");
}

TEST(BundledScenarios, EveryCsvHasOneFieldCountAndTheViewerTakesEveryOutput) {
  const ScratchDir scratch{"bundled_scenarios"};
  const std::vector<fs::path> scenarios = bundledScenarios();
  ASSERT_GE(scenarios.size(), 10u);  // the folder holds 11 scenarios today
  for (const fs::path& scenario : scenarios) {
    const std::string name = scenario.stem().string();
    SCOPED_TRACE(name);
    const fs::path out = scratch / ("out_" + name);
    const CommandResult run = vcontact("simulate " + inQuotes(shortened(scenario, scratch.path())) +
                                           " --out " + inQuotes(out) + " --quiet",
                                       scratch.path());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    int csvs = 0;
    for (const auto& e : fs::directory_iterator(out)) {
      if (e.path().extension() != ".csv") continue;
      ++csvs;
      const std::vector<long> counts = fieldCounts(e.path());
      // a header, and the row at t = 0 but in a patch file (no rows while apart)
      const bool patches = e.path().stem().string().find("_patches") != std::string::npos;
      ASSERT_GE(counts.size(), patches ? 1u : 2u) << e.path();
      for (std::size_t line = 1; line < counts.size(); ++line) {
        ASSERT_EQ(counts[line], counts[0]) << e.path() << " line " << line + 1;
      }
    }
    EXPECT_GE(csvs, 2) << "bodies.csv and a pair file";
    const CommandResult view =
        vcontact("view " + inQuotes(out) + " --out " + inQuotes(out / "view.html"), scratch.path());
    EXPECT_EQ(view.exitCode, 0) << view.err;
    EXPECT_TRUE(fs::exists(out / "view.html"));
  }
}

}  // namespace
