// Shape and pose text forms: what parses, and the message for what does not.

#include "io/shape_spec.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "support/test_support.hpp"

namespace vcontact::io {
namespace {

std::string rejection(const std::function<void()>& f) { return test::inputErrorMessage(f); }

TEST(ShapeSpec, Primitives) {
  EXPECT_DOUBLE_EQ(std::get<geometry::Sphere>(parseShape("sphere:0.01", "A").shape).radius, 0.01);
  const auto c = std::get<geometry::Cylinder>(parseShape("cylinder:0.01,0.02", "A").shape);
  EXPECT_DOUBLE_EQ(c.length, 0.02);
  const auto b = std::get<geometry::Box>(parseShape("box:1,2,3", "A").shape);
  EXPECT_EQ(b.size, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(std::holds_alternative<geometry::HalfSpace>(parseShape("halfspace", "A").shape));
}

TEST(ShapeSpec, BadShapesNameTheSourceAndTheExpectedForm) {
  EXPECT_EQ(rejection([] { parseShape("sphere:-1", "A"); }),
            "A: sphere radius must be a finite positive length in metres, got -1");
  EXPECT_EQ(rejection([] { parseShape("cylinder:1", "B"); }),
            "B: expected cylinder:R,L, got 'cylinder:1'");
  EXPECT_EQ(rejection([] { parseShape("box:1,x,3", "A"); }),
            "A: 'x' in '1,x,3' is not a number (expected a decimal such as 0.01 or 1e-3)");
  EXPECT_EQ(rejection([] { parseShape("sphere:nan", "A"); }),
            "A: 'nan' in 'nan' is not a number (expected a decimal such as 0.01 or 1e-3)");
}

// Issue 20: hex, trailing text, an empty item (a trailing comma), nan and inf were read.
TEST(ShapeSpec, NumbersAreDecimalsWithNothingAround) {
  for (const char* text : {"0x1p-4", "0x10", "0.01m", "1,", ",1", "1,,2", "nan", "inf", "-inf",
                           "1e", "e3", ".", "+-1", "1 2", "1e+", "0.5.5", "", "1;2"}) {
    EXPECT_NE(rejection([&] { parseNumberList(text, "--x"); }).find("is not a number"),
              std::string::npos)
        << text;
  }
  EXPECT_NE(rejection([] { parseNumberList("1e400", "--x"); }).find("beyond the range of a double"),
            std::string::npos);
  EXPECT_EQ(parseNumberList(" +1.5e-3 , -2 ,.5, 3.", "--x"),
            (std::vector<double>{1.5e-3, -2.0, 0.5, 3.0}));
  EXPECT_EQ(parseNumberList("1e-400", "--x"), std::vector<double>{0.0});  // underflow is zero
}

// io/input_ranges.hpp: lengths in [1e-6, 1e3] m; 1e-300 gave a volume of 0, 1e300 infinity.
TEST(ShapeSpec, LengthsOutsideThePhysicalRangeAreRefused) {
  for (const char* text :
       {"sphere:1e-300", "sphere:1e300", "sphere:2e3", "cylinder:0.01,5e-7", "box:1,1,1001"}) {
    EXPECT_NE(rejection([&] { parseShape(text, "A"); }).find("in [1e-06, 1000] m"),
              std::string::npos)
        << text;
  }
  EXPECT_NO_THROW(parseShape("sphere:1e-6", "A"));
  EXPECT_NO_THROW(parseShape("box:1000,1e-6,1", "A"));
}

TEST(Pose, TranslationRpyAndQuaternionForms) {
  const Eigen::Isometry3d t = parsePose("1,2,3", "--pose-a");
  EXPECT_EQ(t.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(t.linear().isIdentity());
  const Eigen::Isometry3d r = parsePose("0,0,0,0,0,90", "--pose-a");
  EXPECT_TRUE((r.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-15));
  const double h = std::sqrt(0.5);
  const Eigen::Isometry3d q =
      parsePose("0,0,0," + std::to_string(h) + ",0," + std::to_string(h) + ",0", "--pose-a");
  EXPECT_TRUE((q.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX(), 1e-6));
}

TEST(Pose, BadPoses) {
  EXPECT_NE(rejection([] {
              parsePose("1,2", "--pose-b");
            }).find("--pose-b: a pose is x,y,z or x,y,z,roll,pitch,yaw"),
            std::string::npos);
  EXPECT_NE(rejection([] {
              parsePose("0,0,0,1,1,0,0", "--pose-b");
            }).find("quaternion (w, x, y, z) must be unit length"),
            std::string::npos);
  EXPECT_NE(rejection([] { parsePose("0,0,inf", "--pose-b"); }).find("not a number"),
            std::string::npos);
}

// Positions within +-1000 m and angles within one turn (io/input_ranges.hpp).
TEST(Pose, ValuesBeyondTheWorkspaceOrATurnAreRefused) {
  EXPECT_EQ(rejection([] { parsePose("0,1e4,0", "--pose-a"); }),
            "--pose-a: y = 10000 is beyond +-1000 m (the workspace)");
  EXPECT_EQ(rejection([] { parsePose("0,0,0,0,0,-361", "--pose-a"); }),
            "--pose-a: yaw = -361 is beyond +-360 degrees (one turn)");
  EXPECT_NO_THROW(parsePose("-1000,1000,0,360,-360,0", "--pose-a"));
  EXPECT_NO_THROW(parsePose("0,0,0,1,0,0,0", "--pose-a"));
}

class MeshText : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("vcontact_shape_spec_" +
            std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "a@b");
    // The part in millimetres (30 x 50 x 70), a number a float holds exactly.
    TriangleMesh mm = geometry::tessellateBox({30, 50, 70});
    writeObj(mm, (dir_ / "part.obj").string());
    writeObj(mm, (dir_ / "a@b" / "part.obj").string());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  const geometry::TriangleMesh& mesh(const ParsedShape& s) {
    return *std::get<geometry::Mesh>(s.shape).mesh;
  }
  std::filesystem::path dir_;
  using TriangleMesh = geometry::TriangleMesh;
};

TEST_F(MeshText, UnitNameEqualsItsFactorToTheBit) {
  const std::string part = (dir_ / "part.obj").string();
  const ParsedShape mm = parseShape(part + "@mm", "A");
  const ParsedShape factor = parseShape(part + "@0.001", "A");
  EXPECT_EQ(mesh(mm).vertices, mesh(factor).vertices);
  EXPECT_TRUE(mm.warnings.empty());
  const ParsedShape in = parseShape(part + "@in", "A");
  EXPECT_EQ(mesh(in).vertices, (mesh(parseShape(part, "A")).vertices * 0.0254).eval());
}

TEST_F(MeshText, AtSignInAFolderNameIsPartOfThePath) {
  const std::string inFolder = (dir_ / "a@b" / "part.obj").string();
  EXPECT_EQ(splitMeshScale(inFolder), std::make_pair(inFolder, 1.0));
  EXPECT_EQ(splitMeshScale(inFolder + "@mm"), std::make_pair(inFolder, 0.001));
  EXPECT_EQ(std::get<geometry::Mesh>(parseShape(inFolder + "@mm", "A").shape).mesh->vertexCount(),
            8);
}

// A file whose own name ends in what reads as a scale is that file (issue 20).
TEST_F(MeshText, AnExistingFileIsAPathWhateverFollowsItsAtSign) {
  const std::string named = (dir_ / "part.obj@2").string();
  std::filesystem::copy_file(dir_ / "part.obj", named);
  EXPECT_EQ(splitMeshScale(named), std::make_pair(named, 1.0));
  const std::string other = (dir_ / "part.obj@mm").string();
  EXPECT_EQ(splitMeshScale(other), std::make_pair((dir_ / "part.obj").string(), 0.001));
  EXPECT_EQ(splitMeshScale((dir_ / "part.obj@0x2").string()).second, 1.0);  // not a scale
}

TEST_F(MeshText, UnknownSuffixIsReadAsAPath) {
  const std::string part = (dir_ / "part.obj").string();
  EXPECT_EQ(rejection([&] { parseShape(part + "@furlong", "A"); }),
            part + "@furlong: no such file");
}

TEST_F(MeshText, MetreReadingOfAMillimetreFileWarns) {
  const ParsedShape s = parseShape((dir_ / "part.obj").string(), "A");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("implausible for a file in metres"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::io
