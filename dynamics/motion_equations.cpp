#include "dynamics/motion_equations.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/error.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {
namespace {

constexpr int kBodyStates = MotionEquations::kBodyStates;

Eigen::Quaterniond quaternionAt(const double* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
}

// The penetration the run is stopped on: the mean depth V/A over the contact area. The
// deepest column (cv.depth) is not used: the force evaluations skip it (PairContacts), and a
// region with volume has a projection of positive area, so the fallback serves only a method
// that reports no area.
double meanPenetration(const volume::ContactVolume& cv) {
  if (!cv.inContact()) return 0.0;
  return cv.area > 0.0 ? cv.volume / cv.area : cv.depth;
}

void checkBody(const RigidBody& b) {
  if (b.motion != BodyMotion::kFree) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(b.I_BBcm_B);
  if (!(b.mass > 0.0) || !std::isfinite(b.mass) || !(eig.eigenvalues().minCoeff() > 0.0)) {
    throw InputError("body '" + b.name + "'",
                     "a free body needs a positive mass and a positive-definite inertia");
  }
}

/// A distributed-friction pair integrates over the columns δ map with a model that can be
/// distributed (Model::checkDistributedFriction), on a grid of a resolution in range.
void checkDistributedPair(const ContactPair& p) {
  if (p.friction != FrictionMode::kDistributed) return;
  const std::string where = "pair '" + p.name + "'";
  if (p.method && !volume::fillsDepthField(*p.method)) {
    throw InputError(where, "distributed friction needs the columns method, not " +
                                volume::methodName(*p.method));
  }
  if (p.column_resolution < kMinColumnResolution || p.column_resolution > kMaxColumnResolution) {
    throw InputError(where, "column resolution " + std::to_string(p.column_resolution) +
                                " is outside [" + std::to_string(kMinColumnResolution) + ", " +
                                std::to_string(kMaxColumnResolution) + "]");
  }
  try {
    p.model.checkDistributedFriction();
  } catch (const InputError& e) {
    throw InputError(where, e.message());
  }
}

}  // namespace

MotionEquations::MotionEquations(Scenario scenario) : scenario_(std::move(scenario)) {
  const bool keep_contexts = scenario_.settings.integrator == Integrator::kDiscrete;
  const int n = layoutStates();
  setInitialState(n);
  last_pairs_.resize(scenario_.pairs.size());
  kin_.resize(scenario_.bodies.size());
  contacts_.emplace(scenario_, keep_contexts);
  checkLoads();
  if (keep_contexts) last_context_.resize(scenario_.pairs.size());
  force_.resize(scenario_.bodies.size());
  torque_.resize(scenario_.bodies.size());
}

// Checks the bodies and pairs and places their states: the free bodies' 13 each, then each
// pair's model states. Returns the state size.
int MotionEquations::layoutStates() {
  int n = 0;
  for (const auto& b : scenario_.bodies) {
    checkBody(b);
    offset_.push_back(b.motion == BodyMotion::kFree ? n : -1);
    if (b.motion == BodyMotion::kFree) n += kBodyStates;
    size_.push_back(characteristicSize(b.shape));
    I_inv_B_.push_back(b.motion == BodyMotion::kFree ? Eigen::Matrix3d(b.I_BBcm_B.inverse())
                                                     : Eigen::Matrix3d::Zero());
  }
  for (const auto& p : scenario_.pairs) {
    if (p.a >= scenario_.bodies.size() || p.b >= scenario_.bodies.size() || p.a == p.b) {
      throw InputError("pair '" + p.name + "'", "needs two different bodies of the scenario");
    }
    checkDistributedPair(p);
    pair_offset_.push_back(n);
    slots_.push_back(patchSlots(scenario_, p));
    trackers_.emplace_back(slots_.back());
    matches_.emplace_back();
    n += slots_.back() * p.model.stateLayout().size();
  }
  return n;
}

// x0_: the free bodies' initial poses and velocities; the pair states start at zero.
void MotionEquations::setInitialState(int n) {
  x0_.assign(static_cast<std::size_t>(n), 0.0);
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    if (offset_[i] < 0) continue;
    const RigidBody& b = scenario_.bodies[i];
    double* s = &x0_[static_cast<std::size_t>(offset_[i])];
    const Eigen::Vector3d p = b.X_WB0 * b.p_BBcm;
    const Eigen::Quaterniond q(b.X_WB0.linear());
    const double init[kBodyStates] = {
        p.x(),         p.y(),         p.z(),         q.w(),       q.x(),       q.y(),      q.z(),
        b.v_WBcm0.x(), b.v_WBcm0.y(), b.v_WBcm0.z(), b.w_WB0.x(), b.w_WB0.y(), b.w_WB0.z()};
    std::copy(init, init + kBodyStates, s);
  }
}

