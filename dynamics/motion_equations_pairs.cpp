// The contact pairs' part of the equations of motion: each pair's query, its patches' forces on
// the two bodies, the discrete updates of its patches' states, and the output snapshot with the
// pairs' depths (motion_equations.hpp).

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "dynamics/motion_equations.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics {
namespace {

// Wrench w at p moved to the point q: the same force, τ + (p − q) × f.
Wrench movedTo(const Wrench& w, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  return {w.f_W, w.tau_W + (p - q).cross(w.f_W)};
}

// The pair's figures from its patches: the wrenches (and shares) summed at the aggregate's
// centroid, f_n summed, s and μ_max of the first (largest) patch, the rates of slot 0. One
// share per effect of the model whether or not a patch is in contact (with none, every share
// is zero): the CSV writes a column for each (issue 36: out of contact the list was empty).
void combine(const std::vector<PatchOutput>& patches, const Eigen::Vector3d& p_c,
             std::size_t effects, ContactResult& r) {
  r.wrench = Wrench{};
  r.f_n = 0.0;
  r.shares.assign(effects, Wrench{});
  for (const PatchOutput& p : patches) {
    r.wrench += movedTo(p.result.wrench, p.cv.p_WC, p_c);
    r.f_n += p.result.f_n;
    assert(p.result.shares.size() == effects);
    for (std::size_t i = 0; i < r.shares.size(); ++i) {
      r.shares[i] += movedTo(p.result.shares[i], p.cv.p_WC, p_c);
    }
  }
  r.s = patches.empty() ? 0.0 : patches.front().result.s;
  r.mu_max = patches.empty() ? 0.0 : patches.front().result.mu_max;
  r.rates = PairStateRates{};
  for (const PatchOutput& p : patches) {
    if (p.slot == 0) r.rates = p.result.rates;
  }
}

}  // namespace

// Whether kin_ is kinematics(x, ·, t) for every body: the latest right-hand side was evaluated
// at the same bits of x and at t. The readers after an accepted step (check, settle, output)
// then take kin_ instead of converting the quaternions again.
bool MotionEquations::kinematicsCurrent(const State& x, double t) const {
  return shortcuts_ && t == rhs_t_ && x.size() == last_x_.size() &&
         std::memcmp(x.data(), last_x_.data(), x.size() * sizeof(double)) == 0;
}

// The output at (x, t) in output_, whose vectors keep their capacity from one output time to
// the next: copying the pairs' figures costs no allocation once their sizes have settled.
// With `depths`, the depths the force evaluation left out are filled in (fillDepths).
const Snapshot& MotionEquations::snapshot(const State& x, double t, bool depths) {
  if (x != last_x_) {
    snapshot_dxdt_.resize(x.size());
    rhs(x, snapshot_dxdt_, t);
  }
  output_.t = t;
  if (kinematicsCurrent(x, t)) {
    output_.bodies = kin_;
  } else {
    output_.bodies.resize(scenario_.bodies.size());
    for (std::size_t i = 0; i < scenario_.bodies.size(); ++i)
      output_.bodies[i] = kinematics(x, i, t);
  }
  output_.pairs = last_pairs_;
  for (std::size_t k = 0; depths && k < output_.pairs.size(); ++k) fillDepths(k, output_.pairs[k]);
  output_.loads = last_loads_;
  return output_;
}

// The depths the force evaluation left out (NaN, QueryOptions::depth) in pair k's output
// `out` at kin_: the pair asked once more with the depth pass; each patch takes the depth of
// the patch of that answer whose centroid is nearest to its own (the same region: the pose is
// the same, only the order of patches of equal volume could differ).
void MotionEquations::fillDepths(std::size_t k, PairOutput& out) {
  const bool any =
      depthLeftOut(out.cv) || std::any_of(out.patches.begin(), out.patches.end(),
                                          [](const PatchOutput& p) { return depthLeftOut(p.cv); });
  if (!any) return;
  const volume::ContactPatches exact =
      contacts_->contact(k, kin_, sleep_.frozen(k), volume::DepthMode::kDeepest);
  out.cv.depth = exact.aggregate.depth;
  for (PatchOutput& p : out.patches) {
    double best = std::numeric_limits<double>::infinity();
    for (const volume::ContactVolume& e : exact.patches) {
      const double d = (e.p_WC - p.cv.p_WC).squaredNorm();
      if (d < best) best = d, p.cv.depth = e.depth;
    }
  }
}

