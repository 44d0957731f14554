#include "dynamics/steppers/bdf_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dynamics/steppers/bdf_integrator.hpp"

namespace vcontact::dynamics {
namespace {

// BDF: |q| may drift this far from 1 before the state is rescaled (a restart). The error
// weights of q change by as much, relatively: negligible.
constexpr double kQuaternionNormDrift = 1e-3;

// True when some state moved from `before` to `after` by more than its error tolerance.
bool exceedsTolerance(const MotionEquations::State& before, const MotionEquations::State& after,
                      const SimulationSettings& set) {
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (std::abs(after[i] - before[i]) > set.abs_tol + set.rel_tol * std::abs(before[i])) {
      return true;
    }
  }
  return false;
}

bool allFinite(const MotionEquations::State& v) {
  return std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); });
}

}  // namespace

// The right-hand side for CVODE: false, and the first non-finite rate remembered, when the
// derivative is not finite (CVODE then retries with a shorter step).
bool BdfStepper::rhsFinite(const double* x, double* dxdt, double t) {
  const std::size_t n = eq_.initialState().size();
  rhs_x_.assign(x, x + n);
  rhs_dxdt_.resize(n);
  eq_.rhs(rhs_x_, rhs_dxdt_, t);
  std::copy(rhs_dxdt_.begin(), rhs_dxdt_.end(), dxdt);
  if (allFinite(rhs_dxdt_)) return true;
  const auto bad =
      std::find_if(rhs_dxdt_.begin(), rhs_dxdt_.end(), [](double d) { return !std::isfinite(d); });
  non_finite_ = eq_.stateOwner(static_cast<std::size_t>(bad - rhs_dxdt_.begin()));
  return false;
}

// CVODE's failures in the words of the explicit path: time, pair or body, quantity.
SimulationError BdfStepper::failure(const BdfError& e, double t_last) const {
  const double t = std::max(e.time(), t_last);
  if (e.stepCollapse())
    return eq_.stepCollapse(t, std::abs(e.stepSize()), "; BDF: " + std::string(e.what()));
  std::ostringstream s;
  if (e.rhsFailed()) {
    s << stopTime(t) << ", " << non_finite_ << ": the rate of change is not finite at every step "
      << "size tried, down to " << std::abs(e.stepSize()) << " s" << eq_.nonFiniteEffect();
    return SimulationError(t, StopCause::kNonFinite, s.str());
  }
  s << stopTime(t) << eq_.stiffestPair() << ": the implicit (BDF) integrator stopped at step size "
    << std::abs(e.stepSize()) << " s: " << e.what();
  return SimulationError(t, StopCause::kIntegratorFailure, s.str());
}

// CVODE steps freely (up to max_step) and the outputs are read from each step's interpolating
// polynomial. The discrete updates of the pair states are applied by a restart, and only when
// they move some state by more than its error tolerance: smaller ones (the projection of z
// after the normal turned by a step's worth) are within the integration error, and
// Model::evaluate applies them anyway. The quaternions are rescaled only when |q| drifted by
// kQuaternionNormDrift: kinematics() normalises q, and q̇ = ½ (0, ω) ⊗ q turns q at the right
// rate whatever its length, so the drift changes no physics; a restart at every step's worth of
// drift (the relative tolerance) would keep the BDF at order 1.
void BdfStepper::run(State& x, State& /*dxdt*/, double& t, const OutputFn& on_output,
                     const ProgressFn& on_progress, SimulationSummary& summary) {
  const SimulationSettings& set = eq_.scenario().settings;
  const BdfIntegrator::Settings bdf_settings{set.abs_tol,  set.rel_tol,  set.initial_step,
                                             set.max_step, set.min_step, set.duration};
  BdfIntegrator bdf(
      x.size(), [this](double t, const double* x, double* dxdt) { return rhsFinite(x, dxdt, t); },
      bdf_settings, t, x.data());
  const double interval = 1.0 / set.output_rate_hz;
  long next_output = 1;
  State x_out(x.size()), settled(x.size());
  auto count = [&] {
    const BdfIntegrator::Counts c = bdf.counts();
    summary.steps = c.steps;
    summary.rejected_steps = c.rejected;
    summary.jacobian_evaluations = c.jacobians;
  };
  while (t < set.duration) {
    const double t_last = t;
    try {
      t = bdf.step();
    } catch (const BdfError& e) {
      count();
      throw failure(e, t_last);
    }
    count();
    std::copy(bdf.state(), bdf.state() + x.size(), x.begin());
    // The contacts of the last Newton iterate stand for those of x: it converged to within a
    // tenth of the error tolerance of x (CVODE's convergence test), and a fresh evaluation would
    // cost a third of all contact evaluations.
    eq_.check(x, t);
    settled = x;
    eq_.settlePairs(settled, t);
    const bool jumped = exceedsTolerance(x, settled, set) ||
                        eq_.normaliseQuaternions(settled) > kQuaternionNormDrift;
    for (;;) {
      const double t_out = std::min(static_cast<double>(next_output) * interval, set.duration);
      if (t_out > t + kOutputTimeSlack * interval) break;
      bdf.interpolate(std::min(t_out, t), x_out.data());
      on_output(eq_.snapshot(x_out, t_out, eq_.outputDepths()));
      ++next_output;
      if (t_out >= set.duration) break;
    }
    if (jumped) bdf.restart(t, settled.data());
    on_progress(t);
  }
}

}  // namespace vcontact::dynamics
