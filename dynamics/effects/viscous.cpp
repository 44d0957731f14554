// viscous: −|f_n| σ2 v_t and −r_gyr² |f_n| σ2 ω_n n (MODEL.md §3).
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Viscous final : public EffectBase<Viscous> {
 public:
  static constexpr std::string_view kId = "viscous";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"sigma2", "s/m", 0.0, 0.0, 1e9, "viscous friction per unit normal force"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }

  void configure(ContactContext& ctx) const override { ctx.sigma2 = parameter(0); }

  Wrench apply(ContactContext& ctx) const override {
    const double c = ctx.f_n * ctx.sigma2;
    return {-c * ctx.v_t, -ctx.r_gyr * ctx.r_gyr * c * ctx.omega_n * ctx.n};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // v_t = P v_c, ω_n = n·ω, at the frozen f_n (docs/DISCRETE.md §2.4).
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    const double r = ctx.r_gyr;
    terms.D.topLeftCorner<3, 3>() -= ctx.f_n * ctx.sigma2 * planeProjector(ctx.n);
    const Eigen::Matrix3d nn = ctx.n * ctx.n.transpose();
    terms.D.bottomRightCorner<3, 3>() -= r * r * ctx.f_n * ctx.sigma2 * nn;
  }
};

}  // namespace

std::unique_ptr<Effect> makeViscous() { return std::make_unique<Viscous>(); }

}  // namespace vcontact::dynamics
