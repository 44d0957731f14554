// rolling_resistance: τ_r = −kv a J_s ω_t (MODEL.md §3); uses damping.a, no own parameter.
// Its power is τ_r·ω_t = −kv a ω_tᵀ J_s ω_t ≤ 0 (J_s is positive semi-definite).
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class RollingResistance final : public EffectBase<RollingResistance> {
 public:
  static constexpr std::string_view kId = "rolling_resistance";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s;
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"damping"}; }

  Wrench apply(ContactContext& ctx) const override {
    return {Eigen::Vector3d::Zero(), -ctx.kv * ctx.a * (ctx.cv->J_s * ctx.omega_t)};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // ω_t = P ω: ∂τ_r/∂ω = −kv a J_s P (docs/DISCRETE.md §2.3).
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    terms.D.bottomRightCorner<3, 3>() -= ctx.kv * ctx.a * ctx.cv->J_s * planeProjector(ctx.n);
  }
};

}  // namespace

std::unique_ptr<Effect> makeRollingResistance() { return std::make_unique<RollingResistance>(); }

}  // namespace vcontact::dynamics
