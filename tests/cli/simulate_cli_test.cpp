// `vcontact simulate`: the files it writes, and its exit status when a run stops.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::test::readAll;

int runCli(const std::string& args, const fs::path& err) {
  std::ostringstream cmd;
  cmd << '"' << VCONTACT_BINARY << "\" " << args << " 2> \"" << err.string() << '"';
  const int status = std::system(cmd.str().c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

long lineCount(const fs::path& p) {
  const std::string text = readAll(p);
  return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("vcontact_simulate_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// The values of one column of a CSV file with a header row.
std::vector<double> column(const fs::path& csv, const std::string& name) {
  std::istringstream lines(readAll(csv));
  std::string line;
  std::getline(lines, line);
  std::vector<std::string> header;
  std::istringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto at = std::find(header.begin(), header.end(), name);
  if (at == header.end()) {
    ADD_FAILURE() << csv << " has no column " << name;
    return {};
  }
  const auto index = static_cast<std::size_t>(at - header.begin());
  std::vector<double> out;
  while (std::getline(lines, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t i = 0; i <= index && std::getline(row, cell, ','); ++i) {
    }
    out.push_back(std::stod(cell));
  }
  return out;
}

double largest(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// The bundled lumped-against-distributed scenario, shortened to `duration` s, in `dir`.
fs::path shortPunchScenario(const fs::path& dir, const std::string& duration) {
  const fs::path assets = fs::path(VCONTACT_ASSETS_DIR) / "scenarios";
  std::string text = readAll(assets / "punch_lumped_vs_distributed.json");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  replace("\"duration\": 0.06", "\"duration\": " + duration);
  std::ostringstream mesh;  // the absolute path, quoted
  mesh << '"' << (assets / "meshes" / "punch.stl").string() << '"';
  for (int i = 0; i < 2; ++i) replace("\"meshes/punch.stl\"", mesh.str());
  const fs::path out = dir / "punch.json";
  std::ofstream(out) << text;
  return out;
}

// "friction": "distributed" end to end: the distributed pair's spin torque is carried by the
// coulomb share (spin and contensou zero), the lumped pair's by spin.
TEST(SimulateCli, DistributedPairPutsTheSpinTorqueInCoulomb) {
  const fs::path dir = scratch("distributed");
  const fs::path scenario = shortPunchScenario(dir, "0.003");
  ASSERT_EQ(runCli("simulate \"" + scenario.string() + "\" --out \"" + (dir / "out").string() +
                       "\" --quiet",
                   dir / "err"),
            0)
      << readAll(dir / "err");
  const fs::path distributed = dir / "out" / "pair_distributed-plate.csv";
  const fs::path lumped = dir / "out" / "pair_lumped-plate.csv";
  EXPECT_EQ(lineCount(distributed), 1 + 4);  // t = 0, 1, 2, 3 ms
  EXPECT_EQ(largest(column(distributed, "spin.tauz")), 0.0);
  EXPECT_EQ(largest(column(distributed, "contensou.tauz")), 0.0);
  EXPECT_GT(largest(column(distributed, "coulomb.tauz")), 0.0);
  EXPECT_GT(largest(column(lumped, "spin.tauz")), 0.0);
  EXPECT_EQ(largest(column(lumped, "coulomb.tauz")), 0.0);
  // Sliding dominates (ε = 5): the lumped spin torque is about twice the pointwise one.
  const double ratio =
      column(lumped, "spin.tauz").front() / column(distributed, "coulomb.tauz").front();
  EXPECT_GT(ratio, 1.8);
  EXPECT_LT(ratio, 2.1);
  fs::remove_all(dir);
}

// The short punch scenario with `from` replaced by `to` is bad input: `simulate` exits 2 with
// `message` on standard error and writes no output.
void expectRefused(const std::string& name, const std::string& from, const std::string& to,
                   const std::string& message) {
  const fs::path dir = scratch(name);
  const fs::path scenario = shortPunchScenario(dir, "0.003");
  std::string text = readAll(scenario);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(scenario) << text;
  EXPECT_EQ(
      runCli("simulate \"" + scenario.string() + "\" --out \"" + (dir / "out").string() + "\"",
             dir / "err"),
      2);
  const std::string err = readAll(dir / "err");
  EXPECT_NE(err.find(message), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out" / "bodies.csv"));
  fs::remove_all(dir);
}

TEST(SimulateCli, BadColumnGridExitsWithTwoNamingPairAndKey) {
  expectRefused("columns", "\"columns\": 64", "\"columns\": 4",
                "pairs[1].columns: pair 'distributed-plate': expected an integer number of grid "
                "lines per side in [8, 512], got 4");
}

// A method that does not handle a pair's shapes is bad input: found when the file is read,
// exit 2, no output (it used to surface at the first evaluation, after the CSV headers).
TEST(SimulateCli, MethodThatCannotTakeThePairExitsWithTwoBeforeAnyOutput) {
  expectRefused("method", "\"method\": \"halfspace\"", "\"method\": \"fast\"",
                "pairs[0].method: bodies 'lumped' and 'plate': cannot compute");
}

TEST(SimulateCli, WritesBodiesPairsAndSummary) {
  const fs::path dir = scratch("ok");
  const std::string scenario = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/ball_drop.json";
  ASSERT_EQ(runCli("simulate \"" + scenario + "\" --out \"" + dir.string() + "\"", dir / "err"), 0)
      << readAll(dir / "err");
  // 0.3 s at 2000 Hz: 601 output times, two bodies each, plus the header.
  EXPECT_EQ(lineCount(dir / "bodies.csv"), 1 + 2 * 601);
  EXPECT_EQ(lineCount(dir / "pair_ball-plate.csv"), 1 + 601);
  EXPECT_NE(readAll(dir / "pair_ball-plate.csv").find("bristle.fx"), std::string::npos);
  EXPECT_NE(readAll(dir / "summary.json").find("\"status\": \"completed\""), std::string::npos);
  EXPECT_NE(readAll(dir / "err").find("real-time factor"), std::string::npos);
  fs::remove_all(dir);
}

TEST(SimulateCli, StoppedRunExitsWithThreeAndKeepsOutput) {
  const fs::path dir = scratch("stop");
  std::ofstream(dir / "soft.json") << R"({
    "format": "vcontact.scenario/1", "duration": 1.0, "output_rate": 1000,
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.0105"}],
    "pairs": [{"a": "ball", "b": "plate",
               "model": {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e3}}}}]})";
  const std::string args =
      "simulate \"" + (dir / "soft.json").string() + "\" --out \"" + (dir / "out").string() + "\"";
  EXPECT_EQ(runCli(args, dir / "err"), 3);
  const std::string err = readAll(dir / "err");
  EXPECT_NE(err.find("simulation stopped: t = "), std::string::npos) << err;
  EXPECT_NE(err.find("pair 'ball-plate': mean penetration V/A"), std::string::npos) << err;
  EXPECT_GT(lineCount(dir / "out" / "bodies.csv"), 20);  // ~10 ms of fall at 1 kHz, 2 bodies
  EXPECT_NE(readAll(dir / "out" / "summary.json").find("mean penetration"), std::string::npos);
  fs::remove_all(dir);
}

// A discrete run whose impacts "auto" left to the plain step says so on the terminal, with the
// count and what to change, and summary.json labels the impact: a ball dropped 5 mm rebounds
// at about 0.26 m/s, below a restitution threshold of 1 m/s. At the default threshold the same
// drop's impacts are resolved and nothing is said.
TEST(SimulateCli, SaysWhichImpactsThePlainStepTook) {
  const fs::path dir = scratch("plain");
  const std::string drop = R"({
    "format": "vcontact.scenario/1", "duration": 0.05, "output_rate": 1000,
    "integrator": "discrete", THRESHOLD
    "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
               {"name": "ball", "shape": "sphere:0.01", "density": 7900, "pose": "0,0,0.015"}],
    "pairs": [{"a": "ball", "b": "plate",
               "model": {"format": "vcontact.model/1",
                         "effects": {"stiffness": {"kv": 5.17e12}, "damping": {"a": 1.0}}}}]})";
  for (const bool high : {true, false}) {
    std::string text = drop;
    text.replace(text.find("THRESHOLD"), 9, high ? R"("restitution_threshold": 1.0,)" : "");
    std::ofstream(dir / "drop.json") << text;
    const std::string args = "simulate \"" + (dir / "drop.json").string() + "\" --out \"" +
                             (dir / "out").string() + "\"";
    ASSERT_EQ(runCli(args, dir / "err"), 0) << readAll(dir / "err");
    const std::string err = readAll(dir / "err"), summary = readAll(dir / "out" / "summary.json");
    const std::size_t said = err.find("1 of 1 fast impacts were left to the plain step");
    if (high) {
      EXPECT_NE(said, std::string::npos) << err;
      EXPECT_NE(err.find("restitution_threshold = 1 m/s"), std::string::npos) << err;
      EXPECT_NE(summary.find("\"resolution\": \"plain\""), std::string::npos) << summary;
    } else {
      EXPECT_EQ(err.find("left to the plain step"), std::string::npos) << err;
      EXPECT_NE(summary.find("\"resolution\": \"resolved\""), std::string::npos) << summary;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
