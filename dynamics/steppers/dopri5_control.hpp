#pragma once
// The error control of the Dormand–Prince runs, shared by Dopri5Stepper and the resolved
// intervals of the discrete stepper (DiscreteStepper::resolveInterval): odeint's controlled
// Dormand–Prince stepper and the one rule added to it. Included by the simulator's sources only
// (odeint is a heavy header).

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <vector>

namespace vcontact::dynamics {

class Dopri5Control {
 public:
  using State = std::vector<double>;

  Dopri5Control(double abs_tol, double rel_tol)
      : stepper_(boost::numeric::odeint::make_controlled(
            abs_tol, rel_tol, boost::numeric::odeint::runge_kutta_dopri5<State>())) {}

  // One attempt of a step of dt from (x, t), dxdt = f(x, t) on entry (first same as last).
  // Accepted: x, dxdt and t advance, dt holds the controller's proposal for the next step and
  // the result is true. Rejected: x and t stay, dt holds the smaller step to try next.
  template <class System>
  bool attempt(System&& system, State& x, State& dxdt, double& t, double& dt) {
    dt_tried_ = dt;
    const bool accepted = stepper_.try_step(system, x, dxdt, t, dt) != boost::numeric::odeint::fail;
    just_rejected_ = just_rejected_ || !accepted;
    return accepted;
  }

  // The next step after an accepted one, from the caller's choice `next`: right after a
  // rejection no larger than the step just accepted (Hairer, Nørsett & Wanner I, §II.4: at the
  // stability limit of a stiff contact this avoids the grow–reject cycle of the plain
  // controller).
  double afterAccept(double next) {
    if (just_rejected_) next = std::min(next, dt_tried_);
    just_rejected_ = false;
    return next;
  }

 private:
  decltype(boost::numeric::odeint::make_controlled(
      0.0, 0.0, boost::numeric::odeint::runge_kutta_dopri5<State>())) stepper_;
  double dt_tried_ = 0.0;
  bool just_rejected_ = false;
};

}  // namespace vcontact::dynamics
