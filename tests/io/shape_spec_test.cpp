// Shape and pose text forms: what parses, and the message for what does not.

#include "io/shape_spec.hpp"

#include <gtest/gtest.h>

#include "geometry/error.hpp"
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

}  // namespace
}  // namespace vcontact::io
