#pragma once
// Dormand–Prince 5(4) (`"integrator": "dopri5"`, docs/SCENARIO.md): Boost.Odeint's
// runge_kutta_dopri5 (FSAL), error-controlled with the scenario's tolerances
// (dopri5_control.hpp). Steps are shortened to land on output times, so outputs are exact
// states, not interpolations. After each accepted step the quaternions are renormalised and
// every pair state is settled (Model::settle: z projected onto the contact plane, reset on loss
// of contact, dwell jumps): Dopri5Steps, which the discrete stepper's resolved intervals share.

#include "dynamics/steppers/stepper.hpp"
#include "dynamics/trackers/impact_tracker.hpp"

namespace vcontact::dynamics {

class Dopri5Control;

/// The attempt and the aftermath of one Dormand–Prince step, for Dopri5Stepper and the
/// resolved intervals of DiscreteStepper.
class Dopri5Steps {
 public:
  using State = MotionEquations::State;

  Dopri5Steps(MotionEquations& equations, ImpactTracker& impacts)
      : eq_(equations), impacts_(impacts) {}

  /// One attempt of dt from (x, t): accepted, x, dxdt and t advance and dt holds the
  /// controller's proposal; rejected, the rejection is counted and dt holds the smaller step.
  /// @throws SimulationError when the step falls below the scenario's min_step
  bool attempt(Dopri5Control& control, State& x, State& dxdt, double& t, double& dt,
               SimulationSummary& summary);
  /// After an accepted step: the contacts at x, the checks, the pair states' discrete updates
  /// and the impact tracker.
  void accepted(State& x, State& dxdt, double t);

 private:
  MotionEquations& eq_;
  ImpactTracker& impacts_;
};

class Dopri5Stepper final : public Stepper {
 public:
  Dopri5Stepper(MotionEquations& equations, ImpactTracker& impacts)
      : eq_(equations), steps_(equations, impacts) {}

  void run(State& x, State& dxdt, double& t, const OutputFn& on_output,
           const ProgressFn& on_progress, SimulationSummary& summary) override;

 private:
  MotionEquations& eq_;
  Dopri5Steps steps_;
};

}  // namespace vcontact::dynamics
