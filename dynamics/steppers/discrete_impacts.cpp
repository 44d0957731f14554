// Impacts in the discrete stepper (docs/DISCRETE.md §5): a fixed step of backward Euler takes
// the energy of any contact mode faster than 1/h, so an impact of 25 µs stepped at 1 ms does
// not rebound at all. A step is instead integrated by Dormand–Prince at the scenario's
// tolerances, from its start to its end, when
//
//   - a contact region at its start moves along its normal faster than the impact threshold
//     (either way: the compression and the rebound both need resolving), or
//   - a contact region after the plain step approached faster than the threshold at the
//     step's start (a new contact, a new patch of a pair in contact, or one that stiffened in
//     the step: the step is then taken again from its start, one query wasted per impact),
//
// where a region is a pair's single-region contact or, with several slots, one of its patches
// (its own normal and centroid), and the region's estimated impact duration
// π sqrt(m_eff / k_n) (k_n = f_n A / V, which is kv (1 + a δ̇_c) A for the volumetric model,
// m_eff the pair's effective mass along the normal at the region's centroid) is below
// kResolvedSteps steps. The threshold 2 |g| h is twice the speed at which a step out of contact
// lands a resting body (g h): resting contact and its hop (§5) stay on the fixed step. Outputs
// stay on the fixed grid; the Dormand–Prince steps inside are not output.
//
// "impacts": "resolve" resolves every such step. "auto" (the default) resolves one only for a
// region whose predicted rebound e v_in reaches the scenario's restitution_threshold: a
// resolution costs at least six queries per Dormand–Prince step and max(1, h / max_step) steps
// against the plain step's one query, and a rebound slower than the threshold is a hop below
// v² / 2g that the plain step may dissipate. The safety net of a plain step whose linearisation
// missed (linearisationMiss) resolves in either mode, except for a pair whose impact "auto"
// left to the plain step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "dynamics/steppers/discrete_stepper.hpp"
#include "dynamics/steppers/dopri5_control.hpp"