BodyKinematics MotionEquations::kinematics(const State& x, std::size_t i, double t) const {
  const RigidBody& body = scenario_.bodies[i];
  if (offset_[i] < 0) return scheduledKinematics(body, t);
  const double* s = &x[static_cast<std::size_t>(offset_[i])];
  BodyKinematics k;
  k.t = t;
  k.p_WBcm = Eigen::Vector3d(s[0], s[1], s[2]);
  k.X_WB.linear() = quaternionAt(s + 3).toRotationMatrix();
  k.X_WB.translation() = k.p_WBcm - k.X_WB.linear() * body.p_BBcm;
  k.v_WBcm = Eigen::Vector3d(s[7], s[8], s[9]);
  k.w_WB = Eigen::Vector3d(s[10], s[11], s[12]);
  return k;
}

// ẋ for the bodies (Newton–Euler in W) and the pair states (the models' rates).
void MotionEquations::rhs(const State& x, State& dxdt, double t) {
  ++rhs_count_;
  rhs_t_ = t;
  const std::size_t nb = scenario_.bodies.size();
  for (std::size_t i = 0; i < nb; ++i) {
    if (shortcuts_ && fixed_ready_ && scenario_.bodies[i].motion == BodyMotion::kFixed)
      kin_[i].t = t;  // a fixed body's pose and (zero) twist are those of every other time
    else
      kin_[i] = kinematics(x, i, t);
    force_[i].setZero();
    torque_[i].setZero();
  }
  contacts_->screen(kin_);
  evaluatePairs(x, dxdt);
  applyLoads(t);
  for (std::size_t i = 0; i < nb; ++i) {
    if (offset_[i] >= 0) bodyRates(i, x, dxdt);
  }
  last_x_ = x;
  fixed_ready_ = true;
}

// Free body i's 13 rates into dxdt, from force_[i] and torque_[i] (about its Bcm).
void MotionEquations::bodyRates(std::size_t i, const State& x, State& dxdt) const {
  const RigidBody& body = scenario_.bodies[i];
  const double* s = &x[static_cast<std::size_t>(offset_[i])];
  double* d = &dxdt[static_cast<std::size_t>(offset_[i])];
  if (sleep_.asleep(i)) {  // it stays put (in an interval the discrete stepper resolves)
    std::fill_n(d, kBodyStates, 0.0);
    return;
  }
  const Eigen::Vector3d& w = kin_[i].w_WB;
  // q̇ = ½ (0, ω_W) ⊗ q  (ω in the world frame)
  const Eigen::Quaterniond q(s[3], s[4], s[5], s[6]);
  const Eigen::Quaterniond q_dot = Eigen::Quaterniond(0.0, w.x(), w.y(), w.z()) * q;
  // m v̇ = F + m g;  I_W ω̇ = τ − ω × I_W ω,  I_W = R I_B Rᵀ, I_W⁻¹ = R I_B⁻¹ Rᵀ
  const Eigen::Matrix3d R = kin_[i].X_WB.linear();
  const Eigen::Vector3d w_B = R.transpose() * w;
  const Eigen::Vector3d h_W = R * (body.I_BBcm_B * w_B);
  const Eigen::Vector3d v_dot = force_[i] / body.mass + scenario_.gravity_W;
  const Eigen::Vector3d w_dot = R * (I_inv_B_[i] * (R.transpose() * (torque_[i] - w.cross(h_W))));
  const double rates[kBodyStates] = {s[7],
                                     s[8],
                                     s[9],
                                     0.5 * q_dot.w(),
                                     0.5 * q_dot.x(),
                                     0.5 * q_dot.y(),
                                     0.5 * q_dot.z(),
                                     v_dot.x(),
                                     v_dot.y(),
                                     v_dot.z(),
                                     w_dot.x(),
                                     w_dot.y(),
                                     w_dot.z()};
  std::copy(rates, rates + kBodyStates, d);
}

// Rescales every free body's quaternion to unit length; returns the largest | |q| − 1 | found.
double MotionEquations::normaliseQuaternions(State& x) const {
  double drift = 0.0;
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    if (offset_[i] < 0) continue;
    double* q = &x[static_cast<std::size_t>(offset_[i]) + 3];
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int j = 0; j < 4; ++j) q[j] /= norm;
    drift = std::max(drift, std::abs(norm - 1.0));
  }
  return drift;
}

// Discrete updates after an accepted step; true when the derivative must be re-evaluated.
bool MotionEquations::settle(State& x, double t) {
  normaliseQuaternions(x);
  return settlePairs(x, t);
}

// The blow-up guard after an accepted step (trackers/energy_guard.hpp): O(bodies + pairs).
void MotionEquations::checkEnergy(const State& x, double t) {
  const bool current = kinematicsCurrent(x, t);
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i)
    guard_kin_[i] = current ? kin_[i] : kinematics(x, i, t);
  const std::string message = energy_guard_->check(guard_kin_, last_pairs_, last_loads_, t);
  if (!message.empty()) throw SimulationError(t, StopCause::kBlowUp, stopTime(t) + ", " + message);
}

