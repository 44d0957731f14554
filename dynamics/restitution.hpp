#pragma once
// The coefficient of restitution of a head-on impact under a normal force f_s(δ) (1 + a δ̇),
// any elastic law f_s and any shape (docs/MODEL.md §5): with α = a v_in, e solves
//
//   α (1 + e) = ln((1 + α) / (1 − α e)),
//
// since m v dv / (1 + a v) = −f_s(δ) dδ integrates to the same elastic work on the way in and
// out. The discrete stepper predicts an impact's rebound with it (docs/DISCRETE.md §5).

namespace vcontact::dynamics {

/// e ∈ (0, 1] for α = a v_in ≥ 0: 1 at α = 0, 1 − 2α/3 for small α, 1/α for large α.
double dampedRestitution(double alpha);

}  // namespace vcontact::dynamics
