#pragma once
// One effect of the contact model (MODEL.md §3): named parameters with units and bounds,
// optional internal states, and a contribution to the wrench at the centroid.
//
// Composition. Effects interact (stribeck changes μ_max, dwell replaces s in μ_max,
// contensou sets C_v and C_ω, bristle replaces the Coulomb forms, damping modifies f_n and
// rolling_resistance reads damping.a). They do so only through one shared ContactContext,
// in two passes that Model::evaluate runs for every contact:
//
//   1. configure: every effect writes its own parameters into the context
//      (kv, a, μ_C, v_s, μ_S, σ0, σ1, σ2, flags). Order does not matter: each field has one
//      writer. Then the model derives the kinematics and the stick–slip state s, which need
//      v_s (MODEL.md §2, §3), and sets the defaults μ_max = μ_C, s_μ = s, C_v = C_ω = 1.
//   2. apply, in the fixed order of Stage: each effect may refine derived quantities that
//      later stages read (f_n, s_μ, μ_max, C_v, C_ω, the bristle rates) and returns its own
//      share of the wrench. The shares add up to the total wrench.
//
// An effect also owns what else is particular to it: its states (stateSlots, at the offset in
// the pair state that the model gives it), the relations its parameters must keep with other
// effects' (brokenRelation), whether it works with distributed friction, and how the discrete
// stepper treats its share (stepForm, linearise: docs/DISCRETE.md §2).
//
// Adding an effect is one new file in dynamics/effects/ (a class deriving from
// dynamics/effects/effect_base.hpp) plus its id in the effect list of dynamics/CMakeLists.txt;
// simulation, fitting and diagnosis then see it through Model.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cassert>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dynamics/pair_state.hpp"
#include "dynamics/relative_motion.hpp"
#include "dynamics/wrench.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::dynamics {

class Model;

/// One named, bounded model parameter.
struct ParameterSpec {
  std::string name;         ///< e.g. "kv" (the model calls it "stiffness.kv")
  std::string unit;         ///< SI unit, "–" for none
  double default_value;     ///< used when a model file leaves it out
  double lower;             ///< physical lower bound (inclusive)
  double upper;             ///< physical upper bound (inclusive)
  std::string description;  ///< one line
};

/// p ≥ q between two parameters of a model, by qualified names ("stribeck.mu_s" ≥
/// "coulomb.mu"). A fit keeps it by optimising p − q ≥ 0 instead of p (validation/fit.hpp).
struct ParameterRelation {
  std::string parameter;  ///< p, a parameter of the effect that declares the relation
  std::string atLeast;    ///< q, a parameter of an effect it requires
};

/// Model settings that are not fitted parameters.
struct ModelSettings {
  double v_eps = 1e-5;  ///< m/s, regularisation speed of dir_ε and sgn_ε (MODEL.md §3)
};

/// The order in which effects apply (see the header comment). Each stage reads what the
/// earlier stages left in the context.
enum class Stage {
  kNormalForce = 0,   ///< stiffness: f_n = kv V
  kNormalLaw,         ///< power_law: f_n ← kv V (V/V_ref)^(p−1)
  kNormalRelaxation,  ///< viscoelastic: f_n ← r f_n + q (standard linear solid, state q)
  kNormalDamping,     ///< damping: f_n ← f_n (1 + a δ̇), clamped ≥ 0
  kStickState,        ///< dwell: s_μ ← s_dw
  kFrictionLimit,     ///< stribeck: μ_max = μ_C + (μ_S − μ_C) s_μ
  kFrictionSharing,   ///< contensou: C_v, C_ω
  kFrictionState,     ///< bristle: ż, θ̇_n and the bristle friction force
  kFriction,      ///< coulomb, spin, viscous, rolling_resistance, adhesion: read the final context
  kGeometryOnly,  ///< misalignment: acts on the pose before geometry, no wrench
};

enum class FrictionLaw { kCoulomb, kBristle };

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// How an effect's share of the wrench enters a step of the discrete stepper (Effect::stepForm,
/// docs/DISCRETE.md §2).
enum class StepForm {
  /// At its value at the step's start only (the default): a stiff share then limits the step,
  /// and `vcontact simulate` names the effect (Model::explicitEffects).
  kExplicit,
  /// Effect::linearise writes its share's derivatives into StepTerms.
  kLinearised,
  /// What it does is in the context that linearised effects read at the step's start: the
  /// normal law's k_n (power_law, viscoelastic at a fixed Maxwell force), μ_max (stribeck,
  /// dwell), the Contensou factors, the pose of the geometry (misalignment).
  kThroughContext,
};

