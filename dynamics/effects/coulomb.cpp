// coulomb: f_t = −μ_max C_v |f_n| dir_ε(v_t) (MODEL.md §3). Also provides μ_C and the
// stick–slip speed v_s that every friction effect uses. With bristle in the model the bristle
// form replaces this one and the share is zero.
// Distributed friction (ContactContext::field set): the traction −μ_max p(s) dir_ε(v(s))
// integrated over the δ map instead, force and torque about p_c together
// (dynamics/distributed_friction.hpp); spin and the Contensou factors are then not used.
#include <algorithm>

#include "dynamics/distributed_friction.hpp"
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Coulomb final : public EffectBase<Coulomb> {
 public:
  static constexpr std::string_view kId = "coulomb";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"mu", "-", 0.2, 0.0, 10.0, "Coulomb (kinetic) friction coefficient mu_C"},
        {"v_s", "m/s", 1e-3, 1e-12, 1e3, "stick-slip speed in s = exp(-v_avg^2/v_s^2)"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }
  bool integratesDistributedFriction() const override { return true; }

  void configure(ContactContext& ctx) const override {
    ctx.mu_C = parameter(0);
    ctx.v_s = parameter(1);
  }

  Wrench apply(ContactContext& ctx) const override {
    if (ctx.law == FrictionLaw::kBristle) return {};
    if (ctx.field != nullptr) {
      // The relative motion at p_c back from the context: v_c = v_t − δ̇ n; only ω_n acts
      // in the plate.
      const RelativeMotion motion{ctx.v_t - ctx.delta_dot * ctx.n, ctx.omega_n * ctx.n, ctx.t};
      return distributedFriction(*ctx.cv, *ctx.field, {ctx.kv, ctx.a}, motion, ctx.mu_max,
                                 ctx.settings.v_eps)
          .wrench;
    }
    return {-ctx.mu_max * ctx.C_v * ctx.f_n * dirEps(ctx.v_t, ctx.settings.v_eps),
            Eigen::Vector3d::Zero()};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // The secant of dir_ε about the step's start, 1/max(|v_t|, v_ε) frozen: exact across the
  // slip, and along it D ξ0 is the force at ξ0 (docs/DISCRETE.md §2.5). Lumped friction;
  // under the bristle law its share is zero.
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    if (ctx.law != FrictionLaw::kCoulomb) return;
    terms.D.topLeftCorner<3, 3>() -=
        (ctx.mu_max * ctx.C_v * ctx.f_n / std::max(ctx.v_t.norm(), ctx.settings.v_eps)) *
        planeProjector(ctx.n);
  }
};

}  // namespace

std::unique_ptr<Effect> makeCoulomb() { return std::make_unique<Coulomb>(); }

}  // namespace vcontact::dynamics
