#pragma once
// One interface over the integrators of a run (SimulationSettings::integrator,
// docs/SCENARIO.md). Each integrates the equations of motion (motion_equations.hpp) from a
// settled initial state to the scenario's duration, outputs at every output time
// k / output_rate_hz and reports after each accepted step:
//
// - Dopri5Stepper (dopri5_stepper.hpp): Dormand–Prince 5(4), Boost.Odeint, error-controlled;
//   steps shortened to land on the output times, so outputs are exact states.
// - BdfStepper (bdf_stepper.hpp): variable-order BDF, SUNDIALS CVODE, for stiff friction
//   states; free steps, outputs from each step's interpolating polynomial.
// - DiscreteStepper (discrete_stepper.hpp, docs/DISCRETE.md): a linearly implicit step of
//   fixed size about each pair's contact Jacobians, impacts resolved by Dormand–Prince
//   intervals or by the implicit step itself, bodies at rest put to sleep.
//
// The run loop (simulator.hpp) makes the one its scenario names and owns what every run has
// whatever the integrator (the first output, the impact tracker, the summary, interruption).

#include <functional>

#include "dynamics/motion_equations.hpp"
#include "dynamics/simulation_output.hpp"

namespace vcontact::dynamics {

/// Output times k / rate are reached by shortened steps; a step that ends within this fraction
/// of the output interval of it counts as landing on it (round-off of t + dt).
inline constexpr double kOutputTimeSlack = 1e-9;

class Stepper {
 public:
  using State = MotionEquations::State;
  using OutputFn = std::function<void(const Snapshot&)>;
  using ProgressFn = std::function<void(double t)>;

  virtual ~Stepper() = default;

  /// From (x, t), with dxdt = f(x, t) and the equations' latest evaluation at x, to the
  /// scenario's duration: on_output at every output time after t, on_progress after each
  /// accepted step (either may throw to stop the run), the summary's step counts.
  /// @throws SimulationError on a failure, with t the latest accepted time
  virtual void run(State& x, State& dxdt, double& t, const OutputFn& on_output,
                   const ProgressFn& on_progress, SimulationSummary& summary) = 0;
};

}  // namespace vcontact::dynamics
