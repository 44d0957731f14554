// adhesion: a tensile normal force over the contact area (MODEL.md §3 "Normal law"):
//   f_adh = −σ_a A n,
// which outweighs the compressive law near separation (kv V < σ_a A, i.e. a mean depth below
// σ_a/kv): the force turns tensile before the contact opens, the pull-off of an adhesive
// contact (a DMT-like law with the adhesive stress σ_a). Friction reads the compressive f_n
// of the earlier stages; the adhesive share is added to the wrench only.
#include "dynamics/effects/effect_base.hpp"

namespace vcontact::dynamics {
namespace {

class Adhesion final : public EffectBase<Adhesion> {
 public:
  static constexpr std::string_view kId = "adhesion";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"sigma_a", "N/m^2", 1e3, 0.0, 1e9, "adhesive stress over the contact area"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }

  Wrench apply(ContactContext& ctx) const override {
    return {-parameter(0) * contactArea(*ctx.cv) * ctx.n, Eigen::Vector3d::Zero()};
  }
};

}  // namespace

std::unique_ptr<Effect> makeAdhesion() { return std::make_unique<Adhesion>(); }

}  // namespace vcontact::dynamics
