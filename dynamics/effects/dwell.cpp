// dwell: the state s_dw replaces s in μ_max (MODEL.md §3 "Dwell time"):
//   ṡ_dw = (s − s_dw)/τ_dw while s > s_dw;  s_dw = s when s ≤ s_dw
// (bonds form slowly, break at once). The jump is applied after each accepted step (settle);
// within a step μ_max uses min(s_dw, s), which is the value the jump would give.
#include <algorithm>

#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Dwell final : public EffectBase<Dwell> {
 public:
  static constexpr std::string_view kId = "dwell";
  static constexpr Stage kStage = Stage::kStickState;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"tau_dw", "s", 1.0, 1e-9, 1e9, "dwell time constant"}};
    return s;
  }
  static const std::vector<StateSlot>& states() {
    static const std::vector<StateSlot> s = {
        {"s_dw", StateSlot::Kind::kScalar, "-", "dwell stick state (0..1), replaces s in mu_max"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stribeck"}; }

  Wrench apply(ContactContext& ctx) const override {
    const double s_dw = ctx.state[stateOffset()];
    ctx.s_mu = std::min(s_dw, ctx.s);
    ctx.rates[stateOffset()] = ctx.s > s_dw ? (ctx.s - s_dw) / parameter(0) : 0.0;
    return {};
  }

  void settle(const ContactContext& ctx, PairState& state) const override {
    state[stateOffset()] = std::min(state[stateOffset()], ctx.s);
  }

  // The discrete stepper: what it changes is s_μ, frozen at the step's start (its state advanced
  // explicitly).
  StepForm stepForm() const override { return StepForm::kThroughContext; }
};

}  // namespace

std::unique_ptr<Effect> makeDwell() { return std::make_unique<Dwell>(); }

}  // namespace vcontact::dynamics
