// The Dormand–Prince run of a scenario (`"integrator": "dopri5"`, docs/SCENARIO.md):
// error-controlled steps shortened to land on the output times, the checks and the pair
// states' discrete updates after each accepted step. Its attempt and aftermath serve the
// resolved intervals of the discrete stepper too (simulator_discrete_impacts.cpp).

#include "dynamics/dopri5_control.hpp"
#include "dynamics/simulator.hpp"

namespace vcontact::dynamics {

void Simulator::runDopri5(State& x, State& dxdt, double& t, const OutputFn& on_output,
                          const ProgressFn& on_progress, SimulationSummary& summary) {
  const SimulationSettings& set = scenario_.settings;
  Dopri5Control control(set.abs_tol, set.rel_tol);
  const double interval = 1.0 / set.output_rate_hz;
  long next_output = 1;
  double dt = set.initial_step;
  while (t < set.duration) {
    const double t_target = std::min(static_cast<double>(next_output) * interval, set.duration);
    const double dt_free = std::min(dt, set.max_step);
    const bool capped = t_target - t < dt_free;
    double dt_try = capped ? t_target - t : dt_free;
    if (!tryDopri5(control, x, dxdt, t, dt_try, summary)) {
      dt = dt_try;
      continue;
    }
    ++summary.steps;
    dt = control.afterAccept(capped ? std::max(dt_try, dt_free) : dt_try);
    afterDopri5Step(x, dxdt, t);
    if (t >= t_target - kOutputTimeSlack * interval) {
      t = t_target;
      on_output(snapshot(x, t, output_depths_));
      ++next_output;
    }
    on_progress(t);
  }
}

bool Simulator::tryDopri5(Dopri5Control& control, State& x, State& dxdt, double& t, double& dt,
                          SimulationSummary& summary) {
  auto system = [this](const State& x, State& dxdt, double t) { rhs(x, dxdt, t); };
  if (control.attempt(system, x, dxdt, t, dt)) return true;
  ++summary.rejected_steps;
  if (dt < scenario_.settings.min_step) throw stepCollapse(t, dt, "");
  return false;
}

void Simulator::afterDopri5Step(State& x, State& dxdt, double t) {
  if (x != last_x_) rhs(x, dxdt, t);
  check(x, t);
  if (settle(x, t)) rhs(x, dxdt, t);
  impacts_.observe(t, kin_, last_pairs_);
}

}  // namespace vcontact::dynamics
