// `vcontact view`: the page it writes for a simulation folder, and for a dynamic compare's
// folder, loaded in headless Chromium.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "support/run_command.hpp"

namespace vcontact {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::runCommand;

const fs::path kChromium = "/usr/bin/chromium";
const fs::path kThreeJs = "/usr/share/javascript/three/three.min.js";

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

class ViewCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vcontact_view_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  CommandResult vcontact(const std::string& args) {
    return runCommand(std::string("\"") + VCONTACT_BINARY + "\" " + args, dir_ / "stderr.txt");
  }
  // Chromium with a fresh profile and no network; WebGL through its software rasteriser.
  CommandResult chromium(const std::string& args, const std::string& page) {
    const std::string cmd = "timeout 120 " + kChromium.string() +
                            " --headless --no-sandbox --disable-background-networking"
                            " --disable-component-update --disable-sync --no-first-run"
                            " --use-angle=swiftshader --enable-unsafe-swiftshader"
                            " --enable-logging=stderr --v=0 --window-size=900,700"
                            " --user-data-dir=" +
                            (dir_ / "profile").string() + ' ' + args + " \"file://" +
                            (dir_ / "view.html").string() + page + '"';
    return runCommand(cmd, dir_ / "chromium.txt");
  }
  // Runs the bundled scenario NAME into out/ and writes its page, view.html.
  void simulateAndView(const std::string& name) {
    const std::string scenario = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/" + name + ".json";
    const CommandResult s =
        vcontact("simulate " + scenario + " --out " + (dir_ / "out").string() + " --quiet");
    ASSERT_EQ(s.exitCode, 0) << s.err;
    const CommandResult v =
        vcontact("view " + (dir_ / "out").string() + " --out " + (dir_ / "view.html").string());
    ASSERT_EQ(v.exitCode, 0) << v.err;
  }
  // The page's data-NAME attribute on <body>, as --dump-dom prints it.
  static std::string attribute(const std::string& dom, const std::string& name) {
    std::smatch m;
    if (!std::regex_search(dom, m, std::regex("data-" + name + "=\"([^\"]*)\""))) return "";
    return m[1];
  }
  fs::path dir_;
};

TEST_F(ViewCli, BallDropPlaysInHeadlessChromium) {
  if (!fs::exists(kChromium) || !fs::exists(kThreeJs))
    GTEST_SKIP() << "chromium or libjs-three is not installed (scripts/setup.sh installs both)";
  ASSERT_NO_FATAL_FAILURE(simulateAndView("ball_drop"));
  const std::string html = readText(dir_ / "view.html");
  EXPECT_EQ(html.find("<script src"), std::string::npos);  // everything inlined: no server
  EXPECT_NE(html.find("REVISION"), std::string::npos);     // three.js is in the page

  // Paused at t = 0, at the first impact (t = 0.032 s, the only contact until 0.085 s: the
  // ball bounces) and past the end (the last output is shown).
  const CommandResult start = chromium("--virtual-time-budget=3000 --dump-dom", "#t=0");
  ASSERT_EQ(start.exitCode, 0) << start.err;
  const CommandResult impact = chromium("--virtual-time-budget=3000 --dump-dom", "#t=0.032");
  ASSERT_EQ(impact.exitCode, 0) << impact.err;
  const CommandResult end = chromium("--virtual-time-budget=3000 --dump-dom", "#t=1");
  ASSERT_EQ(end.exitCode, 0) << end.err;
  for (const auto* r : {&start, &impact, &end}) {
    EXPECT_EQ(attribute(r->out, "ready"), "1") << r->out.substr(0, 400);
    EXPECT_EQ(attribute(r->out, "errors"), "0") << attribute(r->out, "error-text");
    EXPECT_EQ(attribute(r->out, "body-meshes"), "2");  // the plate and the ball
    // Chromium prints an uncaught exception or console.error of the page on its log.
    EXPECT_EQ(r->err.find("Uncaught"), std::string::npos) << r->err;
  }
  EXPECT_EQ(attribute(start.out, "markers"), "0");   // 5 mm above the plate
  EXPECT_EQ(attribute(impact.out, "markers"), "1");  // one patch
  EXPECT_EQ(attribute(impact.out, "frame"), "64");   // 0.032 s at 2000 outputs a second
  EXPECT_EQ(attribute(end.out, "frames"), "601");    // t = 0 included
  EXPECT_EQ(attribute(end.out, "frame"), "600");

  // The ball's centre on the screen moved down by its 5 mm fall (the plate stays put).
  std::smatch a, b;
  const std::regex ball("\\[\\[(-?\\d+),(-?\\d+)\\],\\[(-?\\d+),(-?\\d+)\\]\\]");
  const std::string screenStart = attribute(start.out, "screen");
  const std::string screenEnd = attribute(impact.out, "screen");
  ASSERT_TRUE(std::regex_search(screenStart, a, std::regex(ball))) << screenStart;
  ASSERT_TRUE(std::regex_search(screenEnd, b, std::regex(ball))) << screenEnd;
  EXPECT_EQ(a[1], b[1]);  // the plate
  EXPECT_EQ(a[2], b[2]);
  EXPECT_GT(std::stoi(b[4]) - std::stoi(a[4]), 20) << screenStart << " -> " << screenEnd;

  // Screenshots at the two times differ.
  ASSERT_EQ(
      chromium("--virtual-time-budget=3000 --screenshot=" + (dir_ / "t0.png").string(), "#t=0")
          .exitCode,
      0);
  ASSERT_EQ(
      chromium("--virtual-time-budget=3000 --screenshot=" + (dir_ / "t1.png").string(), "#t=0.032")
          .exitCode,
      0);
  const std::string png0 = readText(dir_ / "t0.png"), png1 = readText(dir_ / "t1.png");
  EXPECT_GT(png0.size(), 1000u);
  EXPECT_NE(png0, png1);
}

