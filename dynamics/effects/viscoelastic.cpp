// viscoelastic: a standard linear solid in the normal direction (MODEL.md §3 "Normal law"):
// the elastic force f_e of the earlier stages (kv V, or the power law) is carried by a spring
// of the relaxed stiffness r·k and a Maxwell branch of stiffness (1 − r)·k and relaxation
// time τ, whose force q is this effect's state:
//   f_n = max(0, r f_e + q),   q̇ = (1 − r) (∂f_e/∂V) A δ̇ − q/τ
// (V̇ = A δ̇: the volume grows by the contact area A times the penetration rate). A fast
// indentation sees the instantaneous law f_e, a hold relaxes to r f_e with time constant τ,
// and the unloading branch lies below the loading one (hysteresis, creep of the sample).
// The state resets to 0 when contact is lost (MODEL.md §3 "State handling").
#include <algorithm>

#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Viscoelastic final : public EffectBase<Viscoelastic> {
 public:
  static constexpr std::string_view kId = "viscoelastic";
  static constexpr Stage kStage = Stage::kNormalRelaxation;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"tau", "s", 0.1, 1e-6, 1e6, "relaxation time of the Maxwell branch"},
        {"ratio", "-", 0.5, 0.0, 1.0, "relaxed / instantaneous stiffness (1: elastic)"}};
    return s;
  }
  static const std::vector<StateSlot>& states() {
    static const std::vector<StateSlot> s = {
        {"ve_q", StateSlot::Kind::kScalar, "N", "normal force of the Maxwell branch"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }

  // Linearised by stiffness at a fixed q, from the k_n it leaves; q is advanced explicitly (the
  // discrete stepper).
  StepForm stepForm() const override { return StepForm::kThroughContext; }

  Wrench apply(ContactContext& ctx) const override {
    const double tau = parameter(0), r = parameter(1);
    const double q = ctx.state[stateOffset()];
    const double f_n = std::max(0.0, r * ctx.f_n + q);
    ctx.rates[stateOffset()] = (1.0 - r) * ctx.k_n * contactArea(*ctx.cv) * ctx.delta_dot - q / tau;
    const double change = f_n - ctx.f_n;
    ctx.k_n = f_n > 0.0 ? r * ctx.k_n : 0.0;  // at fixed q
    ctx.f_n = ctx.f_spring = f_n;
    ctx.linear_normal_law = false;
    return {change * ctx.n, Eigen::Vector3d::Zero()};
  }
};

}  // namespace

std::unique_ptr<Effect> makeViscoelastic() { return std::make_unique<Viscoelastic>(); }

}  // namespace vcontact::dynamics
