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
  EXPECT_EQ(rejection([] { parseShape("box:1,x,3", "A"); }), "A: 'x' is not a number (in '1,x,3')");
  EXPECT_EQ(rejection([] { parseShape("sphere:nan", "A"); }), "A: 'nan' is not finite");
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
  EXPECT_NE(rejection([] { parsePose("0,0,inf", "--pose-b"); }).find("not finite"),
            std::string::npos);
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