TEST_F(ViewCli, PegInsertionShowsItsDriveForce) {
  if (!fs::exists(kChromium) || !fs::exists(kThreeJs))
    GTEST_SKIP() << "chromium or libjs-three is not installed (scripts/setup.sh installs both)";
  ASSERT_NO_FATAL_FAILURE(simulateAndView("peg_insertion"));
  // The drive's 121 rows of loads.csv go into the page, six numbers each.
  EXPECT_NE(readText(dir_ / "view.html").find("\"loads\":[{\"name\":\"drive\""), std::string::npos);
  // At 0.12 s the drive pushes the peg onto the hole's floor with its limit, 5 N: one arrow.
  const CommandResult end = chromium("--virtual-time-budget=3000 --dump-dom", "#t=0.12");
  ASSERT_EQ(end.exitCode, 0) << end.err;
  EXPECT_EQ(attribute(end.out, "ready"), "1") << end.out.substr(0, 400);
  EXPECT_EQ(attribute(end.out, "errors"), "0") << attribute(end.out, "error-text");
  EXPECT_EQ(attribute(end.out, "loads"), "1");
  EXPECT_EQ(attribute(end.out, "frame"), "120");
}

// A dynamic dataset whose record cannot be a free body's: the box moves at 0.5 m/s along x
// 0.3 m above the plate and never falls. `compare` releases it from the record's first state
// (the velocity columns), so the simulated box falls g t²/2 = 0.196 m in 0.2 s, still in flight.
void writeLevitatingBox(const fs::path& dir) {
  std::ofstream csv(dir / "levitating.csv");
  csv << "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  for (int i = 0; i <= 20; ++i) {
    const double t = 0.01 * i;
    csv << t << ',' << 0.5 * t << ",0,0.3,1,0,0,0,0.5,0,0,0,0,0\n";
  }
  std::ofstream(dir / "levitating.json")
      << R"({"format": "vcontact.dataset/1", "name": "levitating", "data": "levitating.csv",
 "mode": "dynamic", "payload": {"shape": "box", "size": [0.1, 0.1, 0.1]},
 "plate": {"shape": "halfspace"}, "payload_inertia": {"mass": 0.37, "inertia": [6e-4, 6e-4, 6e-4]},
 "outputs": ["position", "attitude"]})";
  std::ofstream(dir / "model.json")
      << R"({"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 2e6}}})";
}