/// The linear form of a contact's wrench w = (f, τ) on body A at p_c over one step of length h,
/// about the step's start (twist ξ0 = (v_c, ω), world frame), summed over the effects that
/// linearise (Effect::linearise, in stage order; docs/DISCRETE.md §2):
///   w⁺ = w0 + D (ξ⁺ − ξ0) + h K ξ⁺
/// with the shares of implicitly advanced states (bristle) replaced by their form over the step.
/// The states a step advances implicitly (bristle's z and θ_n), affine in the twist ξ⁺ at the
/// step's end: z⁺ = z_c + Z ξ⁺ (a plane vector) and θ⁺ = theta_c + Theta ξ⁺ (the scalar after
/// it), from state index `offset` on.
struct ImplicitStates {
  int offset = -1;  ///< −1: the model has no implicitly advanced state
  Eigen::Vector3d z_c = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> Z = Eigen::Matrix<double, 3, 6>::Zero();
  double theta_c = 0.0;
  Eigen::Matrix<double, 1, 6> Theta = Eigen::Matrix<double, 1, 6>::Zero();
  bool any() const { return offset >= 0; }
};

struct StepTerms {
  double h = 0.0;  ///< s, the step (0: the instantaneous Jacobians)
  /// ∂w/∂ξ at fixed states; friction magnitudes are frozen at ξ0 (secants of dir_ε, sgn_ε).
  Matrix6d D = Matrix6d::Zero();
  /// ∂w/∂(du, dθ), the displacement of A about p_c at a fixed twist.
  Matrix6d K = Matrix6d::Zero();
  /// Shares whose states the step advances implicitly (the bristle force and the bristle spin
  /// torque): at the step's start they are c_now + L_now ξ0 (L_now is their ∂w/∂ξ at fixed
  /// states), over the step c_step + L_step ξ⁺ instead.
  Vector6d c_now = Vector6d::Zero(), c_step = Vector6d::Zero();
  Matrix6d L_now = Matrix6d::Zero(), L_step = Matrix6d::Zero();
  ImplicitStates implicit;
};

/// Everything one contact evaluation shares between effects. Plain data.
struct ContactContext {
  // ---- inputs ----
  const volume::ContactVolume* cv = nullptr;
  /// The δ map of cv (volume::DepthField) when the pair's friction is distributed
  /// (docs/DISTRIBUTED_FRICTION.md): coulomb then integrates pointwise Coulomb friction
  /// over it, force and spin torque together, and spin adds nothing. Null: lumped friction.
  const volume::DepthField* field = nullptr;
  PairState state;  ///< with every plane vector projected onto the contact plane
  ModelSettings settings;

  // ---- kinematics at p_c (MODEL.md §2) ----
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();       ///< out of body B into body A
  double delta_dot = 0.0;                             ///< −v_c·n, m/s
  Eigen::Vector3d v_t = Eigen::Vector3d::Zero();      ///< tangential slip, m/s
  double omega_n = 0.0;                               ///< spin ω·n, rad/s
  Eigen::Vector3d omega_t = Eigen::Vector3d::Zero();  ///< rolling, rad/s
  double r_gyr = 0.0;                                 ///< m
  double t = 0.0;  ///< time of the evaluation, s (RelativeMotion::t)

  // ---- pass 1: configured parameters ----
  double kv = 0.0;      ///< N/m³
  double a = 0.0;       ///< s/m
  double mu_C = 0.0;    ///< –
  double mu_S = 0.0;    ///< – (read only by stribeck, which writes it)
  double v_s = 1e-3;    ///< m/s, stick–slip speed
  double sigma0 = 0.0;  ///< 1/m
  double sigma1 = 0.0;  ///< s/m
  double sigma2 = 0.0;  ///< s/m
  FrictionLaw law = FrictionLaw::kCoulomb;

  // ---- derived, refined in stage order ----
  double v_avg = 0.0;   ///< sqrt(|v_t|² + (r_gyr ω_n)²), m/s
  double s = 1.0;       ///< exp(−v_avg²/v_s²)
  double s_mu = 1.0;    ///< the stick measure in μ_max (s, or s_dw with dwell)
  double mu_max = 0.0;  ///< –
  double C_v = 1.0;     ///< Contensou factor on translation
  double C_w = 1.0;     ///< Contensou factor on spin
  double f_n = 0.0;     ///< normal force magnitude, N (≥ 0)
  /// ∂f_n/∂V of the normal law at fixed states, before damping, N/m³: kv from stiffness,
  /// refined by power_law and viscoelastic (the discrete stepper's normal stiffness).
  double k_n = 0.0;
  /// f_n before damping (the force damping multiplies by 1 + a δ̇), N.
  double f_spring = 0.0;
  /// f_spring is kv V, linear in V (true until power_law or viscoelastic clears it):
  /// the tilt stiffness of the discrete stepper is then k_n itself, else the secant f_n/V.
  bool linear_normal_law = true;
  double theta_n = 0.0;    ///< θ_n from the bristle stage (its state), rad
  double theta_dot = 0.0;  ///< θ̇_n from the bristle stage, rad/s

