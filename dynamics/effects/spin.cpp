// spin: friction torque about the normal (MODEL.md §3).
//   Coulomb form: τ_s = −μ_max C_ω r_gyr |f_n| sgn_ε(ω_n) n
//   bristle form: τ_s = −r_gyr² |f_n| sat(σ0 θ_n + σ1 θ̇_n, μ_max / r_gyr) n
// (the σ2 ω_n term of the bristle form belongs to the viscous effect).
// With distributed friction the coulomb share carries the spin torque, and this one is zero.
#include <algorithm>
#include <cmath>

#include "dynamics/effects/bristle_step.hpp"
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Spin final : public EffectBase<Spin> {
 public:
  static constexpr std::string_view kId = "spin";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s;
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"coulomb"}; }

  Wrench apply(ContactContext& ctx) const override {
    const double r = ctx.r_gyr;
    if (r <= 0.0 || ctx.field != nullptr) return {};
    double torque = 0.0;  // N·m along n
    if (ctx.law == FrictionLaw::kBristle) {
      const double m = ctx.sigma0 * ctx.theta_n + ctx.sigma1 * ctx.theta_dot;
      torque = -r * r * ctx.f_n * saturate(m, ctx.mu_max / r);
    } else {
      torque = -ctx.mu_max * ctx.C_w * r * ctx.f_n * sgnEps(ctx.omega_n, ctx.settings.v_eps, r);
    }
    return {Eigen::Vector3d::Zero(), torque * ctx.n};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // Coulomb form: the secant of sgn_ε about the step's start (docs/DISCRETE.md §2.5). Bristle
  // form: affine in ξ⁺ with θ_n advanced implicitly (bristle_step.hpp; docs/DISCRETE.md §2.6), at
  // the step's start and over the step.
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    const double r = ctx.r_gyr;
    if (r <= 0.0) return;
    if (ctx.law == FrictionLaw::kCoulomb) {
      const double w_eps = ctx.settings.v_eps / r;
      const Eigen::Matrix3d nn = ctx.n * ctx.n.transpose();
      terms.D.bottomRightCorner<3, 3>() -=
          (ctx.mu_max * ctx.C_w * r * ctx.f_n / std::max(std::abs(ctx.omega_n), w_eps)) * nn;
      return;
    }
    const BristleTorsion b = bristleTorsion(ctx);
    const auto form = [&](double h, Vector6d& c, Matrix6d& L) {
      const double s = ctx.s, s0 = ctx.sigma0, s1 = ctx.sigma1;
      const double k = ctx.f_n * bristleRelaxation(ctx, h);
      c.tail<3>() = -b.scale_w * r * r * k * s * s0 * ctx.theta_n * ctx.n;
      L.bottomRightCorner<3, 3>() =
          -b.scale_w * r * r * k * (h * s0 + s1) * b.e_w * ctx.n * ctx.n.transpose();
    };
    form(0.0, terms.c_now, terms.L_now);
    form(terms.h, terms.c_step, terms.L_step);
  }
};

}  // namespace

std::unique_ptr<Effect> makeSpin() { return std::make_unique<Spin>(); }

}  // namespace vcontact::dynamics
