// bristle: LuGre-type bristle friction of Gonthier 2007 / Boos & McPhee 2012 (MODEL.md §3):
//   ż   = s v_t + (1 − s) ((C_v μ_C / σ1) dir_ε(v_t) − (σ0/σ1) z)
//   f_t = −|f_n| sat(σ0 z + σ1 ż, μ_max)          (σ2 term: the viscous effect)
//   θ̇_n = s ω_n + (1 − s) ((C_ω μ_C / (σ1 r_gyr)) sgn_ε(ω_n) − (σ0/σ1) θ_n)
// It owns the states z and θ_n, replaces the Coulomb form of coulomb, and leaves θ̇_n in the
// context (with θ_n) for the bristle form of spin. It has no pointwise form for distributed
// friction.
#include <algorithm>

#include "dynamics/effects/bristle_step.hpp"
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Bristle final : public EffectBase<Bristle> {
 public:
  static constexpr std::string_view kId = "bristle";
  static constexpr Stage kStage = Stage::kFrictionState;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"sigma0", "1/m", 4500.0, 1e-6, 1e12, "bristle stiffness per unit normal force"},
        {"sigma1", "s/m", 300.0, 1e-9, 1e12, "bristle damping per unit normal force"}};
    return s;
  }
  static const std::vector<StateSlot>& states() {
    static const std::vector<StateSlot> s = {
        {"z", StateSlot::Kind::kPlaneVector, "m", "bristle deflection, in the contact plane"},
        {"theta_n", StateSlot::Kind::kScalar, "rad", "torsional bristle deflection about n"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"coulomb"}; }
  std::string_view distributedFrictionConflict() const override {
    return "distributed friction is pointwise Coulomb friction and cannot replace the bristle "
           "law; remove bristle or use lumped friction";
  }

  void configure(ContactContext& ctx) const override {
    ctx.sigma0 = parameter(0);
    ctx.sigma1 = parameter(1);
    ctx.law = FrictionLaw::kBristle;
  }

  Wrench apply(ContactContext& ctx) const override {
    const double s = ctx.s, s0 = ctx.sigma0, s1 = ctx.sigma1;
    const Eigen::Vector3d z_W = ctx.state.vector(zOffset());
    const Eigen::Vector3d z_dot =
        s * ctx.v_t + (1.0 - s) * ((ctx.C_v * ctx.mu_C / s1) * dirEps(ctx.v_t, ctx.settings.v_eps) -
                                   (s0 / s1) * z_W);
    ctx.rates.vector(zOffset()) = z_dot;
    ctx.theta_n = ctx.state[thetaOffset()];
    ctx.theta_dot = thetaRate(ctx);
    ctx.rates[thetaOffset()] = ctx.theta_dot;
    return {-ctx.f_n * saturate(Eigen::Vector3d(s0 * z_W + s1 * z_dot), ctx.mu_max),
            Eigen::Vector3d::Zero()};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // The bristle force affine in ξ⁺ with z advanced by backward Euler over the step
  // (bristle_step.hpp; docs/DISCRETE.md §2.6): at the step's start (h = 0, the
  // instantaneous Jacobian at a fixed z) and over the step, and the states z⁺, θ_n⁺ at its end
  // (spin adds the torsional bristle's torque).
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    const double s = ctx.s, s0 = ctx.sigma0, s1 = ctx.sigma1;
    const double v_eps = ctx.settings.v_eps;
    const Eigen::Matrix3d P = planeProjector(ctx.n);
    // the pull term's secant: (C_v μ_C / σ1) dir_ε(v_t) = g_v v_t
    const double g_v = ctx.C_v * ctx.mu_C / (s1 * std::max(ctx.v_t.norm(), v_eps));
    const double e_v = s + (1.0 - s) * g_v;
    const Eigen::Vector3d z = ctx.state.vector(zOffset());
    // saturation at the step's start, kept as a fixed scale over the step
    const Eigen::Vector3d x0 = s * s0 * z + s1 * e_v * ctx.v_t;
    const double scale_v = x0.norm() > ctx.mu_max ? ctx.mu_max / x0.norm() : 1.0;
    // over a step h with the state's relaxation β over it (β = 1 at h = 0)
    const auto form = [&](double h, double beta, Vector6d& c, Matrix6d& L) {
      const double k = ctx.f_n * beta;
      c.head<3>() = -scale_v * k * s * s0 * z;
      L.topLeftCorner<3, 3>() = -scale_v * k * (h * s0 + s1) * e_v * P;
    };
    const double h = terms.h, beta = bristleRelaxation(ctx, h);
    form(0.0, 1.0, terms.c_now, terms.L_now);
    form(h, beta, terms.c_step, terms.L_step);
    const BristleTorsion torsion = bristleTorsion(ctx);
    ImplicitStates& next = terms.implicit;
    next.offset = zOffset();
    next.z_c = beta * z;
    next.Z.setZero();
    next.Z.leftCols<3>() = beta * h * e_v * P;
    next.theta_c = beta * ctx.theta_n;
    next.Theta.setZero();
    next.Theta.rightCols<3>() = (beta * h * torsion.e_w) * ctx.n.transpose();
  }

 private:
  int zOffset() const { return stateOffset(); }
  int thetaOffset() const { return stateOffset() + 3; }

  double thetaRate(const ContactContext& ctx) const {
    const double s = ctx.s;
    const double pull = ctx.r_gyr > 0.0 ? (ctx.C_w * ctx.mu_C / (ctx.sigma1 * ctx.r_gyr)) *
                                              sgnEps(ctx.omega_n, ctx.settings.v_eps, ctx.r_gyr)
                                        : 0.0;
    return s * ctx.omega_n +
           (1.0 - s) * (pull - (ctx.sigma0 / ctx.sigma1) * ctx.state[thetaOffset()]);
  }
};

}  // namespace

std::unique_ptr<Effect> makeBristle() { return std::make_unique<Bristle>(); }

}  // namespace vcontact::dynamics
