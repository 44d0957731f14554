// stribeck: μ_max = μ_C + (μ_S − μ_C) s_μ (MODEL.md §3), s_μ = s (or s_dw with dwell).
// Relation: μ_S ≥ μ_C (static friction is not below kinetic friction).
#include <sstream>

#include "dynamics/effects/effect_base.hpp"
#include "dynamics/model.hpp"

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

  std::string brokenRelation(const Model& model) const override {
    const double mu_C = model.parameter("coulomb.mu");
    if (parameter(0) >= mu_C) return {};
    std::ostringstream s;
    s << "stribeck.mu_s = " << parameter(0) << " must be >= coulomb.mu = " << mu_C
      << " (MODEL.md section 3)";
    return s.str();
  }

  std::vector<ParameterRelation> relations() const override {
    return {{"stribeck.mu_s", "coulomb.mu"}};
  }

  void configure(ContactContext& ctx) const override { ctx.mu_S = parameter(0); }

  Wrench apply(ContactContext& ctx) const override {
    ctx.mu_max = ctx.mu_C + (ctx.mu_S - ctx.mu_C) * ctx.s_mu;
    return {};
  }

  // The discrete stepper: what it changes is μ_max, frozen at the step's start for the friction
  // effects that read it.
  StepForm stepForm() const override { return StepForm::kThroughContext; }
};

}  // namespace

std::unique_ptr<Effect> makeStribeck() { return std::make_unique<Stribeck>(); }

}  // namespace vcontact::dynamics