namespace vcontact::dynamics {
namespace {

// Impacts lasting fewer steps than this are resolved: backward Euler's restitution of an
// elastic impact is 0.66 at 14 steps per impact, 0.81 at 28 and 0.978 at 280, so 2 % needs
// about 250 steps (docs/DISCRETE.md §5). With 25, impacts estimated at 25–250 steps were left
// to the plain step and lost up to a fifth of the rebound, more where the estimate at a face's
// first touch (a sliver of contact) is longer than the impact.
constexpr double kResolvedSteps = 250.0;
// m/s, the least impact speed to resolve without gravity (the threshold is 2 |g| h otherwise).
constexpr double kMinImpactSpeed = 1e-3;
// A Dormand–Prince step that ends within this fraction of the interval of its end lands on it.
constexpr double kEndSlack = 1e-9;
// A plain step missed its linearisation when a pair's normal force queried at the step's end
// differs from the force the step applied (h n·f⁺, stepImpulses) by more than this fraction of
// the larger of the two, and by more than a quarter of the weight of the pair's lighter free
// body: a step that rests or slides on a contact the linearisation describes well lands within
// a few percent; one that fell into the contact from apart (the hop of docs/DISCRETE.md §5), or
// whose tilt stiffness or missing cross terms (§2.2) are off by more than two, does not.
constexpr double kMissedForceFraction = 0.5;
constexpr double kMissedWeightFraction = 0.25;
// Newton iterations of a plain step whose linearisation missed, before its interval is resolved
// by Dormand–Prince instead.
constexpr int kNewtonIterations = 12;
// Once iterating, a step's Newton iterations go on until its worst pair misses by a tenth of
// the allowance (5 % of the force) or the count runs out: a step accepted just inside the
// allowance would start the next one half a weight out of balance, and a resting part would
// hop from one missed step to the next instead of coming to rest.
constexpr double kNewtonTarget = 0.1;

}  // namespace

double impactThreshold(const Scenario& scenario, double h) {
  return std::max(2.0 * scenario.gravity_W.norm() * h, kMinImpactSpeed);
}

// π sqrt(m_eff / k_n) of a contact region cv of pair k with normal force f_n; infinite
// without a normal force.
double DiscreteStepper::impactDuration(std::size_t k, const volume::ContactVolume& cv,
                                       double f_n) const {
  const ContactPair& pair = scenario_.pairs[k];
  const double k_n = f_n * cv.area / cv.volume;
  if (!(k_n > 0.0)) return std::numeric_limits<double>::infinity();
  double inverse_mass = 0.0;
  for (const std::size_t b : {pair.a, pair.b}) {
    if (eq_.bodyOffset(b) < 0) continue;
    const Eigen::Matrix3d R = kin_[b].X_WB.linear();
    const Eigen::Vector3d rn = (cv.p_WC - kin_[b].p_WBcm).cross(cv.n_W);
    inverse_mass +=
        1.0 / scenario_.bodies[b].mass + rn.dot(R * eq_.inverseInertia(b) * R.transpose() * rn);
  }
  if (inverse_mass == 0.0) return std::numeric_limits<double>::infinity();
  return std::numbers::pi * std::sqrt(1.0 / (inverse_mass * k_n));
}

// The rebound speed e v_in predicted for an impact of pair k at approach speed v_in: the
// restitution the pair's effects give a head-on impact (Model::impactRestitution: the exact
// relation of docs/MODEL.md §5 for damping, e = 1 without a dissipating effect). Other
// dissipation (a Maxwell element, friction) only lowers the rebound of a head-on impact: the
// prediction errs towards resolving there; a rocking or tumbling part can leave faster than it
// came (docs/DISCRETE.md §5).
double DiscreteStepper::predictedRebound(std::size_t k, double approach) const {
  return scenario_.pairs[k].model.impactRestitution(approach) * approach;
}

// Whether a contact region of a pair at the latest query is in an impact to resolve over a
// step h, its normal speed at the region's centroid taken from speed_kin; each fast region is
// appended to `fast`. The regions are the pair's single-region contact (the aggregate) and, for
// a pair with several slots, each of its patches with its own normal and centroid: a tray's
// base landing while its pins touch the hole walls is fast where the aggregate is slow, and a
// peg driven down a hole whose wall patches slide along their normals' planes is fast only in
// the aggregate. approaching_only: the check after a plain step, which takes any region
// approaching faster than the threshold at the step's start (a pair apart then, or a patch that
// appeared or stiffened in the step). A fast region's rebound is predicted from the larger of
// its speed and the approach speed of its pair's open impact, and an open impact is taken as
// its first fast step was (resolved or left to the plain step); every estimate errs towards
// resolving.
bool DiscreteStepper::impactAhead(const std::vector<BodyKinematics>& speed_kin,
                                  bool approaching_only, double h,
                                  std::vector<FastRegion>& fast) const {
  const SimulationSettings& set = scenario_.settings;
  const double threshold = impactThreshold(scenario_, h);
  const double gravity = scenario_.gravity_W.norm();
  bool resolve = false;
  const auto check = [&](std::size_t k, const volume::ContactVolume& cv, double f_n) {
    if (!cv.inContact()) return;
    const ContactPair& pair = scenario_.pairs[k];
    const double speed = cv.n_W.dot(speed_kin[pair.a].pointVelocity(cv.p_WC) -
                                    speed_kin[pair.b].pointVelocity(cv.p_WC));
    const bool quick = approaching_only ? -speed > threshold : std::abs(speed) > threshold;
    if (!quick || !(impactDuration(k, cv, f_n) < kResolvedSteps * h)) return;
    // after a plain step, the region touched within it: its speed at the touch is at most
    // |g| h above the start's (gravity alone acts before it)
    const double approach = std::abs(speed) + (approaching_only ? gravity * h : 0.0);
    const double rebound = predictedRebound(k, std::max(approach, impacts_.openApproach(k)));
    // one impact is taken one way throughout: as its first fast step was
    const bool worth = set.impacts == ImpactMode::kResolve || impacts_.openAndResolved(k) ||
                       (!impacts_.openAndPlain(k) && rebound >= set.restitution_threshold);
    fast.push_back({k, rebound, worth});
    resolve = resolve || worth;
  };
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const PairOutput& out = last_pairs_[k];
    if (!out.cv.inContact()) continue;
    check(k, out.cv, out.result.f_n);
    if (eq_.slots(k) == 1) continue;
    for (const PatchOutput& p : out.patches) check(k, p.cv, p.result.f_n);
  }
  return resolve;
}

