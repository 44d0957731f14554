// vcontact synth for any payload and motion (issue 15, item 5), diagnose --candidates and
// expression effects as a user runs them: a mesh payload replays the record of the exact
// primitive within the polygon's area deficit; a motion CSV is followed sample by sample;
// --noise-scale 0 writes an exact record; a bad formula exits 2 naming file, key and character.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "formats/dataset_file.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "support/run_command.hpp"
#include "support/scratch_dir.hpp"
#include "validation/load_varying_drive.hpp"

namespace vcontact {
namespace {

namespace fs = std::filesystem;

const char* kTruth = R"({"format": "vcontact.model/1",
  "effects": {"stiffness": {"kv": 4.2e12}, "coulomb": {"mu": 0.15, "v_s": 1.5e-3}}})";

// The expression effect mu_load (μ(f_n) = μ_C + b f_n) with b = `b` 1/N.
std::string muLoadEntry(const std::string& b) {
  return R"({"kind": "expression",
  "parameters": {"b": {"value": )" +
         b + R"(, "unit": "1/N", "lower": 0, "upper": 1}},
  "tangential": "-b*f_n^2", "requires": ["stiffness", "coulomb"]})";
}

class SynthCli : public ::testing::Test {
 public:
  void SetUp() override { write("truth.model.json", kTruth); }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  test::CommandResult run(const std::string& args) const {
    return test::runCommand(std::string(VCONTACT_BINARY) + " " + args, dir_ / "stderr.txt");
  }
  validation::Dataset read(const std::string& name) const {
    return formats::readDataset(path(name)).dataset;
  }

  // The load-varying drive as a motion CSV (t, pose, velocities).
  void writeMotion(const std::string& name, std::size_t n) const {
    const validation::Dataset d = test::loadVaryingDrive(n);
    std::ofstream out(dir_ / name);
    out.precision(17);
    const char* cols[] = {"t",  "x",  "y",  "z",  "qw", "qx", "qy",
                          "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
    for (int c = 0; c < 14; ++c) out << (c ? "," : "") << cols[c];
    out << '\n';
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(n); ++i) {
      for (int c = 0; c < 14; ++c) out << (c ? "," : "") << d.columns.at(cols[c])[i];
      out << '\n';
    }
  }

  test::ScratchDir scratch_{"synth_cli"};
  const fs::path& dir_ = scratch_.path();
};

TEST_F(SynthCli, NoiseScaleZeroWritesAnExactRecord) {
  const std::string base = "synth --profile drive --samples 100 --noise-scale 0 --model " +
                           path("truth.model.json") + " --out ";
  ASSERT_EQ(run(base + path("a.json") + " --seed 1").exitCode, 0);
  ASSERT_EQ(run(base + path("b.json") + " --seed 2").exitCode, 0);
  const validation::Dataset a = read("a.json"), b = read("b.json");
  EXPECT_TRUE(a.noise.empty());
  EXPECT_EQ(a.measured("fz"), b.measured("fz"));  // no noise: the seed changes nothing
  EXPECT_GT(a.measured("fz").maxCoeff(), 1.0);    // and the record is not empty
}

