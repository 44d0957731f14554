#pragma once
// Distributed (pointwise) Coulomb friction over the Winkler pressure field, the reference for
// the lumped Coulomb + spin + contensou friction of MODEL.md §3 (see docs/DISTRIBUTED_FRICTION.md;
// its closed form for a flat punch is validation/punch_friction.hpp).
//
// Frames and units. Everything is in the world frame W, SI units. The contact plate S is the
// plane through p_c normal to n (MODEL.md §1); a column of the δ map at world point q_W meets
// S at s = p_c + ρ, ρ = P (q_W − p_c), P = I − n nᵀ. Forces act on body A;
// body B gets the opposite.
//
//   pressure     p(s) = kv δ(s) max(0, 1 + a δ̇_c)                          [Pa]
//                (∫_S p dS = kv V (1 + a δ̇_c) = the lumped f_n of stiffness + damping)
//   slip         v(s) = P (v_c + ω × ρ) = v_t + ω_n n × ρ                   [m/s]
//   traction     t(s) = −μ p(s) dir_ε(v(s)),  dir_ε(v) = v / max(|v|, v_ε)  [Pa]
//   force        f_t  = ∫_S t dS                  (in the plate)             [N]
//   torque       τ    = ∫_S ρ × t dS  about p_c   (along n)                  [N·m]
//

#include "dynamics/effect.hpp"
#include "dynamics/wrench.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::dynamics {

/// The normal pressure law consistent with stiffness + damping (MODEL.md §3).
struct PressureLaw {
  double kv = 0.0;  ///< N/m³, > 0
  double a = 0.0;   ///< s/m, damping factor (0 without damping), ≥ 0
};

struct DistributedFriction {
  Wrench wrench;           ///< on body A: friction force in the plate, torque about p_c along n
  double f_n = 0.0;        ///< ∫ p dS, N: equals the lumped f_n
  double cell_area = 0.0;  ///< dS of one column, m²
  int cells = 0;           ///< columns with δ > 0
};

/// Pointwise Coulomb friction integrated over the columns δ map (midpoint rule, one column
/// per cell, as the columns backend integrates V).
/// @param cv     the contact from volume::computeContact (p_c, n, V, area)
/// @param field  the δ map of the same call; every cell has dS = field.cell_area (cv.area / cells
///               for a field without one)
/// @param mu     friction coefficient, ≥ 0
/// @param v_eps  regularisation speed of dir_ε, m/s, > 0 (ModelSettings::v_eps)
/// @pre cv.inContact() and field.points_W.size() == field.depth.size() > 0
/// @throws std::invalid_argument when the inputs are not finite or in range, or when the field
///         does not belong to cv (Σ δ dS ≠ V to 1e-9)
DistributedFriction distributedFriction(const volume::ContactVolume& cv,
                                        const volume::DepthField& field, const PressureLaw& law,
                                        const RelativeMotion& motion, double mu, double v_eps);

}  // namespace vcontact::dynamics
