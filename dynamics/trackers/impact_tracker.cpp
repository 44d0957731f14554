#include "dynamics/trackers/impact_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "dynamics/simulation_output.hpp"

namespace vcontact::dynamics {

namespace {

// The time to cross a mean depth d at speed v, at most `step`: where between two accepted states
// the contact began or ended (the mean depth V/A is the depth of a flat face, half that of a
// sphere's cap; the error is a fraction of the one step around the onset or separation).
double exitTime(double d, double v, double step) {
  if (!(v > 0.0) || !(d > 0.0)) return step;
  return std::min(step, d / v);
}

}  // namespace

void ImpactTracker::reset(const Scenario& scenario, double settle_speed, double settle_time,
                          bool discrete) {
  scenario_ = &scenario;
  settle_speed_ = settle_speed;
  settle_time_ = settle_time;
  discrete_ = discrete;
  step_ = -1;
  resolved_ = false;
  marks_.assign(scenario.pairs.size(), StepMark{});
  last_kin_.clear();
  open_.assign(scenario.pairs.size(), Open{});
  impacts_.clear();
}

void ImpactTracker::beginStep(bool resolved) {
  ++step_;
  resolved_ = resolved;
  std::fill(marks_.begin(), marks_.end(), StepMark{});
}

void ImpactTracker::markPlain(std::size_t k, double rebound) {
  marks_[k].plain = true;
  marks_[k].rebound = std::max(marks_[k].rebound, rebound);
}

void ImpactTracker::markResolved(std::size_t k, double rebound) {
  marks_[k].rebound = std::max(marks_[k].rebound, rebound);
}

// The step under way, once per open impact of pair k that its states show.
void ImpactTracker::countStep(std::size_t k) {
  Open& o = open_[k];
  if (!discrete_ || o.counted_step == step_) return;
  o.counted_step = step_;
  if (resolved_) {
    ++o.resolved_steps;
  } else if (marks_[k].plain) {
    ++o.plain_steps;
  }
  if (o.predicted_rebound == 0.0) o.predicted_rebound = marks_[k].rebound;  // the deciding step's
}

// −δ̇_c: the normal relative speed of A against B at p along n, > 0 separating.
double ImpactTracker::normalSpeed(std::size_t k, const std::vector<BodyKinematics>& kin,
                                  const Eigen::Vector3d& p, const Eigen::Vector3d& n) const {
  const ContactPair& pair = scenario_->pairs[k];
  return n.dot(kin[pair.a].pointVelocity(p) - kin[pair.b].pointVelocity(p));
}

// The relative acceleration of A against B along n in free flight: gravity on the free ones.
double ImpactTracker::gravityAlong(std::size_t k, const Eigen::Vector3d& n) const {
  const ContactPair& pair = scenario_->pairs[k];
  const auto falls = [&](std::size_t b) {
    return scenario_->bodies[b].motion == BodyMotion::kFree ? 1.0 : 0.0;
  };
  return (falls(pair.a) - falls(pair.b)) * n.dot(scenario_->gravity_W);
}

void ImpactTracker::close(std::size_t k, double end, double impulse, double separation,
                          const char* outcome) {
  Open& o = open_[k];
  ImpactRecord r;
  r.pair = scenario_->pairs[k].name;
  r.start = o.start;
  r.duration = end - o.start;
  r.impulse = impulse;
  r.approach_speed = o.approach;
  r.separation_speed = separation;
  r.restitution = o.approach > 0.0 ? separation / o.approach : 0.0;
  r.outcome = outcome;
  if (discrete_) {
    r.resolved_steps = o.resolved_steps;
    r.plain_steps = o.plain_steps;
    r.predicted_rebound = o.predicted_rebound;
    r.resolution = o.resolved_steps > 0 ? (o.plain_steps > 0 ? "partly" : "resolved")
                                        : (o.plain_steps > 0 ? "plain" : "slow");
  }
  impacts_.push_back(r);
  o.active = false;
}

void ImpactTracker::observe(double t, const std::vector<BodyKinematics>& kin,
                            const std::vector<PairOutput>& pairs,
                            const std::vector<double>* step_impulse) {
  for (std::size_t k = 0; k < open_.size(); ++k) {
    Open& o = open_[k];
    const volume::ContactVolume& cv = pairs[k].cv;
    if (!cv.inContact()) {
      if (o.active) {  // separated: back from the first state apart to the last in contact
        countStep(k);
        const double v = normalSpeed(k, kin, o.p, o.n) - gravityAlong(k, o.n) * (t - o.last_t);
        const double end = o.last_t + exitTime(o.last_depth, v, t - o.last_t);
        const double impulse =
            o.impulse + (step_impulse ? (*step_impulse)[k] : 0.5 * o.last_fn * (end - o.last_t));
        close(k, end, impulse, std::max(v, 0.0), "separated");
      }
      o.resting = false;
      continue;
    }
    const double f_n = pairs[k].result.f_n;
    if (o.resting) continue;
    if (!o.active) {
      if (last_kin_.empty()) {  // in contact at the start: resting or pressed, no impact
        o.resting = true;
        continue;
      }
      o = Open{};
      o.active = true;
      o.approach =
          -normalSpeed(k, last_kin_, cv.p_WC, cv.n_W) - gravityAlong(k, cv.n_W) * (t - last_t_);
      o.start = t - exitTime(cv.volume / cv.area, o.approach, t - last_t_);
      // f_n rises from 0 at the contact's onset
      o.impulse = step_impulse ? (*step_impulse)[k] : 0.5 * f_n * (t - o.start);
    } else {
      o.impulse += step_impulse ? (*step_impulse)[k] : 0.5 * (o.last_fn + f_n) * (t - o.last_t);
    }
    countStep(k);
    o.last_t = t;
    o.last_fn = f_n;
    o.last_depth = cv.volume / cv.area;
    o.n = cv.n_W;
    o.p = cv.p_WC;
    if (std::abs(normalSpeed(k, kin, cv.p_WC, cv.n_W)) >= settle_speed_) {
      o.slow_since = -1.0;
    } else if (o.slow_since < 0.0) {
      o.slow_since = t;
      o.impulse_at_slow = o.impulse;
    } else if (t - o.slow_since >= settle_time_) {
      close(k, o.slow_since, o.impulse_at_slow, 0.0, "settled");
      o.resting = true;
    }
  }
  last_t_ = t;
  last_kin_ = kin;
}

void ImpactTracker::finish(double t) {
  for (std::size_t k = 0; k < open_.size(); ++k) {
    if (open_[k].active) close(k, t, open_[k].impulse, 0.0, "open");
  }
}

}  // namespace vcontact::dynamics
