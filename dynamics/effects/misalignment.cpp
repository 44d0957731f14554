// misalignment: the payload B1 is rotated by small angles rx, ry about its own origin, about
// axes parallel to the plate's (B2's) x and y axes, before the geometry is evaluated
// (MODEL.md §3):  R_W1' = R_W2 Rx(rx) Ry(ry) R_W2ᵀ R_W1,  p_W1' = p_W1.
#include "dynamics/effects/registry.hpp"

namespace vcontact::dynamics {
namespace {

class Misalignment final : public EffectBase<Misalignment> {
 public:
  static constexpr std::string_view kId = "misalignment";
  static constexpr Stage kStage = Stage::kGeometryOnly;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"rx", "rad", 0.0, -0.2, 0.2, "small rotation about the plate x axis"},
        {"ry", "rad", 0.0, -0.2, 0.2, "small rotation about the plate y axis"}};
    return s;
  }

  Eigen::Isometry3d adjustPayloadPose(const Eigen::Isometry3d& X_W1,
                                      const Eigen::Isometry3d& X_W2) const override {
    const Eigen::Matrix3d R_2 = X_W2.linear();
    const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(parameter(0), Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(parameter(1), Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
    Eigen::Isometry3d X = X_W1;
    X.linear() = R_2 * tilt * R_2.transpose() * X_W1.linear();
    return X;
  }
};

}  // namespace

std::unique_ptr<Effect> makeMisalignment() { return std::make_unique<Misalignment>(); }

}  // namespace vcontact::dynamics
