// misalignment: body A (the payload) is rotated by small angles rx, ry about its own origin,
// about axes parallel to the x and y axes of body B (the plate), before the geometry is
// evaluated (MODEL.md §3):  R_WA' = R_WB Rx(rx) Ry(ry) R_WBᵀ R_WA,  p_WA' = p_WA.
#include "dynamics/effects/effect_base.hpp"

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

  Eigen::Isometry3d adjustPayloadPose(const Eigen::Isometry3d& X_WA,
                                      const Eigen::Isometry3d& X_WB) const override {
    const Eigen::Matrix3d R_WB = X_WB.linear();
    const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(parameter(0), Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(parameter(1), Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
    Eigen::Isometry3d X_WA_tilted = X_WA;
    X_WA_tilted.linear() = R_WB * tilt * R_WB.transpose() * X_WA.linear();
    return X_WA_tilted;
  }

  // The discrete stepper: what it changes is the pose the geometry is computed at.
  StepForm stepForm() const override { return StepForm::kThroughContext; }
};

}  // namespace

std::unique_ptr<Effect> makeMisalignment() { return std::make_unique<Misalignment>(); }

}  // namespace vcontact::dynamics
