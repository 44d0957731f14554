// The discrete stepper's hooks of sleeping islands (dynamics/trackers/sleep.hpp, docs/SLEEP.md).

#include <cmath>

#include "dynamics/steppers/discrete_stepper.hpp"

namespace vcontact::dynamics {

// Before the step from t: the tracker sees which pairs touch (the contacts the
// step is assembled from) and which pairs' boxes overlap (the latest broad phase; a pair that
// is always queried counts as near only in contact); the bodies that fall asleep now stop with
// zero velocity, in the state and in the kinematics the step reads.
void DiscreteStepper::sleepBeforeStep(State& x, double t) {
  const std::size_t np = scenario_.pairs.size();
  sleep_contact_.resize(np);
  sleep_near_.resize(np);
  for (std::size_t k = 0; k < np; ++k) {
    sleep_contact_[k] = last_pairs_[k].cv.inContact();
    sleep_near_[k] = sleep_contact_[k] || (eq_.contacts().screened(k) && eq_.contacts().queried(k));
  }
  contactBalance(sleep_balanced_);
  for (const std::size_t i :
       eq_.sleep().update(t, kin_, sleep_contact_, sleep_near_, sleep_balanced_)) {
    std::fill_n(x.begin() + eq_.bodyOffset(i) + 7, 6, 0.0);  // v (3), ω (3) after p (3), q (4)
    kin_[i].v_WBcm.setZero();
    kin_[i].w_WB.setZero();
  }
}

// Per free body, whether the contacts of the latest query hold it (SleepTracker::
// kBalanceFraction): the pairs' wrenches on it (B gets the opposite of A's, at the same point)
// against its weight, the torque about its centre of mass against m |g| r_max. A body in
// contact with nothing is not balanced: a part that is quiet in mid-hop does not sleep there.
// With the plain step throughout ("impacts": "implicit") every body counts as balanced: a part
// that hops about its rest on a stiff contact (docs/DISCRETE.md §5) would never balance and
// never sleep, and the preview that mode is for keeps its speed (it may sleep within the hop's
// g h² of its rest, as before).
void DiscreteStepper::contactBalance(std::vector<char>& balanced) const {
  const std::size_t nb = scenario_.bodies.size();
  if (scenario_.settings.impacts == ImpactMode::kImplicit) {
    balanced.assign(nb, 1);
    return;
  }
  std::vector<Eigen::Vector3d> force(nb, Eigen::Vector3d::Zero()),
      torque(nb, Eigen::Vector3d::Zero());
  std::vector<char> touched(nb, 0);
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const PairOutput& out = last_pairs_[k];
    if (!out.cv.inContact()) continue;
    const ContactPair& pair = scenario_.pairs[k];
    const Wrench& w = out.result.wrench;  // on A at cv.p_WC
    const std::size_t body[2] = {pair.a, pair.b};
    const double sign[2] = {1.0, -1.0};
    for (int j = 0; j < 2; ++j) {
      const std::size_t i = body[j];
      const Eigen::Vector3d r = out.cv.p_WC - kin_[i].p_WBcm;
      force[i] += sign[j] * w.f_W;
      torque[i] += sign[j] * (w.tau_W + r.cross(w.f_W));
      touched[i] = 1;
    }
  }
  balanced.assign(nb, 0);
  const double g = scenario_.gravity_W.norm();
  for (std::size_t i = 0; i < nb; ++i) {
    const RigidBody& b = scenario_.bodies[i];
    if (b.motion != BodyMotion::kFree || !touched[i]) continue;
    const double weight = b.mass * g;
    const double limit = SleepTracker::kBalanceFraction * weight;
    if (weight == 0.0) {  // without gravity there is no weight to hold: touching is enough
      balanced[i] = 1;
      continue;
    }
    balanced[i] = (force[i] + b.mass * scenario_.gravity_W).norm() <= limit &&
                  torque[i].norm() <= limit * eq_.sleep().reach(i);
  }
}

}  // namespace vcontact::dynamics
