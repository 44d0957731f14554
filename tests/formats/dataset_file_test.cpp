// The dataset reader (docs/DATASET.md): a good dataset reads with derived velocities
// where the file omits them; each listed defect gives its message naming file, line and
// column.

#include "formats/dataset_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "geometry/error.hpp"
#include "support/test_support.hpp"

namespace vcontact::formats {
namespace {

namespace fs = std::filesystem;

class DatasetFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / (std::string("vcontact_dataset_") +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream((dir_ / name).string()) << text;
    return (dir_ / name).string();
  }
  std::string sidecar(const std::string& extra = "", const std::string& data = "rig.csv") const {
    return write("rig.json", R"({"format": "vcontact.dataset/1", "name": "rig", "data": ")" + data +
                                 R"(", "mode": "kinematic",
      "payload": {"shape": "cylinder", "radius": 0.01, "length": 0.02},
      "plate": {"shape": "halfspace"}, "outputs": ["fz", "tz"])" +
                                 extra + "}");
  }
  // Parabolic drop x = (0, 0, 1 − t²) with constant spin 2 rad/s about z, on a
  // non-uniform time grid, plus an extra column the reader must keep.
  std::string csv(bool velocities) const {
    std::ostringstream os;
    os.precision(17);
    os << "t,x,y,z,qw,qx,qy,qz" << (velocities ? ",vx,vy,vz,wx,wy,wz" : "") << ",fz,tz,temp\n";
    double t = 0.0;
    for (int i = 0; i < 12; ++i) {
      const double half = 0.5 * 2.0 * t;  // half the rotation angle
      os << t << ",0,0," << 1 - t * t << "," << std::cos(half) << ",0,0," << std::sin(half);
      if (velocities) os << ",0,0," << -2 * t << ",0,0,2";
      os << "," << 10 + i << ",0.5," << 20 + i << "\n";
      t += 0.01 * (1 + (i % 3));  // steps of 10, 20, 30 ms
    }
    return os.str();
  }
  fs::path dir_;
};

TEST_F(DatasetFiles, ReadsSamplesAndKeepsExtraColumns) {
  write("rig.csv", csv(true));
  const DatasetReadResult r = readDataset(sidecar(R"(, "noise": {"fz": 0.1})"));
  const validation::Dataset& d = r.dataset;
  EXPECT_EQ(d.size(), 12u);
  EXPECT_EQ(d.outputs, (std::vector<std::string>{"fz", "tz"}));
  EXPECT_EQ(d.noise.at("fz"), 0.1);
  EXPECT_EQ(d.noise.count("tz"), 0u);
  EXPECT_TRUE(d.columns.count("temp"));
  EXPECT_EQ(d.measured("fz")(3), 13.0);
  EXPECT_FALSE(d.velocityFromPositions);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(std::holds_alternative<geometry::Cylinder>(d.payload));
  EXPECT_TRUE(std::holds_alternative<geometry::HalfSpace>(d.plate));
}

TEST_F(DatasetFiles, DifferentiatesMissingVelocitiesAndSaysSo) {
  write("rig.csv", csv(false));
  const DatasetReadResult r = readDataset(sidecar());
  const validation::Dataset& d = r.dataset;
  EXPECT_TRUE(d.velocityFromPositions);
  EXPECT_TRUE(d.omegaFromAttitude);
  EXPECT_EQ(r.warnings.size(), 2u);
  for (const auto& s : d.samples) {
    // The three-point stencil is exact for a parabola on any grid (rounding: ~1e-13).
    EXPECT_NEAR(s.v_BA.z(), -2 * s.t, 1e-12);
    // A constant spin is a constant relative rotation rate: exact up to rounding.
    EXPECT_NEAR(s.w_BA.z(), 2.0, 1e-9);
    EXPECT_NEAR(s.w_BA.head<2>().norm(), 0.0, 1e-12);
  }
}

std::string rejection(const std::function<void()>& f) { return test::inputErrorMessage(f); }

struct BadCsv {
  const char* name;
  std::function<std::string(std::string)> edit;  // from the good CSV
  const char* message;
};

