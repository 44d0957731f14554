// A dataset payload's "surface": "recovered" (docs/DATASET.md): the key's checks, and a replay
// of a ball pressed into the plate on the 2,000-triangle mesh's recovered sphere against the
// same record with the analytic sphere as payload.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "formats/dataset_file.hpp"
#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "validation/replay.hpp"
#include "volume/recovered/recovered_surface.hpp"

namespace vcontact::formats {
namespace {

namespace fs = std::filesystem;

const std::string kBall2k = std::string(VCONTACT_ASSETS_DIR) + "/meshes/ball_r10mm_2k.stl";
constexpr double kR = 0.01;  // m, the radius the mesh was tessellated at

class DatasetSurface : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / (std::string("vcontact_dataset_surface_") +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    // The ball's centre descends at 1 mm/s from first touch to d = 20 µm (d/R = 2e-3).
    std::ofstream csv((dir_ / "press.csv").string());
    csv.precision(17);
    csv << "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fz\n";
    for (int i = 0; i <= 20; ++i) {
      const double t = 1e-3 * i;
      csv << t << ",0,0," << kR - 1e-3 * t << ",1,0,0,0,0,0,-1e-3,0,0,0,1\n";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string sidecar(const std::string& payload) const {
    const std::string path = (dir_ / "press.json").string();
    std::ofstream(path) << R"({"format": "vcontact.dataset/1", "data": "press.csv",
      "mode": "kinematic", "plate": {"shape": "halfspace"}, "outputs": ["fz"],
      "payload": )" << payload
                        << "}";
    return path;
  }
  std::string meshPayload(const std::string& surface) const {
    return R"({"mesh": ")" + kBall2k + R"(", "surface": )" + surface + "}";
  }
  std::string errorOf(const std::string& payload) const {
    try {
      readDataset(sidecar(payload));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  Eigen::VectorXd fz(const validation::Dataset& d) const {
    const dynamics::Model model =
        modelFromJson(nlohmann::json::parse(R"({"format": "vcontact.model/1",
                                  "effects": {"stiffness": {"kv": 5.17e12}}})"),
                      "model", "");
    validation::Replayer replayer(d);
    return replayer.run(model).column("fz");
  }
  fs::path dir_;
};

TEST_F(DatasetSurface, AnUnknownRepresentationNamesThePayloadAndTheChoices) {
  const std::string e = errorOf(meshPayload("\"exact\""));
  EXPECT_NE(e.find("press.json: payload"), std::string::npos) << e;
  EXPECT_NE(e.find("\"surface\" must be \"mesh\""), std::string::npos) << e;
}

TEST_F(DatasetSurface, RecoveredIsRefusedOnAPrimitivePayload) {
  const std::string e = errorOf(R"({"shape": "sphere", "radius": 0.01, "surface": "recovered"})");
  EXPECT_NE(e.find("applies to a mesh payload; a sphere"), std::string::npos) << e;
}

TEST_F(DatasetSurface, MeshIsTheDefault) {
  EXPECT_EQ(readDataset(sidecar(meshPayload("\"mesh\""))).dataset.payload_surface, nullptr);
  EXPECT_NE(readDataset(sidecar(meshPayload("\"recovered\""))).dataset.payload_surface, nullptr);
}

// f_z = kv V (MODEL.md §5 for V). The recovered sphere lies within δ of the true one (the
// fit's largest vertex residual plus the STL's single-precision rounding of 10 mm), so at
// depth d its V differs by at most the relative (1 + δ/d)² − 1 ≈ 2δ/d: checked from d = 1 µm.
TEST_F(DatasetSurface, ReplayOnTheRecoveredSphereMatchesTheAnalyticPayload) {
  const DatasetReadResult recovered = readDataset(sidecar(meshPayload("\"recovered\"")));
  const Eigen::VectorXd onSurface = fz(recovered.dataset);
  const Eigen::VectorXd sphere =
      fz(readDataset(sidecar(R"({"shape": "sphere", "radius": 0.01})")).dataset);
  const Eigen::VectorXd polyhedron = fz(readDataset(sidecar(meshPayload("\"mesh\""))).dataset);
  const double delta = recovered.dataset.payload_surface->recognition.surfaces.at(0).max_residual +
                       kR * std::ldexp(1.0, -24);
  int checked = 0;
  for (int i = 1; i < sphere.size(); ++i) {
    const double d = 1e-6 * i;  // m, the record's depth at sample i
    const double kv = 5.17e12, V = M_PI * d * d * (3 * kR - d) / 3;
    EXPECT_NEAR(sphere[i], kv * V, 1e-9 * kv * V) << i;  // the analytic payload: closed form
    EXPECT_NEAR(onSurface[i], sphere[i], (std::pow(1 + delta / d, 2) - 1) * sphere[i]) << i;
    // the polyhedron's pole vertex is down: a cone of chords, far short of the cap
    EXPECT_LT(polyhedron[i], 0.5 * sphere[i]) << i;
    ++checked;
  }
  EXPECT_EQ(checked, 20);
}

}  // namespace
}  // namespace vcontact::formats
