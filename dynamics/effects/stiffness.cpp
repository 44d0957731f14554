// stiffness: f_n = kv V n (MODEL.md §3).
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
};

}  // namespace

std::unique_ptr<Effect> makeStiffness() { return std::make_unique<Stiffness>(); }

}  // namespace vcontact::dynamics
