// contensou: C_v = |v_t| / v_avg, C_ω = r_gyr |ω_n| / v_avg (both 1 when v_avg = 0), so that
// sliding and spinning share one friction budget (MODEL.md §3).
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Contensou final : public EffectBase<Contensou> {
 public:
  static constexpr std::string_view kId = "contensou";
  static constexpr Stage kStage = Stage::kFrictionSharing;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s;
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"coulomb"}; }

  Wrench apply(ContactContext& ctx) const override {
    if (ctx.v_avg > 0.0) {
      ctx.C_v = ctx.v_t.norm() / ctx.v_avg;
      ctx.C_w = ctx.r_gyr * std::abs(ctx.omega_n) / ctx.v_avg;
    }
    return {};
  }

  // The discrete stepper: what it changes is C_v and C_ω, frozen at the step's start for the
  // friction effects that read them.
  StepForm stepForm() const override { return StepForm::kThroughContext; }
};

}  // namespace

std::unique_ptr<Effect> makeContensou() { return std::make_unique<Contensou>(); }

}  // namespace vcontact::dynamics