// Tells the impact tracker what the step under way does with its fast regions.
void DiscreteStepper::markImpacts(bool resolved) {
  impacts_.beginStep(resolved);
  for (const FastRegion& r : fast_regions_) {
    if (resolved || r.resolve) {
      impacts_.markResolved(r.pair, r.rebound);
    } else {
      impacts_.markPlain(r.pair, r.rebound);
    }
  }
}

// Whether the plain step just taken applied, to some pair in contact at its end, a normal
// force far from the one queried there (kMissedForceFraction): the linearised contact did not
// describe the step. Backward Euler with h² k/m ≫ 1 moves a body to where the linearised force
// balances the others in one step, so a stiffness off by more than twice overshoots further
// than it started, and a resting part rocks or hops in a cycle about its rest (a 5,400-triangle
// housing on its rim: 3 to 19 times its weight at the queries, docs/DISCRETE.md §5). A pair
// whose impact "auto" leaves to the plain step (below the restitution threshold: a fast region
// of this step, or the open impact of earlier ones) misses by design until that impact is over:
// the plain step lands it from apart and dissipates it.
//
// Returned as the worst such pair's miss over its allowance (kMissedForceFraction of the larger
// force): missed when above 1, 0 when no pair misses by more than the weight share.
double DiscreteStepper::linearisationMiss(double h) const {
  const double g = scenario_.gravity_W.norm();
  const auto left_to_the_step = [&](std::size_t k) {
    return impacts_.openAndPlain(k) ||
           std::any_of(fast_regions_.begin(), fast_regions_.end(),
                       [k](const FastRegion& r) { return r.pair == k && !r.resolve; });
  };
  double worst = 0.0;
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const PairOutput& out = last_pairs_[k];
    if (!out.cv.inContact() || eq_.sleep().frozen(k) || left_to_the_step(k)) continue;
    const ContactPair& pair = scenario_.pairs[k];
    double lighter = std::numeric_limits<double>::infinity();
    for (const std::size_t b : {pair.a, pair.b}) {
      if (eq_.bodyOffset(b) >= 0) lighter = std::min(lighter, scenario_.bodies[b].mass);
    }
    if (!std::isfinite(lighter)) continue;
    const double applied = step_impulse_[k] / h, queried = out.result.f_n;
    const double miss = std::abs(queried - applied);
    if (miss <= kMissedWeightFraction * lighter * g) continue;
    const double allowance = kMissedForceFraction * std::max(std::abs(applied), std::abs(queried));
    worst = std::max(worst,
                     allowance > 0.0 ? miss / allowance : std::numeric_limits<double>::infinity());
  }
  return worst;
}

// The Newton iterate in x (and its twists in next_kin_) moved back halfway to the previous one,
// previous_x_: a damped iteration, for a step whose last iteration missed by more than the one
// before (two contacts of a resting stack that the linearisations push to and fro).
void DiscreteStepper::relaxNewtonIterate(State& x) {
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = previous_x_[j] + 0.5 * (x[j] - previous_x_[j]);
  for (std::size_t i = 0; i < next_kin_.size(); ++i) {
    const int o = eq_.bodyOffset(i);
    if (o < 0) continue;
    const double* s = &x[static_cast<std::size_t>(o)];
    next_kin_[i].v_WBcm = Eigen::Vector3d(s[7], s[8], s[9]);
    next_kin_[i].w_WB = Eigen::Vector3d(s[10], s[11], s[12]);
  }
}

