// The loads' and springs' part of the equations of motion: their wrenches on the bodies at
// every right-hand side (motion_equations.hpp, loads.hpp).

#include "dynamics/motion_equations.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics {

// Every load and spring names bodies of the scenario; a spring joins two different ones.
void MotionEquations::checkLoads() const {
  const std::size_t n = scenario_.bodies.size();
  for (const ExternalLoad& l : scenario_.loads) {
    if (l.body >= n) throw InputError("load '" + l.name + "'", "names no body of the scenario");
    if (l.kind == LoadKind::kTable && (!l.table || l.table->t.empty())) {
      throw InputError("load '" + l.name + "'", "has an empty table");
    }
  }
  for (const BodySpring& s : scenario_.springs) {
    if (s.a >= n || s.b >= n || s.a == s.b) {
      throw InputError("spring '" + s.name + "'", "needs two different bodies of the scenario");
    }
  }
}

// The loads' and springs' wrenches at kin_ into force_ and torque_ (about each Bcm) and
// last_loads_. A fixed or prescribed body takes them as a support would: they are reported
// and move nothing.
void MotionEquations::applyLoads(double t) {
  last_loads_.resize(scenario_.loads.size() + scenario_.springs.size());
  std::size_t k = 0;
  for (const ExternalLoad& l : scenario_.loads) {
    const LoadOutput& o = last_loads_[k++] = loadWrench(l, kin_[l.body], t);
    force_[l.body] += o.wrench.f_W;
    torque_[l.body] += o.wrench.tau_W + (o.p_W - kin_[l.body].p_WBcm).cross(o.wrench.f_W);
  }
  for (const BodySpring& s : scenario_.springs) {
    const LoadOutput& o = last_loads_[k++] = springWrench(s, kin_[s.a], kin_[s.b]);
    force_[s.a] += o.wrench.f_W;
    torque_[s.a] += o.wrench.tau_W + (o.p_W - kin_[s.a].p_WBcm).cross(o.wrench.f_W);
    force_[s.b] -= o.wrench.f_W;
    torque_[s.b] -= o.wrench.tau_W + (o.q_W - kin_[s.b].p_WBcm).cross(o.wrench.f_W);
  }
}

// Every load's and spring's wrench at kin_, summed into force_ and torque_ from zero (the
// discrete step's explicit part).
void MotionEquations::loadWrenches(double t) {
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    force_[i].setZero();
    torque_[i].setZero();
  }
  applyLoads(t);
}

}  // namespace vcontact::dynamics
