#pragma once
// The linearisation of one contact patch's wrench for the discrete stepper (docs/DISCRETE.md).
//
// The wrench w = (f, τ) on body A at the patch's centroid p_c is a function of the relative
// twist ξ = (v_c, ω) of A against B at p_c (MODEL.md §2) and of the relative pose. Over one
// step of length h the stepper uses
//
//   w⁺ = w0 + D (ξ⁺ − ξ0) + h K ξ⁺        (the relative displacement over the step is h ξ⁺)
//
// with the normal n, p_c, the area A and J_s of the step's start; the friction laws read the
// normal force f_n, the stick measure s, μ_max and the Contensou factors of the step's start
// (frozen). The bristle states are advanced implicitly with the step (PatchStep), so their
// force is affine in ξ⁺ too. Each effect writes its own terms (Effect::stepForm, linearise);
// those that have none (adhesion, expression effects: Model::explicitEffects) stay explicit,
// their share in w0 only.

#include <Eigen/Core>

#include "dynamics/model.hpp"

namespace vcontact::dynamics {

/// ∂w/∂ξ and ∂w/∂(du, dθ) of the lumped effects (docs/DISCRETE.md §2); rows and columns are
/// (force, torque) × (v_c, ω) and (du, dθ), world frame, about p_c.
struct ContactJacobians {
  /// Velocity part. Coulomb friction, the Coulomb spin torque and the bristles' pull term use
  /// the secant of dir_ε, sgn_ε about ξ0 (the magnitude 1/max(|v_t|, v_ε) frozen): exact
  /// across the slip, and along it D ξ0 equals the force at ξ0.
  Matrix6d D = Matrix6d::Zero();
  /// Position part: the normal stiffness kv' A n nᵀ and the tilt stiffness kv' P J_s P / d̄
  /// (d̄ = V/A), kv' = k_n (1 + a δ̇_c) (zero when the damping clamp holds f_n at 0), negated;
  /// k_n = ∂f_n/∂V of the normal law (ContactContext::k_n: kv, or power_law's p f_n/V, times
  /// viscoelastic's ratio r). Adhesion's share and viscoelastic's state q stay explicit.
  Matrix6d K = Matrix6d::Zero();
};

/// The Jacobians at contact cv (in contact), motion and state, for a model with lumped
/// friction. The bristle terms are the instantaneous ones (state fixed).
ContactJacobians contactJacobians(const Model& model, const volume::ContactVolume& cv,
                                  const RelativeMotion& motion, const PairState& state);

/// One patch over one step: w⁺ = c + L ξ⁺, and the bristle states at the step's end
/// z⁺ = z_c + Z ξ⁺, θ⁺ = theta_c + Theta ξ⁺ (meaningful when `bristle`).
struct PatchStep {
  Vector6d c = Vector6d::Zero();
  Matrix6d L = Matrix6d::Zero();
  ContactResult start;      ///< the model at the step's start: wrench w0, state rates
  ImplicitStates implicit;  ///< the states advanced implicitly (bristle's z, θ_n), if any
};

/// The step of length h (> 0) of a patch in contact (cv.inContact()), lumped friction.
/// about_end: cv and motion are not the step's start but a guess of its end reached from the
/// start by h ξ0 (ξ0 the twist of `motion`; a Newton iteration of the step, the state still the
/// start's), so that the displacement over the step is h (ξ⁺ − ξ0) from there: c gains
/// −h K ξ0.
void linearisePatch(const Model& model, const volume::ContactVolume& cv,
                    const RelativeMotion& motion, const PairState& state, double h, PatchStep& out,
                    bool about_end = false);

/// The same from an evaluation already made at (cv, motion, state): `ctx` is its context
/// (Model::evaluate's `context`, whose cv must still be alive) and out.start its result. The
/// discrete stepper passes the evaluation of the step's query, which is the step's start: one
/// evaluation of the model per step instead of three, and the same numbers.
void linearisePatch(const Model& model, const ContactContext& ctx, const RelativeMotion& motion,
                    double h, PatchStep& out, bool about_end = false);

}  // namespace vcontact::dynamics
