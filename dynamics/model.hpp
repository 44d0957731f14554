#pragma once
// A contact model: a list of effects (MODEL.md §3) seen from outside as named parameters in,
// wrench out. This is the only view that simulation, fitting and diagnosis take of forces.
//
//   Model m = Model::withEffects({"stiffness", "damping", "coulomb"});
//   m.parameterNames();          // {"stiffness.kv", "damping.a", "coulomb.mu", "coulomb.v_s"}
//   m.setParameters(values);     // same order, bounds checked
//   ContactResult r = m.evaluate(cv, motion, state);   // wrench at p_c, state rates, shares

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "dynamics/effect.hpp"

namespace vcontact::dynamics {

/// The result of one contact evaluation.
struct ContactResult {
  Wrench wrench;               ///< total wrench on B1 at p_c
  PairStateRates rates;        ///< d/dt of the pair state
  std::vector<Wrench> shares;  ///< one per effect, in Model::effectIds() order; sums to wrench
  double f_n = 0.0;            ///< normal force magnitude, N
  double s = 0.0;              ///< stick–slip state, –
  double mu_max = 0.0;         ///< friction limit used, –
};

class Model {
 public:
  Model() = default;
  Model(const Model& other);
  Model& operator=(const Model& other);
  Model(Model&&) noexcept = default;
  Model& operator=(Model&&) noexcept = default;
  ~Model() = default;

  /// A model of the given effects with default parameters.
  /// @throws InputError (source "model") on an unknown or repeated id or a missing requirement
  static Model withEffects(const std::vector<std::string>& ids);

  /// Adds an effect (kept in Stage order, stable). @throws InputError on a repeated id.
  void add(std::unique_ptr<Effect> effect);
  /// @throws InputError naming the first effect whose required effect is missing, or a
  ///         parameter relation that does not hold (stribeck.mu_s ≥ coulomb.mu)
  void validate() const;

  bool has(std::string_view id) const;
  std::vector<std::string> effectIds() const;
  std::size_t effectCount() const { return effects_.size(); }
  const Effect& effect(std::size_t i) const { return *effects_[i]; }

  /// "effect.parameter" for every parameter of every effect, in effect order.
  std::vector<std::string> parameterNames() const;
  /// Specs with names qualified as in parameterNames().
  std::vector<ParameterSpec> parameterSpecs() const;
  std::vector<double> parameters() const;
  /// @throws InputError (source "model") on a wrong count, a non-finite or out-of-bounds value
  void setParameters(std::span<const double> values);
  /// Sets one parameter by qualified name. @throws InputError as setParameters, or unknown name
  void setParameter(const std::string& qualified_name, double value);
  double parameter(const std::string& qualified_name) const;

  /// Parameters a fitter must not change (qualified names).
  const std::vector<std::string>& fixed() const { return fixed_; }
  /// @throws InputError on an unknown name
  void setFixed(std::vector<std::string> names);

  ModelSettings settings;

  /// Does some effect move B1's pose for the geometry (adjustPayloadPose not the identity)?
  bool adjustsPayloadPose() const { return adjusts_pose_; }
  /// The pose of B1 actually used for the geometry (misalignment), given X_W1 and X_W2.
  Eigen::Isometry3d adjustPayloadPose(const Eigen::Isometry3d& X_W1,
                                      const Eigen::Isometry3d& X_W2) const;

  /// Wrench on B1 at cv.p_WC, state rates and per-effect shares. No contact (V = 0)
  /// gives zero wrench and zero rates.
  /// @param field  the δ map of cv for distributed friction (ContactContext::field), or null
  ///   for the lumped friction of MODEL.md §3; with a field the model must pass
  ///   checkDistributedFriction()
  ContactResult evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                         const PairState& state, const volume::DepthField* field = nullptr) const;
  /// The same, into `out` (reuses its storage: no allocation in the integrator's loop).
  void evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                const PairState& state, ContactResult& out,
                const volume::DepthField* field = nullptr) const;

  /// Distributed friction replaces the lumped Coulomb force and spin torque (coulomb, spin,
  /// contensou) by pointwise Coulomb friction with μ_max over the δ map. It needs coulomb,
  /// and it cannot stand in for the bristle law (bristle states have no pointwise form here).
  /// @throws InputError (source "model") naming the reason
  void checkDistributedFriction() const;

  /// Discrete state updates after an accepted step (MODEL.md §3 "State handling"): z is
  /// projected onto the contact plane; without contact all states reset to zero; effects
  /// apply their own jumps (dwell). Returns true when a state changed by more than a
  /// projection of round-off size (then the integrator must re-evaluate its derivative).
  bool settle(const volume::ContactVolume& cv, const RelativeMotion& motion,
              PairState& state) const;

 private:
  ContactContext makeContext(const volume::ContactVolume& cv, const RelativeMotion& motion,
                             const PairState& state) const;
  std::pair<std::size_t, std::size_t> locate(const std::string& qualified_name) const;

  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<std::string> fixed_;
  bool adjusts_pose_ = false;  ///< some effect acts on the payload pose (Stage::kGeometryOnly)
};

}  // namespace vcontact::dynamics