// The interval [t, t1] of one step, plain or resolved; x, dxdt and the contacts at t on entry,
// at t1 (checked, settled, observed by the impact tracker) on return.
void DiscreteStepper::advance(State& x, State& dxdt, double& t, double h, double t1, bool lands,
                              SimulationSummary& summary) {
  const bool resolve = scenario_.settings.impacts != ImpactMode::kImplicit;
  fast_regions_.clear();
  if (resolve && impactAhead(kin_, false, h, fast_regions_)) {
    resolveInterval(x, dxdt, t, t1, summary);
    return;
  }
  if (resolve) {
    start_x_ = x;
    start_dxdt_ = dxdt;
    start_kin_ = kin_;
  }
  const double t0 = t;
  // The step's one contact query, at the new state; on an output time with the exact
  // depths the output writes, which spares eq_.snapshot() a second query (fillDepths).
  const auto query = [&](bool impulses) {
    if (impulses) stepImpulses(h);
    eq_.normaliseQuaternions(x);
    eq_.contacts().setQueryDepths(lands && eq_.outputDepths());
    eq_.setKeepContexts(true);
    eq_.rhs(x, dxdt, t1);
    eq_.contacts().setQueryDepths(false);
    eq_.setKeepContexts(false);
  };
  plainStep(x, t, h);
  t = t1;
  query(true);
  if (resolve) {
    const bool impact = impactAhead(start_kin_, true, h, fast_regions_);
    double miss = impact ? 0.0 : linearisationMiss(h);
    // A missed linearisation is first taken again about the step's end (Newton iterations of
    // the implicit step, one query each, to kNewtonTarget of the allowance; one that follows an
    // iteration that missed by more than the one before is damped halfway), and resolved only
    // when none of them meets the allowance.
    double before = std::numeric_limits<double>::infinity(), best = miss;
    for (int i = 0; miss > (i == 0 ? 1.0 : kNewtonTarget) && i < kNewtonIterations; ++i) {
      ++summary.newton_iterations;
      const bool damp = miss > before;
      before = miss;
      previous_x_ = x;
      x = start_x_;
      newtonStep(x, h);
      if (damp) relaxNewtonIterate(x);
      query(true);
      miss = linearisationMiss(h);
      if (miss < best) {
        best = miss;
        best_x_ = x;
        best_impulse_ = step_impulse_;
      }
    }
    // iterations that ran out short of the target: their best iterate, if within the allowance
    if (best < miss && best <= 1.0) {
      x = best_x_;
      step_impulse_ = best_impulse_;
      query(false);
      miss = best;
    }
    const bool missed = miss > 1.0;
    if (impact || missed) {
      if (missed) ++summary.resolved_for_linearisation;
      x = start_x_;
      dxdt = start_dxdt_;
      t = t0;
      resolveInterval(x, dxdt, t, t1, summary);
      return;
    }
  }
  markImpacts(false);
  eq_.check(x, t);
  if (eq_.settlePairs(x, t)) {
    eq_.contacts().setReuse(true);
    eq_.setKeepContexts(true);
    eq_.rhs(x, dxdt, t);
    eq_.contacts().setReuse(false);
    eq_.setKeepContexts(false);
  }
  impacts_.observe(t, kin_, last_pairs_, &step_impulse_);
}

// Dormand–Prince from t to t1 as runDopri5 steps (the same control and checks), its step size
// carried from one resolved interval to the next.
void DiscreteStepper::resolveInterval(State& x, State& dxdt, double& t, double t1,
                                      SimulationSummary& summary) {
  const SimulationSettings& set = scenario_.settings;
  ++summary.resolved_steps;
  markImpacts(true);
  const long queries_before = eq_.contacts().queries();
  Dopri5Control control(set.abs_tol, set.rel_tol);
  double dt = std::min(resolve_dt_ > 0.0 ? resolve_dt_ : set.initial_step, set.max_step);
  const double span = t1 - t;
  while (t < t1) {
    const bool capped = t1 - t <= dt * (1.0 + kEndSlack);
    double dt_try = capped ? t1 - t : dt;
    if (!dopri5_.attempt(control, x, dxdt, t, dt_try, summary)) {
      dt = dt_try;
      continue;
    }
    ++summary.resolution_substeps;
    dt = control.afterAccept(std::min(capped ? std::max(dt_try, dt) : dt_try, set.max_step));
    if (capped || t1 - t <= kEndSlack * span) t = t1;
    dopri5_.accepted(x, dxdt, t);
  }
  resolve_dt_ = dt;
  summary.resolution_queries += eq_.contacts().queries() - queries_before;
}

// The normal impulse of each pair over the step just solved: h n·f⁺ of its patches, with the
// implicit wrench f⁺ = c + L ξ⁺ at the new twists.
void DiscreteStepper::stepImpulses(double h) {
  step_impulse_.assign(scenario_.pairs.size(), 0.0);
  for (std::size_t j = 0; j < step_patch_count_; ++j) {
    const DiscretePatch& dp = step_patches_[j];
    const ContactPair& pair = scenario_.pairs[dp.pair];
    const RelativeMotion m = relativeMotion(next_kin_[pair.a], next_kin_[pair.b], dp.p_c);
    Vector6d xi;
    xi << m.v_c_W, m.w_W;
    step_impulse_[dp.pair] += h * dp.n.dot((dp.step.c + dp.step.L * xi).head<3>());
  }
}

}  // namespace vcontact::dynamics
