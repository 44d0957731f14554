#pragma once
// Variable-order BDF (`"integrator": "bdf"`, docs/SCENARIO.md), SUNDIALS CVODE
// (bdf_integrator.hpp), for stiff friction states. Steps are free (up to max_step) and outputs
// come from each step's interpolating polynomial. The settle updates restart the integrator
// when they move a state by more than its tolerance; smaller ones are within the integration
// error and are applied by every reader of the state anyway. CVODE's failures are told in the
// words of the other integrators: time, pair or body, quantity.

#include <string>

#include "dynamics/steppers/stepper.hpp"

namespace vcontact::dynamics {

class BdfError;

class BdfStepper final : public Stepper {
 public:
  explicit BdfStepper(MotionEquations& equations) : eq_(equations) {}

  void run(State& x, State& dxdt, double& t, const OutputFn& on_output,
           const ProgressFn& on_progress, SimulationSummary& summary) override;

 private:
  bool rhsFinite(const double* x, double* dxdt, double t);
  SimulationError failure(const BdfError& e, double t_last) const;

  MotionEquations& eq_;
  State rhs_x_, rhs_dxdt_;  ///< rhsFinite()'s copies of CVODE's vectors
  std::string non_finite_;  ///< the state whose rate was last found not finite
};

}  // namespace vcontact::dynamics