// Wrench w on body A at p_c into force_ and torque_; body B gets the opposite.
void MotionEquations::addWrench(const ContactPair& pair, const Eigen::Vector3d& p_c,
                                const Wrench& w) {
  force_[pair.a] += w.f_W;
  torque_[pair.a] += w.tau_W + (p_c - kin_[pair.a].p_WBcm).cross(w.f_W);
  force_[pair.b] -= w.f_W;
  torque_[pair.b] -= w.tau_W + (p_c - kin_[pair.b].p_WBcm).cross(w.f_W);
}

// The first effect whose wrench is not finite although its contact is (a formula without a
// value at this state, such as the root of a negative number): named in the message of a
// non-finite stop, with the time it was first seen, since by the stop every quantity is NaN.
void MotionEquations::noteNonFinite(std::size_t k, const volume::ContactVolume& cv,
                                    const ContactResult& r) {
  const auto finite = [](const Wrench& w) { return w.f_W.allFinite() && w.tau_W.allFinite(); };
  if (!non_finite_effect_.empty() || finite(r.wrench)) return;
  if (!std::isfinite(cv.volume) || !cv.p_WC.allFinite() || !cv.n_W.allFinite()) return;
  const std::vector<std::string> ids = scenario_.pairs[k].model.effectIds();
  std::string effect;
  for (std::size_t i = 0; i < r.shares.size() && i < ids.size() && effect.empty(); ++i) {
    if (!finite(r.shares[i])) effect = ", effect '" + ids[i] + "'";
  }
  std::ostringstream s;
  s.precision(9);
  s << "; first non-finite force: pair '" << scenario_.pairs[k].name << "'" << effect
    << " at t = " << rhs_t_ << " s with a finite contact (V = " << cv.volume << " m^3)";
  non_finite_effect_ = s.str();
}

// Every pair's contact and model at kin_ (evaluatePair), side by side (TBB) when there are
// several pairs to query, then their wrenches onto the bodies pair by pair in order (applyPair):
// the same sums, to the bit, as one thread. A pair's evaluation touches only what is its own
// (its output, context, caches, tracker and the rates of its states in dxdt) and the query
// counters, which are atomic; the meshes' shared trees are built under a lock
// (volume/kernels/mesh_cache.hpp) and the queries' scratch is per thread.
void MotionEquations::evaluatePairs(const State& x, State& dxdt) {
  const std::size_t n = scenario_.pairs.size();
  std::size_t queries = 0;  // the pairs whose evaluation queries their contact
  if (parallel_pairs_ && !contacts_->reusing()) {
    for (std::size_t k = 0; k < n && queries < 2; ++k) {
      if (contacts_->queried(k) && !sleep_.frozen(k)) ++queries;
    }
  }
  if (queries < 2) {
    for (std::size_t k = 0; k < n; ++k) evaluatePair(k, x, dxdt);
  } else {
    // one pair a task: a mesh pair's query costs 0.1-10 ms, and pairs differ a thousandfold
    tbb::parallel_for(
        std::size_t{0}, n, [&](std::size_t k) { evaluatePair(k, x, dxdt); },
        tbb::simple_partitioner{});
  }
  for (std::size_t k = 0; k < n; ++k) applyPair(k);
}

// Pair k's wrenches onto its bodies from its latest evaluation (last_pairs_[k]), a one-slot
// pair's at its single region, a patched pair's patch by patch; the first non-finite force of
// the run noted on the way.
void MotionEquations::applyPair(std::size_t k) {
  const ContactPair& pair = scenario_.pairs[k];
  const PairOutput& out = last_pairs_[k];
  if (slots_[k] == 1) {
    noteNonFinite(k, out.cv, out.result);
    addWrench(pair, out.cv.p_WC, out.result.wrench);
    return;
  }
  for (const PatchOutput& p : out.patches) {
    noteNonFinite(k, p.cv, p.result);
    addWrench(pair, p.cv.p_WC, p.result.wrench);
  }
}

