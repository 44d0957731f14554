// power_law: the normal force as a power of the interference volume (MODEL.md §3 "Normal
// law"): f_n = kv V (V/V_ref)^(p−1), V_ref = 1 mm³, so that p = 1 is the volumetric law and
// kv keeps its meaning at V = V_ref. A sphere has V ≈ π R d², so f_n ∝ d^(2p): Hertz (d^1.5)
// is p = 0.75; a flat punch has V = A d, so f_n ∝ d^p.
#include <cmath>

#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

// The volume at which the law meets kv V, m³ (1 mm³): a fixed scale, not a parameter, since
// kv and V_ref enter only as kv V_ref^(1−p) and cannot be fitted apart.
constexpr double kReferenceVolume = 1e-9;

class PowerLaw final : public EffectBase<PowerLaw> {
 public:
  static constexpr std::string_view kId = "power_law";
  static constexpr Stage kStage = Stage::kNormalLaw;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"p", "-", 1.0, 0.2, 5.0, "exponent of the volume in f_n = kv V (V/V_ref)^(p-1)"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }

  // Linearised by stiffness, from the k_n it leaves (the discrete stepper).
  StepForm stepForm() const override { return StepForm::kThroughContext; }

  // f_n ← f_n (V/V_ref)^(p−1);  ∂f_n/∂V = p f_n / V
  Wrench apply(ContactContext& ctx) const override {
    const double V = ctx.cv->volume, p = parameter(0);
    const double f_n = ctx.f_n * std::pow(V / kReferenceVolume, p - 1.0);
    const double change = f_n - ctx.f_n;
    ctx.f_n = ctx.f_spring = f_n;
    ctx.k_n = p * f_n / V;
    ctx.linear_normal_law = false;
    return {change * ctx.n, Eigen::Vector3d::Zero()};
  }
};

}  // namespace

std::unique_ptr<Effect> makePowerLaw() { return std::make_unique<PowerLaw>(); }

}  // namespace vcontact::dynamics
