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
  Wrench wrench;               ///< total wrench on body A (the payload) at p_c
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

  /// Adds an effect (kept in Stage order, stable) and gives it its offset in stateLayout().
  /// @throws InputError on a repeated id
  /// @pre an effect with states is a registered one (createEffect)
  void add(std::unique_ptr<Effect> effect);
  /// @throws InputError naming the first effect whose required effect is missing, or the
  ///         first parameter relation that does not hold (Effect::brokenRelation)
  void validate() const;

  bool has(std::string_view id) const;
  /// Whether an effect of the model runs at `stage` (its place in the chain, effect.hpp): a
  /// question about what a model does that needs no effect's name.
  bool hasStage(Stage stage) const;
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

  /// The layout of the pair state that evaluate() and settle() read and write: the state
  /// slots of every registered effect, in registration order; the slots of effects this model
  /// does not hold stay zero. Every model shares it, so that every pair of a simulation writes
  /// the same state columns and carries as many states in the integrator (whose step-size
  /// control depends on their count).
  const StateLayout& stateLayout() const;

  /// Does some effect move body A's pose for the geometry (adjustPayloadPose not the identity)?
  bool adjustsPayloadPose() const { return adjusts_pose_; }
  /// The pose of body A (the payload) actually used for the geometry (misalignment), given
  /// X_WA and the pose X_WB of body B (the plate).
  Eigen::Isometry3d adjustPayloadPose(const Eigen::Isometry3d& X_WA,
                                      const Eigen::Isometry3d& X_WB) const;

  /// Wrench on body A at cv.p_WC, state rates and per-effect shares. No contact (V = 0)
  /// gives zero wrench and zero rates.
  /// @param state  in stateLayout() order (PairState{} is the zero state)
  /// @param field  the δ map of cv for distributed friction (ContactContext::field), or null
  ///   for the lumped friction of MODEL.md §3; with a field the model must pass
  ///   checkDistributedFriction()
  ContactResult evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                         const PairState& state, const volume::DepthField* field = nullptr) const;
  /// The same, into `out` (reuses its storage: no allocation in the integrator's loop). With
  /// `context`, also the shared context after both passes (what context() returns for a null
  /// field), from the same evaluation: the discrete stepper linearises about it.
  void evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                const PairState& state, ContactResult& out,
                const volume::DepthField* field = nullptr, ContactContext* context = nullptr) const;

  /// The shared context after both passes of evaluate() (lumped friction): the final f_n, s,
  /// μ_max, Contensou factors and the configured parameters, for the linearisation of the
  /// discrete stepper (dynamics/steppers/discrete_jacobian.hpp). @pre cv.inContact()
  ContactContext context(const volume::ContactVolume& cv, const RelativeMotion& motion,
                         const PairState& state) const;

  /// The discrete stepper's linear form of the wrench at the context `ctx` of an evaluation
  /// (evaluate's `context`) over a step of terms.h: every effect adds its part, in stage order
  /// (those whose stepForm() is not kLinearised add nothing; docs/DISCRETE.md §2).
  /// @pre ctx.cv in contact
  void linearise(const ContactContext& ctx, StepTerms& terms) const;
  /// The ids of the effects whose share the discrete stepper takes at the step's start only
  /// (StepForm::kExplicit: adhesion, expression effects), in effect order.
  std::vector<std::string> explicitEffects() const;

  /// The restitution of a head-on impact at normal approach speed `approach` (m/s): the
  /// smallest of the effects' own (Effect::restitution; 1 when none dissipates). Other
  /// dissipation only lowers a head-on rebound further, so it errs high, towards resolving.
  double impactRestitution(double approach) const;

  /// Distributed friction replaces the lumped Coulomb force and spin torque (coulomb, spin,
  /// contensou) by pointwise Coulomb friction with μ_max over the δ map. It needs an effect
  /// that integrates it (Effect::integratesDistributedFriction: coulomb), and no effect that
  /// conflicts with it (Effect::distributedFrictionConflict: bristle, whose states have no
  /// pointwise form here).
  /// @throws InputError (source "model") naming the reason
  void checkDistributedFriction() const;

  /// Discrete state updates after an accepted step (MODEL.md §3 "State handling"): plane
  /// vectors (bristle z) are projected onto the contact plane; without contact all states
  /// reset to zero; effects apply their own jumps (dwell). Returns true when a state changed
  /// by more than a projection of round-off size (then the integrator must re-evaluate its
  /// derivative).
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
