// stribeck: μ_max = μ_C + (μ_S − μ_C) s_μ (MODEL.md §3), s_μ = s (or s_dw with dwell).
#include "dynamics/effects/registry.hpp"

namespace vcontact::dynamics {
namespace {

class Stribeck final : public EffectBase<Stribeck> {
 public:
  static constexpr std::string_view kId = "stribeck";
  static constexpr Stage kStage = Stage::kFrictionLimit;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"mu_s", "-", 0.2, 0.0, 10.0, "static friction coefficient mu_S (>= coulomb.mu)"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"coulomb"}; }

  void configure(ContactContext& ctx) const override { ctx.mu_S = parameter(0); }

  Wrench apply(ContactContext& ctx) const override {
    ctx.mu_max = ctx.mu_C + (ctx.mu_S - ctx.mu_C) * ctx.s_mu;
    return {};
  }
};

}  // namespace

std::unique_ptr<Effect> makeStribeck() { return std::make_unique<Stribeck>(); }

}  // namespace vcontact::dynamics
