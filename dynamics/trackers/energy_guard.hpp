#pragma once
// The blow-up guard of a run (StopCause::kBlowUp): the free bodies may not hold more kinetic
// energy than the scenario can have given them, by a wide margin.
//
// Gravity is conservative and every contact effect of a passive model (stiffness, damping,
// friction, bristles) stores or dissipates energy, so the kinetic energy of the free bodies
// obeys
//
//   T(t) ≤ A(t) = T(0) + W_g(t) + E_c(0) + W_p(t) + W_l(t)
//
// with T = Σ ½ m v² + ½ ωᵀ I_W ω over the free bodies, W_g(t) = Σ m g·(p(t) − p(0)) the work
// of gravity, E_c(0) ≤ Σ f_n·depth the energy stored in the contacts at t = 0 (a force that
// grows with the depth stores at most f_n·depth), and W_p(t) the work the fixed and prescribed
// bodies put into their contacts (∫ max(0, P) dt, P the power of the contact wrench at the
// prescribed body's velocity; rectangle rule over the accepted steps), and W_l(t) the work of
// the external loads and springs (∫ max(0, P) dt likewise, P their power on the free bodies,
// which also counts a spring's stored energy as it is released). An explicit integrator
// at its stability limit, or any integrator with tolerances too loose for a very stiff
// contact, can break this: the bodies gain energy at each impact. The run stops when
//
//   T(t) > kBlowUpFactor · max(A(t), 0) + E_floor,   E_floor = Σ ½ m (kBlowUpFloorSpeed)²
//
// The factor leaves room for the integration error of A and T (a few tolerances) and for the
// rectangle rule of W_p; the floor keeps a body that starts at rest from being stopped on the
// round-off of its first steps. An active effect (an expression effect that pushes along the
// slip) can exceed the bound legitimately: docs/SCENARIO.md, "Stopped runs".

#include <string>
#include <vector>

#include "dynamics/loads.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/scenario.hpp"

namespace vcontact::dynamics {

struct PairOutput;

/// T may exceed ten times the energy available before the run is called blown up.
constexpr double kBlowUpFactor = 10.0;
/// m/s: kinetic energy below a free body's ½ m (1 cm/s)² is never a blow-up.
constexpr double kBlowUpFloorSpeed = 0.01;

class EnergyGuard {
 public:
  /// Takes the energy at t = 0.
  /// @param kin0 every body's kinematics at t = 0 (Scenario::bodies order)
  /// @param pairs0 every pair's contact at t = 0 (Scenario::pairs order)
  EnergyGuard(const Scenario& scenario, const std::vector<BodyKinematics>& kin0,
              const std::vector<PairOutput>& pairs0);

  /// After an accepted step ending at t: adds the prescribed bodies' and the loads' work since
  /// the last call and checks the bound.
  /// @param loads the loads' then the springs' wrenches (Scenario::loads, ::springs order)
  /// @return "" within the bound; else the message (body of the largest kinetic energy, T, A
  ///         and its parts), without the time
  std::string check(const std::vector<BodyKinematics>& kin, const std::vector<PairOutput>& pairs,
                    const std::vector<LoadOutput>& loads, double t);

 private:
  double kineticEnergy(std::size_t body, const BodyKinematics& k) const;
  double prescribedPower(const std::vector<BodyKinematics>& kin,
                         const std::vector<PairOutput>& pairs) const;
  double loadPower(const std::vector<BodyKinematics>& kin,
                   const std::vector<LoadOutput>& loads) const;

  const Scenario& scenario_;
  double kinetic0_ = 0.0;              ///< J, T(0)
  double contact0_ = 0.0;              ///< J, E_c(0) bound
  double floor_ = 0.0;                 ///< J, E_floor
  double work_prescribed_ = 0.0;       ///< J, W_p so far
  double work_loads_ = 0.0;            ///< J, W_l so far
  double t_last_ = 0.0;                ///< s, time of the last check
  std::vector<Eigen::Vector3d> p0_W_;  ///< centres of mass at t = 0, m
};

}  // namespace vcontact::dynamics
