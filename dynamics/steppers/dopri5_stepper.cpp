#include "dynamics/steppers/dopri5_stepper.hpp"

#include "dynamics/steppers/dopri5_control.hpp"

namespace vcontact::dynamics {

void Dopri5Stepper::run(State& x, State& dxdt, double& t, const OutputFn& on_output,
                        const ProgressFn& on_progress, SimulationSummary& summary) {
  const SimulationSettings& set = eq_.scenario().settings;
  Dopri5Control control(set.abs_tol, set.rel_tol);
  const double interval = 1.0 / set.output_rate_hz;
  long next_output = 1;
  double dt = set.initial_step;
  while (t < set.duration) {
    const double t_target = std::min(static_cast<double>(next_output) * interval, set.duration);
    const double dt_free = std::min(dt, set.max_step);
    const bool capped = t_target - t < dt_free;
    double dt_try = capped ? t_target - t : dt_free;
    if (!steps_.attempt(control, x, dxdt, t, dt_try, summary)) {
      dt = dt_try;
      continue;
    }
    ++summary.steps;
    dt = control.afterAccept(capped ? std::max(dt_try, dt_free) : dt_try);
    steps_.accepted(x, dxdt, t);
    if (t >= t_target - kOutputTimeSlack * interval) {
      t = t_target;
      on_output(eq_.snapshot(x, t, eq_.outputDepths()));
      ++next_output;
    }
    on_progress(t);
  }
}

bool Dopri5Steps::attempt(Dopri5Control& control, State& x, State& dxdt, double& t, double& dt,
                          SimulationSummary& summary) {
  auto system = [this](const State& x, State& dxdt, double t) { eq_.rhs(x, dxdt, t); };
  if (control.attempt(system, x, dxdt, t, dt)) return true;
  ++summary.rejected_steps;
  if (dt < eq_.scenario().settings.min_step) throw eq_.stepCollapse(t, dt, "");
  return false;
}

void Dopri5Steps::accepted(State& x, State& dxdt, double t) {
  if (!eq_.isLatest(x)) eq_.rhs(x, dxdt, t);
  eq_.check(x, t);
  if (eq_.settle(x, t)) eq_.rhs(x, dxdt, t);
  impacts_.observe(t, eq_.bodies(), eq_.pairs());
}

}  // namespace vcontact::dynamics