std::string replaceFirst(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST_F(DatasetFiles, EachCsvDefectHasItsMessage) {
  const std::vector<BadCsv> cases = {
      {"missing column", [](std::string s) { return replaceFirst(s, "qz,", "q_z,"); },
       "line 1: missing required column 'qz'"},
      {"non-number", [](std::string s) { return replaceFirst(s, ",10,", ",ten,"); },
       "line 2, column 'fz': 'ten' is not a number"},
      {"nan", [](std::string s) { return replaceFirst(s, ",11,", ",nan,"); },
       "line 3, column 'fz': 'nan' is not finite"},
      {"inf", [](std::string s) { return replaceFirst(s, ",12,", ",inf,"); },
       "line 4, column 'fz': 'inf' is not finite"},
      {"time", [](std::string s) { return replaceFirst(s, "\n0.01,", "\n0,"); },
       "line 3, column 't': time 0 is not after the previous sample's 0"},
      {"quaternion",
       [](std::string s) { return replaceFirst(s, "\n0,0,0,1,1,", "\n0,0,0,1,1.1,"); },
       "line 2, columns 'qw'..'qz': quaternion length"},
      {"width", [](std::string s) { return replaceFirst(s, ",20\n", ",20,99\n"); },
       "line 2: 18 fields, but the header names 17 columns"},
      {"no wrench",
       [](std::string s) { return replaceFirst(replaceFirst(s, "fz,", "a,"), "tz,", "b,"); },
       "line 1: no wrench column"},
      {"half a velocity", [](std::string s) { return replaceFirst(s, "vy,", "vq,"); },
       "columns vx, vy, vz come together"},
      // Issue 20: named causes, physical ranges (io/input_ranges.hpp), a time step that made
      // fit and diagnose die on a signal.
      {"byte order mark", [](std::string s) { return "\xEF\xBB\xBF" + s; },
       "line 1: starts with a UTF-8 byte order mark"},
      {"decimal commas",
       [](std::string s) {
         for (char& c : s) c = c == ',' ? ';' : (c == '.' ? ',' : c);
         return s;
       },
       "line 1: columns are separated by ';'; expected ',' and numbers with a decimal point"},
      {"position beyond the workspace",
       [](std::string s) { return replaceFirst(s, "\n0,0,0,", "\n0,1e308,0,"); },
       "line 2, column 'x': 1e+308 is beyond +-1000 m"},
      {"force beyond range", [](std::string s) { return replaceFirst(s, ",10,", ",1e300,"); },
       "line 2, column 'fz': 1e+300 is beyond +-1e+09 N"},
      {"time step below a nanosecond",
       [](std::string s) { return replaceFirst(s, "\n0.01,", "\n1e-12,"); },
       "line 3, column 't': time step 1e-12 s is below 1e-09 s"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string csvPath = write("rig.csv", c.edit(csv(true)));
    const std::string msg = rejection([&] { readDataset(sidecar()); });
    EXPECT_EQ(msg.rfind(csvPath + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(c.message), std::string::npos) << msg;
  }
}

// Velocities differentiated from rows close in time are held to a velocity column's bounds: a
// 1 mm step in 1 ns gave 1e6 m/s (issue 36).
TEST_F(DatasetFiles, ImpossibleDifferentiatedSpeedsNameTheLine) {
  write("rig.csv", replaceFirst(csv(false), "\n0.01,0,0,", "\n1e-9,0,0.001,"));
  const std::string msg = rejection([&] { readDataset(sidecar()); });
  EXPECT_NE(msg.find("rig.csv: line 2: speed differentiated from x, y, z "), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("m/s; expected at most 1000 m/s (rows too close in time, or a jump in the "
                     "motion)"),
            std::string::npos)
      << msg;
}

TEST_F(DatasetFiles, EachSidecarDefectHasItsMessage) {
  write("rig.csv", csv(true));
  const std::string path = (dir_ / "rig.json").string();
  EXPECT_NE(rejection([&] {
              readDataset(write("rig.json", "{\"format\": "));
            }).find(path + ": not valid JSON"),
            std::string::npos);
  EXPECT_NE(rejection([&] {
              readDataset(sidecar("", "gone.csv"));
            }).find("data file \"gone.csv\" not found"),
            std::string::npos);
  EXPECT_NE(rejection([&] { readDataset((dir_ / "nothing.json").string()); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(rejection([&] {
              readDataset(sidecar(R"(, "noise": {"fx": 0.1})"));
            }).find("noise: \"fx\" is not one of the outputs"),
            std::string::npos);
  EXPECT_NE(rejection([&] {
              readDataset(sidecar(R"(, "noise": {"fz": -1})"));
            }).find("must be a positive number"),
            std::string::npos);
  const std::string wrongFormat = write(
      "v2.json", R"({"format": "vcontact.dataset/2", "data": "rig.csv", "mode": "kinematic"})");
  EXPECT_NE(
      rejection([&] { readDataset(wrongFormat); }).find("format must be \"vcontact.dataset/1\""),
      std::string::npos);
  const std::string otherMode = write(
      "dyn.json", R"({"format": "vcontact.dataset/1", "data": "rig.csv", "mode": "sideways"})");
  EXPECT_NE(
      rejection([&] { readDataset(otherMode); }).find("mode must be \"kinematic\" or \"dynamic\""),
      std::string::npos);
  const std::string badShape = write("shape.json", R"({"format": "vcontact.dataset/1",
      "data": "rig.csv", "mode": "kinematic", "payload": {"shape": "cone"},
      "plate": {"shape": "halfspace"}, "outputs": ["fz"]})");
  EXPECT_NE(rejection([&] { readDataset(badShape); }).find("payload: unknown shape \"cone\""),
            std::string::npos);
  const std::string missingMesh = write("mesh.json", R"({"format": "vcontact.dataset/1",
      "data": "rig.csv", "mode": "kinematic", "payload": {"mesh": "part.stl"},
      "plate": {"shape": "halfspace"}, "outputs": ["fz"]})");
  // Named by the sidecar and its field (issue 36), not only by the mesh's path.
  const std::string noMesh = rejection([&] { readDataset(missingMesh); });
  EXPECT_EQ(noMesh.rfind((dir_ / "mesh.json").string() +
                             ": payload: \"mesh\": \"part.stl\": no such file (looked for " +
                             (dir_ / "part.stl").string() + ")",
                         0),
            0u)
      << noMesh;
  EXPECT_NE(rejection([&] { readDataset(sidecar(R"(, "outputs": ["fx"])")); }).size(), 0u);
}

}  // namespace
}  // namespace vcontact::formats
