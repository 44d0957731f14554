#include "dynamics/trackers/sleep.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/broad_phase.hpp"

namespace vcontact::dynamics {
namespace {

// The farthest corner of the shape's box from the centre of mass: a bound on the distance of
// every material point (0 for an unbounded shape, which is never free in practice).
double farthestPoint(const RigidBody& b) {
  const std::optional<geometry::Aabb> box = geometry::localBounds(b.shape);
  if (!box) return 0.0;
  const Eigen::Vector3d far =
      (box->min - b.p_BBcm).cwiseAbs().cwiseMax((box->max - b.p_BBcm).cwiseAbs());
  return far.norm();
}

}  // namespace

void SleepTracker::reset(const Scenario& s) {
  const std::size_t nb = s.bodies.size();
  scenario_ = &s;
  enabled_ = s.settings.integrator == Integrator::kDiscrete && s.settings.sleep.enabled;
  speed_ = s.settings.sleep.speed;
  time_ = s.settings.sleep.time;
  r_max_.assign(nb, 0.0);
  for (std::size_t i = 0; i < nb; ++i) r_max_[i] = farthestPoint(s.bodies[i]);
  never_.assign(nb, 0);
  for (const ExternalLoad& l : s.loads) never_[l.body] = 1;
  for (const BodySpring& sp : s.springs) never_[sp.a] = never_[sp.b] = 1;
  asleep_.assign(nb, 0);
  island_.assign(nb, 0);
  spell_.assign(nb, std::nan(""));
  anchor_p_.assign(nb, Eigen::Vector3d::Zero());
  anchor_R_.assign(nb, Eigen::Matrix3d::Identity());
  parent_.resize(nb);
  blocked_.assign(nb, 0);
  frozen_.assign(s.pairs.size(), 0);
  was_near_.assign(s.pairs.size(), 1);
  fell_.clear();
  events_.clear();
}

std::size_t SleepTracker::root(std::size_t i) {
  while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
  return i;
}

// A sleeping body wakes with its island when an awake free (or a prescribed) body's pair with
// it comes into
// contact, or when their boxes come to overlap (they did not at the previous update): boxes in
// a bin overlap their neighbours' all the time, and waking on that alone would wake every
// island at once. The woken bodies may reach further sleeping ones, so this repeats until
// nothing changes.
void SleepTracker::wake(double t, const std::vector<char>& contact, const std::vector<char>& near) {
  const std::vector<RigidBody>& bodies = scenario_->bodies;
  const auto moves = [&](std::size_t b) {  // an awake free body, or a prescribed one
    return bodies[b].motion == BodyMotion::kPrescribed ||
           (bodies[b].motion == BodyMotion::kFree && !asleep_[b]);
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t k = 0; k < scenario_->pairs.size(); ++k) {
      const ContactPair& p = scenario_->pairs[k];
      if (!contact[k] && !(near[k] && !was_near_[k])) continue;
      std::size_t sleeper = p.a;
      if (asleep_[p.a] && moves(p.b)) {
        sleeper = p.a;
      } else if (asleep_[p.b] && moves(p.a)) {
        sleeper = p.b;
      } else {
        continue;
      }
      const std::size_t island = island_[sleeper];
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!asleep_[i] || island_[i] != island) continue;
        asleep_[i] = 0;
        spell_[i] = std::nan("");
        events_.push_back({bodies[i].name, t, false});
      }
      changed = true;
    }
  }
}

// Union–find over the free bodies linked by pairs in contact; an island touching a prescribed
// body, or holding a body with a load or spring, is blocked.
void SleepTracker::formIslands(const std::vector<char>& contact) {
  const std::vector<RigidBody>& bodies = scenario_->bodies;
  for (std::size_t i = 0; i < bodies.size(); ++i) parent_[i] = i;
  for (std::size_t k = 0; k < scenario_->pairs.size(); ++k) {
    const ContactPair& p = scenario_->pairs[k];
    if (!contact[k]) continue;
    if (bodies[p.a].motion != BodyMotion::kFree || bodies[p.b].motion != BodyMotion::kFree) {
      continue;
    }
    const std::size_t a = root(p.a), b = root(p.b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the smaller index is the root
  }
  std::fill(blocked_.begin(), blocked_.end(), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (never_[i]) blocked_[root(i)] = 1;
  }
  for (std::size_t k = 0; k < scenario_->pairs.size(); ++k) {
    const ContactPair& p = scenario_->pairs[k];
    if (!contact[k]) continue;
    if (bodies[p.a].motion == BodyMotion::kPrescribed) blocked_[root(p.b)] = 1;
    if (bodies[p.b].motion == BodyMotion::kPrescribed) blocked_[root(p.a)] = 1;
  }
}

void SleepTracker::refreeze() {
  const std::vector<RigidBody>& bodies = scenario_->bodies;
  for (std::size_t k = 0; k < scenario_->pairs.size(); ++k) {
    const ContactPair& p = scenario_->pairs[k];
    const auto still = [&](std::size_t b) {
      return asleep_[b] || bodies[b].motion == BodyMotion::kFixed;
    };
    frozen_[k] = (asleep_[p.a] || asleep_[p.b]) && still(p.a) && still(p.b);
  }
}

const std::vector<std::size_t>& SleepTracker::update(double t,
                                                     const std::vector<BodyKinematics>& kin,
                                                     const std::vector<char>& contact,
                                                     const std::vector<char>& near,
                                                     const std::vector<char>& balanced) {
  fell_.clear();
  if (!enabled_) return fell_;
  const std::vector<RigidBody>& bodies = scenario_->bodies;
  wake(t, contact, near);
  was_near_ = near;
  formIslands(contact);
  // Quiet times; an island whose root sees a body not yet quiet long enough, or not balanced
  // on its contacts, stays awake.
  std::vector<char>& ready = blocked_;  // reused: 1 = may not sleep now
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].motion != BodyMotion::kFree || asleep_[i]) continue;
    const Eigen::Matrix3d& R = kin[i].X_WB.linear();
    const double turn = Eigen::AngleAxisd(R * anchor_R_[i].transpose()).angle();
    const double moved = (kin[i].p_WBcm - anchor_p_[i]).norm() + turn * r_max_[i];
    if (moved > speed_ * time_ || std::isnan(spell_[i])) {  // a new quiet spell starts now
      anchor_p_[i] = kin[i].p_WBcm;
      anchor_R_[i] = R;
      spell_[i] = t;
    }
    if (t - spell_[i] < time_ || !balanced[i]) ready[root(i)] = 1;
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].motion != BodyMotion::kFree || asleep_[i] || ready[root(i)]) continue;
    asleep_[i] = 1;
    island_[i] = root(i);
    fell_.push_back(i);
    events_.push_back({bodies[i].name, t, true});
  }
  refreeze();
  return fell_;
}

}  // namespace vcontact::dynamics