// Failures that stop the run: non-finite state, too deep a penetration, a blow-up.
void MotionEquations::check(const State& x, double t) {
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    if (offset_[i] < 0) continue;
    for (int j = 0; j < kBodyStates; ++j) {
      if (std::isfinite(x[static_cast<std::size_t>(offset_[i] + j)])) continue;
      throw SimulationError(t, StopCause::kNonFinite,
                            stopTime(t) + ", body '" + scenario_.bodies[i].name +
                                "': state is not finite (position, attitude or velocity)" +
                                non_finite_effect_);
    }
  }
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const ContactPair& pair = scenario_.pairs[k];
    const double size = std::min(size_[pair.a], size_[pair.b]);
    const double limit = scenario_.settings.max_penetration_fraction * size;
    double depth = meanPenetration(last_pairs_[k].cv);
    for (const PatchOutput& patch : last_pairs_[k].patches) {
      depth = std::max(depth, meanPenetration(patch.cv));
    }
    if (!std::isfinite(depth) || depth > limit) {
      std::ostringstream s;
      s << stopTime(t) << ", pair '" << pair.name << "': mean penetration V/A " << depth
        << " m exceeds " << scenario_.settings.max_penetration_fraction
        << " of the smaller body's size (" << size << " m); the contact is too soft or the "
        << "bodies passed through each other";
      throw SimulationError(t, StopCause::kPenetration, s.str());
    }
  }
  checkEnergy(x, t);
}

// ", pair 'name' (normal force F N)" for the pair with the largest normal force at the latest
// evaluation: the likeliest cause of a step-size collapse. Empty when nothing touches.
std::string MotionEquations::stiffestPair() const {
  std::size_t best = last_pairs_.size();
  double f_max = 0.0;
  for (std::size_t k = 0; k < last_pairs_.size(); ++k) {
    if (last_pairs_[k].result.f_n > f_max) {
      f_max = last_pairs_[k].result.f_n;
      best = k;
    }
  }
  if (best == last_pairs_.size()) return "";
  std::ostringstream s;
  s << ", pair '" << scenario_.pairs[best].name << "' (normal force " << f_max << " N)";
  return s.str();
}

SimulationError MotionEquations::stepCollapse(double t, double h, const std::string& detail) const {
  std::ostringstream s;
  s << stopTime(t) << stiffestPair() << ": step size " << h << " s fell below the minimum "
    << scenario_.settings.min_step << " s (contact too stiff for the tolerances, or a "
    << "discontinuity" << detail << ")";
  return SimulationError(t, StopCause::kStepCollapse, s.str());
}

// "body 'name' (velocity)" or "pair 'name' (bristle state zx)" for state index i.
std::string MotionEquations::stateOwner(std::size_t i) const {
  for (std::size_t b = 0; b < offset_.size(); ++b) {
    if (offset_[b] < 0 || i < static_cast<std::size_t>(offset_[b]) ||
        i >= static_cast<std::size_t>(offset_[b] + kBodyStates)) {
      continue;
    }
    static const char* const kQuantity[] = {"position", "attitude", "velocity", "angular velocity"};
    const std::size_t j = i - static_cast<std::size_t>(offset_[b]);
    return "body '" + scenario_.bodies[b].name + "' (" +
           kQuantity[j < 3    ? 0
                     : j < 7  ? 1
                     : j < 10 ? 2
                              : 3] +
           ")";
  }
  for (std::size_t k = 0; k < pair_offset_.size(); ++k) {
    const StateLayout& layout = scenario_.pairs[k].model.stateLayout();
    const int j = static_cast<int>(i) - pair_offset_[k];
    if (j < 0 || j >= slots_[k] * layout.size()) continue;
    const std::string slot =
        slots_[k] > 1 ? ", patch slot " + std::to_string(j / layout.size()) : "";
    return "pair '" + scenario_.pairs[k].name + "' (" + layout.describe(j % layout.size()) + slot +
           ")";
  }
  return "state " + std::to_string(i);
}

void MotionEquations::beginRun() {
  non_finite_effect_.clear();
  contacts_->setQueryDepths(false);  // a run that stopped in a discrete step may have left it set
  keep_contexts_ = false;
  contacts_->resetCounts();
  sleep_.reset(scenario_);
}

const Snapshot& MotionEquations::firstOutput(const State& x, double t) {
  guard_kin_.resize(scenario_.bodies.size());
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) guard_kin_[i] = kinematics(x, i, t);
  const Snapshot& first = snapshot(x, t, true);  // with the depths, which the guard's bound uses
  energy_guard_.emplace(scenario_, guard_kin_, first.pairs);
  return first;
}

}  // namespace vcontact::dynamics
