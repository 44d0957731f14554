// stiffness: f_n = kv V n (MODEL.md §3).
// For the discrete stepper it linearises the normal force f_n n as the normal stages leave it
// (power_law, viscoelastic, damping refine f_n and publish k_n, f_spring and a): the normal
// stiffness and the tilt stiffness about p_c (docs/DISCRETE.md §2.1, §2.2).
#include <algorithm>

#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Stiffness final : public EffectBase<Stiffness> {
 public:
  static constexpr std::string_view kId = "stiffness";
  static constexpr Stage kStage = Stage::kNormalForce;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"kv", "N/m^3", 5.17e12, 0.0, 1e18, "volumetric stiffness"}};
    return s;
  }

  void configure(ContactContext& ctx) const override { ctx.kv = parameter(0); }

  Wrench apply(ContactContext& ctx) const override {
    ctx.f_n = ctx.kv * ctx.cv->volume;
    ctx.f_spring = ctx.f_n;
    ctx.k_n = ctx.kv;
    return {ctx.f_n * ctx.n, Eigen::Vector3d::Zero()};
  }

  StepForm stepForm() const override { return StepForm::kLinearised; }

  // kv' = ∂f_n/∂V = k_n (1 + a δ̇_c), zero when the damping clamp holds f_n at 0 (a = 0
  // without damping): the normal stiffness kv' A n nᵀ. A tilt about p_c moves the centroid
  // (where f_n acts) by J_s θ / V at an unchanged V, so the torque is (f_n/V) J_s θ: the
  // secant f_n/V, which is kv' for a normal law linear in V (kept as kv' there, to the bit)
  // and f_n/V otherwise (power_law: kv'/p; viscoelastic: its r f_e + q over V).
  void linearise(const ContactContext& ctx, StepTerms& terms) const override {
    const volume::ContactVolume& cv = *ctx.cv;
    const double damping = 1.0 + ctx.a * ctx.delta_dot;
    const double kv = std::max(0.0, ctx.k_n * damping);
    const double area = contactArea(cv);
    if (kv <= 0.0 || area <= 0.0) return;
    const Eigen::Vector3d& n = ctx.n;
    const Eigen::Matrix3d P = planeProjector(n);
    const double mean_depth = cv.volume / area;
    const double tilt =
        ctx.linear_normal_law ? kv : std::max(0.0, ctx.f_spring * damping) / cv.volume;
    terms.K.topLeftCorner<3, 3>() -= kv * area * n * n.transpose();
    terms.K.bottomRightCorner<3, 3>() -= (tilt / mean_depth) * P * cv.J_s * P;
  }
};

}  // namespace

std::unique_ptr<Effect> makeStiffness() { return std::make_unique<Stiffness>(); }

}  // namespace vcontact::dynamics
