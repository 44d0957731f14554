// damping: f_n = kv V (1 + a δ̇_c) n, clamped so that f_n·n ≥ 0 (MODEL.md §3, Hunt–Crossley
// form of Gonthier); with a normal law before it (power_law, viscoelastic) the factor
// multiplies that law's force f_spring. Its share is the change it makes to that force.
#include <algorithm>

#include "dynamics/effects/effect_base.hpp"
#include "dynamics/restitution.hpp"

namespace vcontact::dynamics {
namespace {

class Damping final : public EffectBase<Damping> {
 public:
  static constexpr std::string_view kId = "damping";
  static constexpr Stage kStage = Stage::kNormalDamping;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"a", "s/m", 1.0, 0.0, 1e8, "damping factor (Hunt-Crossley)"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }

  void configure(ContactContext& ctx) const override { ctx.a = parameter(0); }

  Wrench apply(ContactContext& ctx) const override {
    const double f_n = std::max(0.0, ctx.f_spring * (1.0 + ctx.a * ctx.delta_dot));
    const double change = f_n - ctx.f_n;
    ctx.f_n = f_n;
    return {change * ctx.n, Eigen::Vector3d::Zero()};
  }

  // the exact e(a v_in) of the Hunt–Crossley impact (docs/MODEL.md §5, restitution.hpp)
  double restitution(double approach) const override {
    return dampedRestitution(parameter(0) * approach);
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // ∂f_n/∂ξ = −f_spring a n nᵀ (δ̇ = −n·v_c), zero where the clamp holds f_n at 0
  // (docs/DISCRETE.md §2.3); its factor on the position terms is in stiffness's kv'.
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    if (!(1.0 + ctx.a * ctx.delta_dot > 0.0)) return;
    const Eigen::Matrix3d nn = ctx.n * ctx.n.transpose();
    terms.D.topLeftCorner<3, 3>() -= ctx.f_spring * ctx.a * nn;
  }
};

}  // namespace

std::unique_ptr<Effect> makeDamping() { return std::make_unique<Damping>(); }

}  // namespace vcontact::dynamics
