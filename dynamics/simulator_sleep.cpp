// The discrete stepper's hooks of sleeping islands (dynamics/sleep.hpp, docs/SLEEP.md).

#include <cmath>

#include "dynamics/simulator.hpp"

namespace vcontact::dynamics {

// Before the step from t: the tracker sees which pairs touch (the contacts the
// step is assembled from) and which pairs' boxes overlap (the latest broad phase; a pair that
// is always queried counts as near only in contact); the bodies that fall asleep now stop with
// zero velocity, in the state and in the kinematics the step reads.
void Simulator::sleepBeforeStep(State& x, double t) {
  const std::size_t np = scenario_.pairs.size();
  sleep_contact_.resize(np);
  sleep_near_.resize(np);
  for (std::size_t k = 0; k < np; ++k) {
    sleep_contact_[k] = last_pairs_[k].cv.inContact();
    sleep_near_[k] = sleep_contact_[k] || (screen_key_[k].first >= 0 && queried_[k]);
  }
  for (const std::size_t i : sleep_.update(t, kin_, sleep_contact_, sleep_near_)) {
    std::fill_n(x.begin() + offset_[i] + 7, 6, 0.0);  // v (3), ω (3) after p (3), q (4)
    kin_[i].v_WBcm.setZero();
    kin_[i].w_WB.setZero();
  }
}

// Whether pair k's kept contact lacks the exact depth that an output step's query computes.
bool Simulator::lacksDepth(std::size_t k) const {
  const volume::ContactPatches& c = last_contact_[k];
  const auto missing = [](const volume::ContactVolume& cv) {
    return cv.inContact() && std::isnan(cv.depth);
  };
  bool any = missing(c.aggregate);
  for (const volume::ContactVolume& p : c.patches) any = any || missing(p);
  return any;
}

}  // namespace vcontact::dynamics
