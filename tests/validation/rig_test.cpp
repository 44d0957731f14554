// Issue 15 item 3: rig findings that need more than a per-sample correction: the payload's own
// inertia (m·a, I·α) when the sidecar gives mass and inertia, and a lag of a fraction of a
// sample between the motion and the force columns. Records made here with the synth generator
// (rigMotion + synthesizeMeasurement, as `vcontact synth` does).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>

#include "formats/dataset_file.hpp"
#include "geometry/error.hpp"
#include "validation/diagnose.hpp"
#include "validation/effect_cases.hpp"

namespace vcontact::validation {
namespace {

// A fitted value within 3 standard errors of the truth: a 99.7 % band for a Gaussian estimate.
constexpr double kStdErrors = 3.0;

// The drive record's punch (20 nm deep) swayed along x instead, 2 mm at 4 Hz
// (a = −A ω² sin ωt), read by a load cell between the drive and a payload carriage of `mass`.
Dataset swayingDrive(std::size_t n, double mass) {
  Dataset d = rigMotion("drive", n);
  constexpr double A = 2e-3, w = 2.0 * std::numbers::pi * 4.0;  // m, rad/s
  for (std::size_t i = 0; i < n; ++i) {
    Sample& s = d.samples[i];
    const auto k = static_cast<Eigen::Index>(i);
    s.X_BA.translation().x() = A * std::sin(w * s.t);
    s.v_BA.x() = A * w * std::cos(w * s.t);
    d.columns["x"][k] = s.X_BA.translation().x();
    d.columns["vx"][k] = s.v_BA.x();
  }
  d.inertia =
      PayloadInertia{mass, Eigen::Vector3d(1e-4, 1e-4, 2e-4).asDiagonal(), Eigen::Vector3d::Zero()};
  return d;
}

// The force columns hold the load cell's reading, the plate's force minus m·a (the force that
// accelerates the payload): the payload's inertia is left in them.
TEST(Rig, PayloadInertiaLeftInTheForceColumnIsARigFinding) {
  constexpr double mass = 0.5;  // kg
  const std::vector<std::string> effects = {"stiffness", "coulomb"};
  Dataset d = swayingDrive(600, mass);
  synthesizeMeasurement(d, test::trueModel(effects), 9);
  constexpr double A = 2e-3, w = 2.0 * std::numbers::pi * 4.0;
  Eigen::VectorXd ma(static_cast<Eigen::Index>(d.size()));  // exact, not differentiated
  for (std::size_t i = 0; i < d.size(); ++i)
    ma[static_cast<Eigen::Index>(i)] = -mass * A * w * w * std::sin(w * d.samples[i].t);
  d.columns["fx"] -= ma;
  // away from the two end samples (one-sided there), the differentiated inertial force matches
  // the exact one to the central difference's relative error (ω h)²/6 = 0.3 % at h = 5 ms
  // (1 % allowed)
  const Eigen::Index inner = ma.size() - 2;
  EXPECT_LT((inertialWrench(d).at("fx") - ma).segment(1, inner).cwiseAbs().maxCoeff(),
            0.01 * ma.cwiseAbs().maxCoeff());

  const Diagnosis r = diagnose(d, noiseLevels(d), test::startModel(effects, ""));
  const DiagnosisStage& s = r.stages.front();
  std::cout << "verdict: " << s.verdict << '\n';
  EXPECT_EQ(s.kind, "rig") << s.verdict;
  ASSERT_FALSE(s.rig.empty());
  EXPECT_EQ(s.rig.front().kind, "inertia") << s.rig.front().text;
  // k's standard error is 1/sqrt(Σ (m a/σ)²); the stencil adds its 0.3 % bias
  const double sigma = noiseLevels(d).at("fx").sigma;
  const double se = sigma / ma.norm();
  EXPECT_NEAR(s.rig.front().value, -1.0, kStdErrors * se + 0.003) << s.rig.front().text;
  EXPECT_NE(s.verdict.find("payload inertia"), std::string::npos) << s.verdict;
}

TEST(Rig, WithoutMassAndInertiaThereIsNoInertiaCandidate) {
  Dataset d = swayingDrive(300, 0.5);
  d.inertia.reset();
  synthesizeMeasurement(d, test::trueModel({"stiffness", "coulomb"}), 3);
  Replayer replayer(d);
  const Comparison c =
      compare(d, replayer.run(test::trueModel({"stiffness", "coulomb"})), noiseLevels(d));
  for (const auto& f : rigCandidates(d, c)) EXPECT_NE(f.kind, "inertia");
}

// The loading record whose force columns lag the motion by 2.5 samples: made exactly on a grid
// twice as fine (the force of fine sample 2i beside the motion of fine sample 2i + 5).
TEST(Rig, ALagOfTwoAndAHalfSamplesIsRecoveredAsAFraction) {
  const std::vector<std::string> effects = {"stiffness"};
  constexpr std::size_t m = 300;
  Dataset fine = rigMotion("loading", 2 * (m + 3) - 1);
  synthesizeMeasurement(fine, test::trueModel(effects), 4);
  Dataset d = fine;
  d.samples.resize(m);
  for (auto& [name, column] : d.columns) column.resize(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    d.samples[i] = fine.samples[2 * i + 5];
    d.samples[i].t = fine.samples[2 * i].t;
    for (auto& [name, column] : d.columns) {
      const bool force = std::find(d.outputs.begin(), d.outputs.end(), name) != d.outputs.end();
      column[k] = fine.columns.at(name)[force || name == "t" ? 2 * k : 2 * k + 5];
    }
  }
  const double h = d.samples[1].t - d.samples[0].t;
  const Diagnosis r = diagnose(d, noiseLevels(d), test::startModel(effects, ""));
  const DiagnosisStage& s = r.stages.front();
  std::cout << "verdict: " << s.verdict << '\n';
  EXPECT_EQ(s.kind, "rig") << s.verdict;
  ASSERT_FALSE(s.rig.empty());
  ASSERT_EQ(s.rig.front().kind, "lag") << s.rig.front().text;
  // τ's standard error is 1/sqrt(Σ (ŷ'/σ)²) in samples (ŷ' per sample), below 1e-3 sample
  // here; the cubic interpolation across the two kinks where contact starts and ends and the
  // golden-section stop (1e-3 sample) bound the rest: 0.05 sample allowed.
  double slope2 = 0.0;
  for (const auto& o : d.outputs) {
    const Eigen::VectorXd& y = d.measured(o);
    const double sigma = noiseLevels(d).at(o).sigma;
    for (Eigen::Index i = 1; i < y.size(); ++i) slope2 += std::pow((y[i] - y[i - 1]) / sigma, 2);
  }
  EXPECT_LT(kStdErrors / std::sqrt(slope2), 0.01);
  EXPECT_NEAR(s.rig.front().value / h, 2.5, 0.05) << s.rig.front().text;
}

// payload_inertia in the sidecar: read, written back, and a bad entry named.
TEST(Rig, SidecarPayloadInertiaIsReadAndChecked) {
  const auto dir = std::filesystem::temp_directory_path() / "vcontact_rig_test";
  std::filesystem::create_directories(dir);
  Dataset d = swayingDrive(50, 0.25);
  d.inertia->com = Eigen::Vector3d(0.0, 0.0, 0.002);
  synthesizeMeasurement(d, test::trueModel({"stiffness", "coulomb"}), 1);
  const std::string path = (dir / "sway.json").string();
  formats::writeDataset(d, path);
  const Dataset back = formats::readDataset(path).dataset;
  ASSERT_TRUE(back.inertia.has_value());
  EXPECT_EQ(back.inertia->mass, 0.25);
  EXPECT_EQ(back.inertia->inertia, d.inertia->inertia);
  EXPECT_EQ(back.inertia->com, d.inertia->com);

  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto at = text.find("\"mass\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 6, "\"weight\"");
  std::ofstream(dir / "bad.json") << text;
  try {
    formats::readDataset((dir / "bad.json").string());
    ADD_FAILURE() << "a payload_inertia without mass was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("payload_inertia must be an object with \"mass\""),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vcontact::validation
