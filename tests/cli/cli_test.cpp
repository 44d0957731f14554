// The vcontact command as a user runs it: exit codes, messages, output files.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "support/run_command.hpp"

namespace vcontact {
namespace {

namespace fs = std::filesystem;

using test::CommandResult;

CommandResult run(const std::string& args) {
  // One stderr file per test: CTest runs the tests of this file in parallel processes.
  const fs::path errFile =
      fs::temp_directory_path() / (std::string("vcontact_cli_") +
                                   testing::UnitTest::GetInstance()->current_test_info()->name() +
                                   "_" + std::to_string(getpid()) + ".stderr");
  CommandResult r = test::runCommand(std::string(VCONTACT_BINARY) + " " + args, errFile);
  fs::remove(errFile);
  return r;
}

TEST(Cli, HelpListsEverySubcommand) {
  const CommandResult r = run("--help");
  EXPECT_EQ(r.exitCode, 0);
  for (const char* cmd : {"volume", "mesh-info", "tessellate"}) {
    EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd;
  }
}

TEST(Cli, VolumeJsonMatchesSphereCap) {
  const CommandResult r = run("volume sphere:0.01 halfspace --pose-a 0,0,0.0095 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double d = 0.01 - 0.0095;
  // The analytic backend's sphere cap is the same closed form, printed to 17 digits: rounding.
  EXPECT_NEAR(j["volume"].get<double>() / (M_PI * d * d * (0.03 - d) / 3), 1.0, 1e-12);
  EXPECT_EQ(j["method"], "analytic");
  EXPECT_EQ(j["normal"][2], 1.0);
}

TEST(Cli, MeshAgainstHalfspaceUsesTheClip) {
  const fs::path file = fs::temp_directory_path() / "vcontact_cli_box.stl";
  io::writeStl(geometry::tessellateBox({0.02, 0.02, 0.02}), file.string());
  const CommandResult r = run("volume " + file.string() + " halfspace --pose-a 0,0,0.009 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "halfspace");
  // 0.02 × 0.02 × 0.001 m, with the float coordinates of STL (~1e-7 relative).
  EXPECT_NEAR(j["volume"].get<double>() / 4e-7, 1.0, 1e-5);
  fs::remove(file);
}

// Two boxes of one file on a half-space: two patches in the JSON beside the aggregate, each
// listed in the table; lifted clear: in_contact false and no patch.
TEST(Cli, VolumeListsEachPatch) {
  const fs::path file = fs::temp_directory_path() / "vcontact_cli_two_boxes.obj";
  geometry::TriangleMesh boxes = geometry::tessellateBox({0.02, 0.02, 0.02});
  const geometry::TriangleMesh second = boxes;
  boxes.vertices.conservativeResize(16, 3);
  boxes.vertices.bottomRows(8) = second.vertices;
  boxes.vertices.bottomRows(8).col(0).array() += 0.05;
  boxes.triangles.conservativeResize(24, 3);
  boxes.triangles.bottomRows(12) = second.triangles.array() + 8;
  io::writeObj(boxes, file.string());
  const CommandResult r = run("volume " + file.string() + " halfspace --pose-a 0,0,0.009 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["in_contact"], true);
  ASSERT_EQ(j["patches"].size(), 2u);
  const double V = j["volume"].get<double>();
  // two sums of the same faces about two apexes; OBJ keeps the coordinates' digits
  EXPECT_NEAR(j["patches"][0]["volume"].get<double>() + j["patches"][1]["volume"].get<double>(), V,
              1e-12 * V);
  EXPECT_EQ(j["patches"][0]["normal"][2], 1.0);
  const CommandResult table = run("volume " + file.string() + " halfspace --pose-a 0,0,0.009");
  EXPECT_NE(table.out.find("patch 2 of 2"), std::string::npos) << table.out;
  const CommandResult apart =
      run("volume " + file.string() + " halfspace --pose-a 0,0,0.02 --json");
  const auto none = nlohmann::json::parse(apart.out);
  EXPECT_EQ(none["in_contact"], false);
  EXPECT_TRUE(none["patches"].empty());
  fs::remove(file);
}

// Two meshes take `fast`, whose exact depth pass a library query leaves out by default
// (QueryOptions::depth): `volume` asks for it, so --json and the table give the depth of a
// brick pressed 1 mm into a plate (the slab's thickness; OBJ keeps the coordinates' digits).
TEST(Cli, VolumeOfTwoMeshesGivesTheExactDepth) {
  const fs::path brick = fs::temp_directory_path() / "vcontact_cli_depth_brick.obj";
  const fs::path plate = fs::temp_directory_path() / "vcontact_cli_depth_plate.obj";
  io::writeObj(geometry::tessellateBox({0.02, 0.03, 0.01}), brick.string());
  io::writeObj(geometry::tessellateBox({0.2, 0.2, 0.05}), plate.string());
  const std::string args = "volume " + brick.string() + " " + plate.string() +
                           " --pose-a 0.003,-0.002,0.004 --pose-b 0,0,-0.025";
  const CommandResult r = run(args + " --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "fast");
  ASSERT_TRUE(j["depth"].is_number()) << r.out;
  // exact methods on one polyhedron: rounding of the placed vertices (1e-9 of d with room)
  EXPECT_NEAR(j["depth"].get<double>(), 0.001, 1e-12);
  EXPECT_NEAR(j["patches"][0]["depth"].get<double>(), 0.001, 1e-12);
  const CommandResult table = run(args);
  ASSERT_EQ(table.exitCode, 0) << table.err;
  EXPECT_NE(table.out.find("depth           0.001"), std::string::npos) << table.out;
  EXPECT_EQ(table.out.find("nan"), std::string::npos) << table.out;
  fs::remove(brick);
  fs::remove(plate);
}

TEST(Cli, BadMeshGivesOneMessageNonZeroExitAndNoOutputFile) {
  const fs::path file = fs::temp_directory_path() / "vcontact_cli_open.obj";
  const fs::path out = fs::temp_directory_path() / "vcontact_cli_should_not_exist.json";
  fs::remove(out);
  geometry::TriangleMesh open = geometry::tessellateBox({0.01, 0.01, 0.01});
  open.triangles.conservativeResize(10, 3);  // two faces missing
  io::writeObj(open, file.string());
  const CommandResult r = run("volume " + file.string() + " halfspace --out " + out.string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find(file.string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("boundary edges, mesh is not closed; first at vertex ("), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove(file);
}

TEST(Cli, UnsupportedPairNamesBothShapes) {
  const CommandResult r = run("volume sphere:1 sphere:1 --method analytic");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--method analytic: cannot compute sphere R=1 against sphere R=1"),
            std::string::npos)
      << r.err;
}

TEST(Cli, BadPoseNamesTheOption) {
  const CommandResult r = run("volume sphere:1 halfspace --pose-a 1,2");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--pose-a: a pose is"), std::string::npos) << r.err;
}

TEST(Cli, CommandLinesThatDoNotParseExitWith2) {
  // CLI11's own codes (104-114) would tell a script nothing more than "bad input" does.
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"", "A subcommand is required"},                   // no subcommand
      {"volume sphere:0.01", "B is required"},            // a missing positional
      {"friction-map --mu abc --out /dev/null", "--mu"},  // a value of the wrong type
      {"volume sphere:0.01 halfspace --no-such-flag", "--no-such-flag"},  // an unknown option
  };
  for (const auto& c : cases) {
    const CommandResult r = run(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
  }
  EXPECT_EQ(run("--version").exitCode, 0);
}

}  // namespace
}  // namespace vcontact