TEST_F(ViewCli, DynamicComparePlaysTheRecordAsAGhost) {
  if (!fs::exists(kChromium) || !fs::exists(kThreeJs))
    GTEST_SKIP() << "chromium or libjs-three is not installed (scripts/setup.sh installs both)";
  writeLevitatingBox(dir_);
  const CommandResult c =
      vcontact("compare " + (dir_ / "levitating.json").string() + " --model " +
               (dir_ / "model.json").string() + " --out " + (dir_ / "cmp").string());
  ASSERT_EQ(c.exitCode, 0) << c.err;
  const CommandResult v =
      vcontact("view " + (dir_ / "cmp").string() + " --out " + (dir_ / "view.html").string());
  ASSERT_EQ(v.exitCode, 0) << v.err;
  const std::string html = readText(dir_ / "view.html");
  EXPECT_NE(html.find("\"name\":\"levitating (record)\""), std::string::npos);
  EXPECT_NE(html.find("\"ghost\":true"), std::string::npos);

  const CommandResult start = chromium("--virtual-time-budget=3000 --dump-dom", "#t=0");
  ASSERT_EQ(start.exitCode, 0) << start.err;
  const CommandResult end = chromium("--virtual-time-budget=3000 --dump-dom", "#t=0.2");
  ASSERT_EQ(end.exitCode, 0) << end.err;
  for (const auto* r : {&start, &end}) {
    EXPECT_EQ(attribute(r->out, "ready"), "1") << r->out.substr(0, 400);
    EXPECT_EQ(attribute(r->out, "errors"), "0") << attribute(r->out, "error-text");
    EXPECT_EQ(attribute(r->out, "body-meshes"), "3");  // plate, simulated box, recorded ghost
    EXPECT_EQ(attribute(r->out, "markers"), "0");
    EXPECT_EQ(r->err.find("Uncaught"), std::string::npos) << r->err;
  }
  EXPECT_EQ(attribute(end.out, "frames"), "21");
  EXPECT_EQ(attribute(end.out, "frame"), "20");
  // Screen positions of [plate, simulated, record]: together at the start; at the end the
  // simulated box lies below its ghost (screen y grows downwards), at the same x on screen
  // within the perspective's shift.
  const std::regex three(
      "\\[\\[(-?\\d+),(-?\\d+)\\],\\[(-?\\d+),(-?\\d+)\\],\\[(-?\\d+),(-?\\d+)\\]\\]");
  std::smatch a, b;
  const std::string s0 = attribute(start.out, "screen"), s1 = attribute(end.out, "screen");
  ASSERT_TRUE(std::regex_search(s0, a, three)) << s0;
  ASSERT_TRUE(std::regex_search(s1, b, three)) << s1;
  EXPECT_EQ(a[3], a[5]) << s0;
  EXPECT_EQ(a[4], a[6]) << s0;
  EXPECT_GT(std::stoi(b[4]) - std::stoi(b[6]), 20) << s1;
  EXPECT_LT(std::abs(std::stoi(b[3]) - std::stoi(b[5])), std::stoi(b[4]) - std::stoi(b[6])) << s1;
}

TEST_F(ViewCli, ACompareFolderWithoutItsDatasetNamesTheOption) {
  fs::create_directories(dir_ / "cmp");
  std::ofstream(dir_ / "cmp" / "compare.json") << R"({"e_q": 0.1})";
  std::ofstream(dir_ / "cmp" / "trajectory.csv") << "t,x,x_sim\n0,0,0\n";
  const CommandResult r =
      vcontact("view " + (dir_ / "cmp").string() + " --out " + (dir_ / "view.html").string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--dataset"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "view.html"));
}

TEST_F(ViewCli, RefusesAFolderWithoutASimulation) {
  const CommandResult r =
      vcontact("view " + dir_.string() + " --out " + (dir_ / "view.html").string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("no summary.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "view.html"));
}

}  // namespace
}  // namespace vcontact
