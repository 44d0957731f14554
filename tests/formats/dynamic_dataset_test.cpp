// Dynamic datasets (docs/DATASET.md, "Dynamic datasets"): a record of a free payload's poses.
// A good one reads with its mass properties; each bad input the format lists stops the read
// with a message naming the file and the place.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "formats/dataset_file.hpp"
#include "geometry/error.hpp"
#include "support/scratch_dir.hpp"

namespace vcontact::formats {
namespace {

// A 0.1 m cube dropped from 0.3 m with a spin about z: free flight (z = 0.3 − g t²/2) for the
// first 0.2 s at 100 Hz, every sample far above the plate; `rows` edits the CSV's lines.
std::string tossCsv(bool velocities, double z0 = 0.3) {
  std::ostringstream os;
  os.precision(17);
  os << "t,x,y,z,qw,qx,qy,qz" << (velocities ? ",vx,vy,vz,wx,wy,wz" : "") << "\n";
  for (int i = 0; i <= 20; ++i) {
    const double t = 0.01 * i;
    os << t << ",0,0," << z0 - 0.5 * 9.81 * t * t << "," << std::cos(t) << ",0,0," << std::sin(t);
    if (velocities) os << ",0,0," << -9.81 * t << ",0,0,2";
    os << "\n";
  }
  return os.str();
}

class DynamicDataset : public ::testing::Test {
 protected:
  test::ScratchDir dir_{"dynamic_dataset"};
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream((dir_ / name).string()) << text;
    return (dir_ / name).string();
  }
  std::string sidecar(const std::string& inertia =
                          R"("payload_inertia": {"mass": 0.37, "inertia": [6e-4, 6e-4, 6e-4]})",
                      const std::string& extra = "") const {
    return write("toss.json", R"({"format": "vcontact.dataset/1", "data": "toss.csv",
      "mode": "dynamic", "payload": {"shape": "box", "size": [0.1, 0.1, 0.1]},
      "plate": {"shape": "halfspace"}, "outputs": ["position", "attitude"],
      "noise": {"position": 0.001, "attitude": 0.01}, )" +
                                  inertia + extra + "}");
  }
  static std::string rejection(const std::string& path) {
    try {
      readDataset(path);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(DynamicDataset, ReadsPosesMassFromDensityAndThePlatePose) {
  write("toss.csv", tossCsv(true));
  const auto r = readDataset(
      sidecar(R"("payload_inertia": {"density": 1000})", R"(, "plate_pose": [0, 0, -0.001])"));
  const auto& d = r.dataset;
  EXPECT_EQ(d.mode, validation::DatasetMode::kDynamic);
  ASSERT_TRUE(d.inertia.has_value());
  EXPECT_NEAR(d.inertia->mass, 1.0, 1e-12);                       // 1000 kg/m³ × 1e-3 m³
  EXPECT_NEAR(d.inertia->inertia(0, 0), 1.0 * 0.02 / 12, 1e-15);  // m (b² + c²) / 12
  EXPECT_NEAR(d.X_BP.translation().z(), -0.001, 1e-15);
  EXPECT_EQ(d.size(), 21u);
  EXPECT_DOUBLE_EQ(d.noise.at("position"), 0.001);
  EXPECT_FALSE(d.velocityFromPositions);
}

TEST_F(DynamicDataset, WritesWhatItReads) {
  write("toss.csv", tossCsv(true));
  auto d = readDataset(sidecar()).dataset;
  const std::string copy = (dir_ / "copy.json").string();
  writeDataset(d, copy);
  const auto again = readDataset(copy).dataset;
  EXPECT_EQ(again.mode, validation::DatasetMode::kDynamic);
  EXPECT_EQ(again.outputs, d.outputs);
  EXPECT_DOUBLE_EQ(again.inertia->mass, 0.37);
  EXPECT_DOUBLE_EQ(again.samples.back().X_BA.translation().z(),
                   d.samples.back().X_BA.translation().z());
}

// The first sample already touches the plate and no velocity is given: no free flight to
// estimate a state from.
TEST_F(DynamicDataset, RefusesAStartInContactWithoutVelocities) {
  write("toss.csv", tossCsv(false, 0.049));
  const std::string message = rejection(sidecar());
  EXPECT_NE(message.find("toss.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("touches the plate at sample 1"), std::string::npos) << message;
  // with the velocities it is a valid record (the state is the first sample's)
  write("toss.csv", tossCsv(true, 0.049));
  EXPECT_NO_THROW(readDataset(sidecar()));
}

TEST_F(DynamicDataset, RefusesANonUnitQuaternion) {
  std::string csv = tossCsv(true);
  const auto at = csv.find('\n', csv.find('\n') + 1) + 1;  // the second sample's row
  csv.replace(at, csv.find('\n', at) - at, "0.01,0,0,0.3,2,0,0,0,0,0,0,0,0,2");
  write("toss.csv", csv);
  const std::string message = rejection(sidecar());
  EXPECT_NE(message.find("line 3, columns 'qw'..'qz': quaternion length 2"), std::string::npos)
      << message;
}

TEST_F(DynamicDataset, RefusesANaNQuaternion) {
  std::string csv = tossCsv(true);
  const auto at = csv.find('\n', csv.find('\n') + 1) + 1;
  csv.replace(at, csv.find('\n', at) - at, "0.01,0,0,0.3,nan,0,0,0,0,0,0,0,0,2");
  write("toss.csv", csv);
  const std::string message = rejection(sidecar());
  EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  EXPECT_NE(message.find("qw"), std::string::npos) << message;
}

TEST_F(DynamicDataset, RefusesTimeThatDoesNotIncrease) {
  std::string csv = tossCsv(true);
  const auto at = csv.find('\n', csv.find('\n') + 1) + 1;
  csv.replace(at, 4, "0.00");  // the second sample at t = 0 again
  write("toss.csv", csv);
  EXPECT_NE(rejection(sidecar()).find("time must increase strictly"), std::string::npos);
}

TEST_F(DynamicDataset, RefusesAPayloadWithoutMass) {
  write("toss.csv", tossCsv(true));
  const std::string message = rejection(sidecar(R"("name": "toss")"));
  EXPECT_NE(message.find("toss.json"), std::string::npos) << message;
  EXPECT_NE(message.find("needs its mass"), std::string::npos) << message;
  EXPECT_NE(rejection(sidecar(R"("payload_inertia": {"density": -2})")).find("density"),
            std::string::npos);
}

TEST_F(DynamicDataset, RefusesWrenchOutputs) {
  write("toss.csv", tossCsv(true));
  const std::string path = write("w.json", R"({"format": "vcontact.dataset/1", "data": "toss.csv",
      "mode": "dynamic", "payload": {"shape": "box", "size": [0.1, 0.1, 0.1]},
      "plate": {"shape": "halfspace"}, "outputs": ["fz"],
      "payload_inertia": {"density": 1000}})");
  EXPECT_NE(rejection(path).find("outputs: \"fz\" is not \"position\" or \"attitude\""),
            std::string::npos);
}

}  // namespace
}  // namespace vcontact::formats