// A 256-sided prism (R = 10 mm, L = 20 mm, written in mm so that the face at z = −10 mm is
// exact in the STL's float32) against the exact cylinder of the drive profile. Flat on the
// plate, the contact volume is area × depth, and the polygon's area falls short of the
// circle's by e = 1 − (N/2π) sin(2π/N) = 1.0037e-4: every force of the mesh record is
// (1 − e) times the primitive's, to float32 rounding of the vertices (1e-7 relative).
TEST_F(SynthCli, AMeshPayloadReplaysThePrimitiveRecord) {
  constexpr int kSides = 256;
  io::writeStl(geometry::tessellateCylinder(10.0, 20.0, kSides), path("punch.stl"));
  const std::string base =
      "synth --profile drive --samples 150 --noise-scale 0 --model " + path("truth.model.json");
  ASSERT_EQ(run(base + " --out " + path("exact.json")).exitCode, 0);
  const auto r = run(base + " --payload " + path("punch.stl") + " --payload-scale mm --out " +
                     path("mesh.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const validation::Dataset exact = read("exact.json"), mesh = read("mesh.json");
  EXPECT_TRUE(std::holds_alternative<geometry::Mesh>(mesh.payload));
  const double e =
      1.0 - kSides / (2.0 * std::numbers::pi) * std::sin(2.0 * std::numbers::pi / kSides);
  for (const char* o : {"fx", "fz"}) {
    const Eigen::VectorXd& y = exact.measured(o);
    const double scale = y.cwiseAbs().maxCoeff();
    EXPECT_LT((mesh.measured(o) - (1.0 - e) * y).cwiseAbs().maxCoeff(), 1e-6 * scale) << o;
    EXPECT_GT((mesh.measured(o) - y).cwiseAbs().maxCoeff(), 0.5 * e * scale)
        << o;  // not the same file
  }
}

// Flat punch, stiffness only: f_z = kv π R² (depth), depth = 0.01 − z of the motion CSV.
TEST_F(SynthCli, AMotionCsvIsFollowedSampleBySample) {
  writeMotion("motion.csv", 120);
  const auto r = run("synth --profile drive --noise-scale 0 --motion " + path("motion.csv") +
                     " --model " + path("truth.model.json") + " --out " + path("m.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const validation::Dataset d = read("m.json");
  ASSERT_EQ(d.size(), 120u);
  const validation::Dataset motion = test::loadVaryingDrive(120);
  const double area = std::numbers::pi * 0.01 * 0.01;
  for (Eigen::Index i = 0; i < 120; ++i) {
    EXPECT_EQ(d.columns.at("z")[i], motion.columns.at("z")[i]);
    const double depth = 0.01 - motion.columns.at("z")[i];
    EXPECT_NEAR(d.measured("fz")[i], 4.2e12 * area * depth, 1e-9 * 4.2e12 * area * depth);
  }
  write("bad.csv", "t,x,y,qw,qx,qy,qz\n0,0,0,1,0,0,0\n");
  const std::string bad = "synth --profile drive --motion " + path("bad.csv") + " --model " +
                          path("truth.model.json") + " --out ";
  const auto missing = run(bad + path("other.json"));
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("bad.csv: line 1: missing required column 'z'"), std::string::npos)
      << missing.err;
  // --out bad.json would write bad.csv over the motion it reads.
  const auto overwrite = run(bad + path("bad.json"));
  EXPECT_EQ(overwrite.exitCode, 2);
  EXPECT_NE(overwrite.err.find("bad.csv, which is the motion CSV"), std::string::npos)
      << overwrite.err;
}

TEST_F(SynthCli, DiagnoseWithCandidatesNamesTheHiddenExpression) {
  write("hidden.model.json", R"({"format": "vcontact.model/1", "effects": {
    "stiffness": {"kv": 4.2e12}, "coulomb": {"mu": 0.15, "v_s": 1.5e-3}, "mu_load": )" +
                                 muLoadEntry("5e-4") + "}}");
  write("bare.model.json", R"({"format": "vcontact.model/1",
    "effects": {"stiffness": {}, "coulomb": {}}})");
  write("candidates.json", R"({"format": "vcontact.candidates/1",
    "candidates": {"viscous": {}, "stribeck": {}, "mu_load": )" +
                               muLoadEntry("0") + "}}");
  writeMotion("motion.csv", 400);
  ASSERT_EQ(run("synth --profile drive --motion " + path("motion.csv") + " --model " +
                path("hidden.model.json") + " --out " + path("rec.json"))
                .exitCode,
            0);
  const auto r = run("diagnose " + path("rec.json") + " --model " + path("bare.model.json") +
                     " --candidates " + path("candidates.json") + " --out " + path("out"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("verdict: mu_load"), std::string::npos) << r.out;
}

TEST_F(SynthCli, ABadFormulaExitsTwoNamingFileKeyAndCharacter) {
  write("bad.model.json", R"({"format": "vcontact.model/1", "effects": {"stiffness": {},
    "coulomb": {}, "mu_load": {"kind": "expression", "tangential": "-b*f_n^2",
    "parameters": {"c": {"value": 0, "unit": "1/N", "lower": 0, "upper": 1}}}}})");
  const auto r =
      run("synth --profile drive --model " + path("bad.model.json") + " --out " + path("x.json"));
  EXPECT_EQ(r.exitCode, 2);
  // "b" is not a parameter (the file names "c"): muparser stops at character 2.
  EXPECT_NE(r.err.find("bad.model.json: effects.mu_load.tangential: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at character 2 of \"-b*f_n^2\""), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

}  // namespace
}  // namespace vcontact