// Pair k's contact and model into last_pairs_[k], its state rates into dxdt; the wrench is
// applied by applyPair. A one-slot pair evaluates its single-region contact (the aggregate)
// with slot 0.
void MotionEquations::evaluatePair(std::size_t k, const State& x, State& dxdt) {
  const ContactPair& pair = scenario_.pairs[k];
  PairOutput& out = last_pairs_[k];
  const volume::ContactPatches contact = contacts_->contact(k, kin_, sleep_.frozen(k));
  out.patch_count = static_cast<int>(contact.patches.size());
  out.without_slot = 0;
  if (slots_[k] > 1) {
    evaluatePatches(k, contact, x, dxdt);
    return;
  }
  out.without_slot = std::max(0, out.patch_count - 1);  // lumped into the one region
  const bool distributed = pair.friction == FrictionMode::kDistributed;
  out.cv = contact.aggregate;
  const int state_size = pair.model.stateLayout().size();
  out.state = PairState::unpack(&x[static_cast<std::size_t>(pair_offset_[k])], state_size);
  const Eigen::Vector3d& p_c = out.cv.p_WC;
  const RelativeMotion motion = relativeMotion(kin_[pair.a], kin_[pair.b], p_c);
  EvaluationContext* context = last_context_.empty() ? nullptr : &last_context_[k];
  if (context) {
    context->valid = keep_contexts_ && out.cv.inContact();
    context->motion = motion;
    if (!context->valid) context = nullptr;
  }
  pair.model.evaluate(out.cv, motion, out.state, out.result,
                      distributed && out.cv.inContact() ? &contacts_->field(k) : nullptr,
                      context ? &context->ctx : nullptr);
  out.result.rates.pack(&dxdt[static_cast<std::size_t>(pair_offset_[k])], state_size);
}

// A pair with several slots: the model once per patch with the states of its slot
// (PatchTracker::match), each patch's wrench applied at its own centroid; a slot without a
// patch has zero rates.
void MotionEquations::evaluatePatches(std::size_t k, const volume::ContactPatches& contact,
                                      const State& x, State& dxdt) {
  const ContactPair& pair = scenario_.pairs[k];
  PairOutput& out = last_pairs_[k];
  PatchMatch& m = matches_[k];
  trackers_[k].match(contact.patches, kin_[pair.a].X_WB, kin_[pair.b].X_WB, m);
  out.without_slot = m.without_slot;
  out.cv = contact.aggregate;
  const int size = pair.model.stateLayout().size();
  const std::size_t base = static_cast<std::size_t>(pair_offset_[k]);
  std::fill(dxdt.begin() + std::ptrdiff_t(base),
            dxdt.begin() + std::ptrdiff_t(base + std::size_t(slots_[k] * size)), 0.0);
  out.patches.resize(contact.patches.size());
  for (std::size_t i = 0; i < contact.patches.size(); ++i) {
    PatchOutput& p = out.patches[i];
    p.cv = contact.patches[i];
    p.slot = m.slot[i];
    p.state = PairState::unpack(&x[base + std::size_t(m.host[i] * size)], size);
    const RelativeMotion motion = relativeMotion(kin_[pair.a], kin_[pair.b], p.cv.p_WC);
    pair.model.evaluate(p.cv, motion, p.state, p.result);
    if (p.slot >= 0) p.result.rates.pack(&dxdt[base + std::size_t(p.slot * size)], size);
  }
  out.state = PairState::unpack(&x[base], size);
  combine(out.patches, out.cv.p_WC, pair.model.effectCount(), out.result);
}

// The pair states' discrete updates (Model::settle) at the contacts of the latest evaluation:
// a one-slot pair at its single-region contact; with several slots, each slot at its patch
// (none: reset), and the tracker records the patches' places (PatchTracker::update).
bool MotionEquations::settlePairs(State& x, double t) {
  bool changed = false;
  const bool current = kinematicsCurrent(x, t);
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const ContactPair& pair = scenario_.pairs[k];
    const BodyKinematics A = current ? kin_[pair.a] : kinematics(x, pair.a, t);
    const BodyKinematics B = current ? kin_[pair.b] : kinematics(x, pair.b, t);
    const int size = pair.model.stateLayout().size();
    const PairOutput& out = last_pairs_[k];
    for (int slot = 0; slot < slots_[k]; ++slot) {
      const volume::ContactVolume* cv = slots_[k] == 1 ? &out.cv : nullptr;
      for (const PatchOutput& p : out.patches) {
        if (p.slot == slot) cv = &p.cv;
      }
      const volume::ContactVolume none;
      const volume::ContactVolume& c = cv ? *cv : none;
      const RelativeMotion motion = relativeMotion(A, B, c.p_WC);
      double* s = &x[static_cast<std::size_t>(pair_offset_[k] + slot * size)];
      PairState state = PairState::unpack(s, size);
      changed = pair.model.settle(c, motion, state) || changed;
      state.pack(s, size);
    }
    if (slots_[k] > 1) {
      std::vector<volume::ContactVolume> patches;
      for (const PatchOutput& p : out.patches) patches.push_back(p.cv);
      trackers_[k].update(patches, matches_[k], A.X_WB, B.X_WB);
    }
  }
  return changed;
}

}  // namespace vcontact::dynamics
