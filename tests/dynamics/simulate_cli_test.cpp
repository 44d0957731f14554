// `vcontact simulate`: the files it writes, and its exit status when a run stops.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

int runCli(const std::string& args, const fs::path& err) {
  std::ostringstream cmd;
  cmd << '"' << VCONTACT_BINARY << "\" " << args << " 2> \"" << err.string() << '"';
  const int status = std::system(cmd.str().c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readAll(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

long lineCount(const fs::path& p) {
  const std::string text = readAll(p);
  return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vcontact_simulate_cli_" + name + "_" +
                                                    std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
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

}  // namespace