  PairStateRates rates;  ///< state rates, each written by the effect that owns the state
};

/// The regularised direction, sign and saturation of MODEL.md §3.
Eigen::Vector3d dirEps(const Eigen::Vector3d& v, double v_eps);
double sgnEps(double omega, double v_eps, double r_gyr);
Eigen::Vector3d saturate(const Eigen::Vector3d& x, double max_norm);
double saturate(double x, double max_abs);
/// P = I − n nᵀ, the projector onto the contact plane of normal n.
Eigen::Matrix3d planeProjector(const Eigen::Vector3d& n);
/// The contact area A of cv, or V/d where the volume method leaves it out (0 without
/// contact), m².
double contactArea(const volume::ContactVolume& cv);

class Effect {
 public:
  virtual ~Effect() = default;

  virtual std::string_view id() const = 0;
  virtual const std::vector<ParameterSpec>& parameterSpecs() const = 0;
  virtual Stage stage() const = 0;
  /// Ids of the effects this one needs in the same model.
  virtual std::vector<std::string_view> requiredEffects() const { return {}; }
  virtual std::unique_ptr<Effect> clone() const = 0;

  /// The states this effect owns, in the order they sit in the pair state from
  /// stateOffset() on (MODEL.md §3 "State handling").
  virtual const std::vector<StateSlot>& stateSlots() const;
  /// Index of this effect's first state in the pair state, given by the model that holds it.
  int stateOffset() const { return state_offset_; }
  void setStateOffset(int offset) { state_offset_ = offset; }

  /// A relation between this effect's parameters and those of other effects in `model` that
  /// the values break, in words naming both parameters; empty when it holds.
  /// @pre the effects of requiredEffects() are in `model`
  virtual std::string brokenRelation(const Model& /*model*/) const { return {}; }
  /// The relations of brokenRelation() that are inequalities p ≥ q, for the fit to enforce by
  /// its parametrisation; every q is a parameter of an effect in requiredEffects().
  virtual std::vector<ParameterRelation> relations() const { return {}; }

  /// Distributed friction (Model::checkDistributedFriction): does this effect integrate its
  /// friction pointwise over the δ map (ContactContext::field)?
  virtual bool integratesDistributedFriction() const { return false; }
  /// Why this effect cannot be used with distributed friction; empty when it can.
  virtual std::string_view distributedFrictionConflict() const { return {}; }

  /// How the discrete stepper takes this effect's share (StepForm; kExplicit by default, so
  /// that an effect without a linearisation is named, not silently left explicit).
  virtual StepForm stepForm() const { return StepForm::kExplicit; }
  /// kLinearised: add this effect's part of the step's linear form to `terms`, from the
  /// context of both passes at the step's start (docs/DISCRETE.md §2). @pre ctx.cv->volume > 0
  virtual void linearise(const ContactContext& /*ctx*/, StepTerms& /*terms*/) const {}

  /// The coefficient of restitution this effect alone gives a head-on impact at normal
  /// approach speed `approach` (m/s, > 0): 1 for an effect that dissipates nothing in one
  /// (the default), or whose loss has no closed form. The discrete stepper predicts rebounds
  /// from it (Model::impactRestitution) to decide which impacts to resolve.
  virtual double restitution(double /*approach*/) const { return 1.0; }

  /// Pass 1: write this effect's parameters into the context.
  virtual void configure(ContactContext& /*ctx*/) const {}
  /// Pass 2: refine derived quantities, write own state rates, return own wrench share.
  /// @pre ctx.cv->volume > 0
  virtual Wrench apply(ContactContext& /*ctx*/) const { return {}; }
  /// After an accepted integration step: discrete updates of this effect's states.
  virtual void settle(const ContactContext& /*ctx*/, PairState& /*state*/) const {}
  /// Before geometry: the payload pose actually used for the volume (misalignment).
  virtual Eigen::Isometry3d adjustPayloadPose(const Eigen::Isometry3d& X_WA,
                                              const Eigen::Isometry3d& /*X_WB*/) const {
    return X_WA;
  }

  std::span<const double> parameters() const { return values_; }
  double parameter(std::size_t i) const {
    assert(i < values_.size());
    return values_[i];
  }
  /// @pre i < parameterSpecs().size(); bounds are checked by Model::setParameters
  void setParameter(std::size_t i, double value) {
    assert(i < values_.size());
    values_[i] = value;
  }

 protected:
  /// Call from the derived constructor with the derived class's specs.
  void initialiseParameters(const std::vector<ParameterSpec>& specs);

 private:
  std::vector<double> values_;
  int state_offset_ = -1;  ///< −1 until a model holds the effect (or it has no states)
};

}  // namespace vcontact::dynamics
