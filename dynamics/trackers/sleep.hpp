#pragma once
// Sleeping islands of the discrete stepper (docs/SLEEP.md): bodies that have rested for a
// while stop being integrated, and their contacts stop being queried, until something touches
// them.
//
// Islands are the connected components of the free bodies linked by the pairs in contact at
// the latest query (fixed and prescribed bodies link nothing). A free body is quiet over a
// spell while the displacement bound of its material points since the spell began,
// |p_cm − p_cm,0| + θ r_max (θ the angle turned, r_max the farthest point of its shape from
// its centre of mass), stays within SleepSettings::speed × SleepSettings::time: its mean speed
// over the spell is below `speed`. A displacement, not the instantaneous speed: a body resting
// on a very stiff contact hops at up to g h every step (docs/DISCRETE.md §5) about a fixed
// pose, while a creeping or sliding one moves on. An island falls asleep once every body of
// it has been quiet for SleepSettings::time and every body of it is balanced: in contact, with
// the contact forces and torques of the latest query holding its weight (within
// kBalanceFraction of m |g|, and of m |g| r_max for the torque about its centre of mass), so
// that the contact a sleeping body keeps is one of rest, never a pose in mid-air or mid-rock;
// never while a body of it carries a load or a spring, or touches a prescribed body. A sleeping
// body keeps its pose, has zero velocity and is not integrated; a pair whose bodies are each asleep
// or fixed keeps its latest contact instead of a query. A sleeping island wakes whole when the pair
// of an awake free body (or a prescribed one) with one of its bodies comes to pass the broad phase
// (their boxes overlap now and did not at the previous step), or is in contact (that pair is still
// queried). Everything is decided from the state and in index order: a run is as deterministic with
// sleep as without.

#include <cstddef>
#include <string>
#include <vector>

#include "dynamics/rigid_body.hpp"
#include "dynamics/scenario.hpp"

namespace vcontact::dynamics {

/// A body falling asleep or waking, for summary.json.
struct SleepEvent {
  std::string body;
  double t = 0.0;      ///< s
  bool asleep = true;  ///< true: fell asleep; false: woke
};

class SleepTracker {
 public:
  /// A body is balanced when the net contact force on it, plus its weight, is within this
  /// fraction of its weight (and the torque about its centre of mass within this fraction of
  /// m |g| r_max). Resting parts of the bundled scenarios balance to 1e-3 and better at rest;
  /// a part in a hop or rock cycle of the fixed step is 1 to 20 weights off at most queries.
  static constexpr double kBalanceFraction = 0.25;

  /// Per body of s: r_max from its shape's bounds about its centre of mass; which bodies may
  /// never sleep (loads, springs). On for the discrete integrator with sleep enabled only.
  void reset(const Scenario& s);

  bool enabled() const { return enabled_; }
  bool asleep(std::size_t body) const { return enabled_ && asleep_[body] != 0; }
  /// Pair k keeps its latest contact: each body asleep or fixed, at least one asleep.
  bool frozen(std::size_t k) const { return enabled_ && frozen_[k] != 0; }

  /// Before a step from t, with the bodies at `kin` and per pair whether it is in
  /// contact (`contact`) and whether its boxes overlap (`near`), and per body whether it is
  /// balanced on its contacts (`balanced`, kBalanceFraction): wakes the sleeping islands an
  /// awake free body or a prescribed one reaches, advances the quiet times and puts quiet,
  /// balanced islands to sleep. Returns the bodies that fell asleep now (the caller zeroes
  /// their velocities).
  const std::vector<std::size_t>& update(double t, const std::vector<BodyKinematics>& kin,
                                         const std::vector<char>& contact,
                                         const std::vector<char>& near,
                                         const std::vector<char>& balanced);

  /// r_max of body i (the farthest point of its shape's box from its centre of mass), m.
  double reach(std::size_t i) const { return r_max_[i]; }

  const std::vector<SleepEvent>& events() const { return events_; }

 private:
  std::size_t root(std::size_t i);
  void wake(double t, const std::vector<char>& contact, const std::vector<char>& near);
  void formIslands(const std::vector<char>& contact);
  void refreeze();

  bool enabled_ = false;
  const Scenario* scenario_ = nullptr;
  double speed_ = 0.0, time_ = 0.0;
  std::vector<double> r_max_;              ///< per body, m
  std::vector<char> never_;                ///< per body: a load or spring on it
  std::vector<char> asleep_;               ///< per body
  std::vector<std::size_t> island_;        ///< per sleeping body, the island it fell asleep with
  std::vector<double> spell_;              ///< per body, s: when its quiet spell began (NaN: none)
  std::vector<Eigen::Vector3d> anchor_p_;  ///< per body, its centre of mass when the spell began
  std::vector<Eigen::Matrix3d> anchor_R_;  ///< per body, its attitude then
  std::vector<std::size_t> parent_;        ///< union–find over the bodies
  std::vector<char> blocked_;              ///< per island root: may not sleep
  std::vector<char> frozen_;               ///< per pair
  std::vector<char> was_near_;             ///< per pair, `near` at the previous update
  std::vector<std::size_t> fell_;
  std::vector<SleepEvent> events_;
};

}  // namespace vcontact::dynamics
