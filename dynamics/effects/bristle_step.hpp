#pragma once
// The bristle law made affine in the twist ξ⁺ over a step h of the discrete stepper
// (docs/DISCRETE.md §2.6): what bristle (the force and its states z, θ_n) and spin
// (the bristle spin torque) share. The states are advanced by backward Euler with the step's
// start frozen in s, the pull terms' secants and the saturation scale; h = 0 gives the
// instantaneous Jacobian at fixed states.
#include <algorithm>
#include <cmath>

#include "dynamics/effect.hpp"

namespace vcontact::dynamics {

/// β = 1 / (1 + h (1 − s) σ0/σ1): the relaxation of a state over the step.
inline double bristleRelaxation(const ContactContext& ctx, double h) {
  return 1.0 / (1.0 + h * (1.0 - ctx.s) * ctx.sigma0 / ctx.sigma1);
}

/// The torsional bristle at the step's start: θ̇_n = e_ω ω_n + (relaxation), e_ω = s +
/// (1 − s) g_θ with the pull term's secant g_θ, and the saturation scale of its torque.
struct BristleTorsion {
  double e_w = 0.0;
  double scale_w = 1.0;
};

inline BristleTorsion bristleTorsion(const ContactContext& ctx) {
  const double s = ctx.s, s0 = ctx.sigma0, s1 = ctx.sigma1, r = ctx.r_gyr;
  const double v_eps = ctx.settings.v_eps;
  // (C_ω μ_C / (σ1 r)) sgn_ε(ω_n) = g_θ ω_n
  const double g_w =
      r > 0.0 ? ctx.C_w * ctx.mu_C / (s1 * r * std::max(std::abs(ctx.omega_n), v_eps / r)) : 0.0;
  BristleTorsion b;
  b.e_w = s + (1.0 - s) * g_w;
  const double m0 = s * s0 * ctx.theta_n + s1 * b.e_w * ctx.omega_n;
  const double limit_w = r > 0.0 ? ctx.mu_max / r : 0.0;
  b.scale_w = std::abs(m0) > limit_w && m0 != 0.0 ? limit_w / std::abs(m0) : 1.0;
  return b;
}

}  // namespace vcontact::dynamics
