#pragma once
// Distributed (pointwise) Coulomb friction over the Winkler pressure field, the reference for
// the lumped Coulomb + spin + contensou friction of MODEL.md §3 (see DISTRIBUTED_FRICTION.md).
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
// ---------------------------------------------------------------------------------------
// Closed form: flat circular punch, radius R, uniform pressure p = N/(πR²), sliding at v
// and spinning at ω about its axis, ε = v/(ωR). (Derived here; it agrees with MODEL.md §5.)
//
// 1. Every point turns about the instantaneous centre s₀ = (n × v)/ω at distance b = εR from
//    the centre O: v(s) = ω n × (s − s₀), so t(s) = −μp n × (s − s₀)/|s − s₀|.
// 2. With Φ(s₀) = ∫_D |s − s₀| dS (a function of b only): ∫_D (s − s₀)/|s − s₀| dS = −∇Φ,
//    hence  F = μp Φ'(b)  (opposite to v)  and  M = ∫ s × t dS = −μp (Φ − b Φ'(b)) n,
//    because s·(s − s₀) = |s − s₀|² + s₀·(s − s₀).
// 3. Φ in polar coordinates (ρ, θ) about s₀: Φ = ∫ dθ ∫ ρ² dρ = ⅓ ∫ ρ(θ)³ dθ over the chord.
//    b < R: ρ(θ) = −b cos θ + q, q = √(R² − b² sin²θ); odd terms cancel, k = b/R:
//      Φ = (4R³/3) ∫₀^{π/2} (Δ³ + 3k² cos²θ Δ) dθ,  Δ = √(1 − k² sin²θ)
//        = (4R³/9) [(7 + k²) E − 4 (1 − k²) K]
//    using ∫Δ³ = [2(2 − k²)E − (1 − k²)K]/3 and ∫cos²θ Δ = [(1 + k²)E − (1 − k²)K]/(3k²).
//    b > R: the chord runs from ρ₁ = b cos θ − q to ρ₂ = b cos θ + q, |sin θ| ≤ R/b; with
//    b sin θ = R sin φ, κ = R/b = 1/ε:
//      Φ = (4R³/3) [κ ∫₀^{π/2} cos⁴φ/Δ_κ dφ + (3/κ) ∫₀^{π/2} cos²φ Δ_κ dφ]
//        = (4R³/9) [ε (ε² + 7) E − (ε² − 1)(ε² + 3)/ε · K]     (modulus κ)
//    using ∫cos⁴φ/Δ = [(4κ² − 2)E + (1 − κ²)(2 − 3κ²)K]/(3κ⁴).
// 4. Differentiating with dE/dk = (E − K)/k, dK/dk = E/(k(1 − k²)) − K/k gives, with
//    K, E of modulus ε for ε ≤ 1 and of modulus 1/ε for ε ≥ 1:
//      ε ≤ 1:  F/μN  = 4/(3πε) [(1 + ε²) E − (1 − ε²) K]
//              M/μNR = 4/(9π) [(4 − 2ε²) E − (1 − ε²) K]
//      ε ≥ 1:  F/μN  = 4/(3π) [(1 + ε²) E − (ε² − 1) K]
//              M/μNR = 4/(9πε) [2ε² (2 − ε²) E + (2ε² − 3)(ε² − 1) K]
//    (both branches give F/μN = 8/(3π), M/μNR = 8/(9π) at ε = 1).
// Limits. Pure spin (ε = 0): F = 0, M = (2/3) μNR; small ε: F/μN = ε − ε³/8 + …
//         Pure sliding (ε → ∞): F/μN = 1 − 1/(8ε²) + …, M/μNR = 1/(4ε) + …
//         (M: the in-line slip ω x of a point at x tilts its traction by ωx/v, so
//          M ≈ μp (ω/v) ∫x² dS = μNR/(4ε).)
//
// Numerics. std::comp_ellint_1/2(k) take the modulus k (not m = k²). The brackets cancel:
// F for small ε (O(1) terms, O(ε²) result) and M for large ε (O(ε⁴) terms, O(1) result);
// there the same expressions are evaluated as power series in x = ε² (x = 1/ε²) obtained
// from K = (π/2) Σ aₙ xⁿ, E = (π/2) Σ aₙ xⁿ/(1 − 2n), aₙ = (C(2n, n)/4ⁿ)², with the
// cancelling leading coefficients removed exactly.
// ---------------------------------------------------------------------------------------

#include "dynamics/effect.hpp"
#include "dynamics/wrench.hpp"
#include "volume/columns.hpp"
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
/// @param cv     the contact from volume::columnsContact (p_c, n, V, area)
/// @param field  the δ map of the same call; every cell has dS = field.cellArea (cv.area / cells
///               for a field without one)
/// @param mu     friction coefficient, ≥ 0
/// @param v_eps  regularisation speed of dir_ε, m/s, > 0 (ModelSettings::v_eps)
/// @pre cv.inContact() and field.points_W.size() == field.depth.size() > 0
/// @throws std::invalid_argument when the inputs are not finite or in range, or when the field
///         does not belong to cv (Σ δ dS ≠ V to 1e-9)
DistributedFriction distributedFriction(const volume::ContactVolume& cv,
                                        const volume::ColumnField& field, const PressureLaw& law,
                                        const RelativeMotion& motion, double mu, double v_eps);

/// Dimensionless friction of a flat punch, see the header comment.
struct PunchFriction {
  double force;   ///< F / (μ N)
  double torque;  ///< M / (μ N R)
};

/// The closed form for a uniformly loaded flat circular punch, ε = v/(ωR) ∈ [0, ∞]
/// (ε = ∞: pure sliding). @throws std::invalid_argument for ε < 0 or NaN
PunchFriction flatPunchFriction(double eps);

/// The lumped Coulomb + spin + contensou friction of MODEL.md §3 for the same punch
/// (v_avg ≫ v_ε): F/μN = C_v = ε/√(ε² + g²), M/μNR = g C_ω = g²/√(ε² + g²), g = r_gyr/R
/// (g = 1/√2 for a flat punch, MODEL.md §5). @throws std::invalid_argument for ε < 0, g ≤ 0
PunchFriction lumpedPunchFriction(double eps, double rGyrOverR);

}  // namespace vcontact::dynamics
