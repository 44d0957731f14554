#include "dynamics/simulator.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <sstream>

#include "dynamics/bdf_integrator.hpp"
#include "geometry/error.hpp"
#include "io/interrupt.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {
namespace {

constexpr int kBodyStates = 13;  // p_WBcm (3), q_WB (w, x, y, z), v_WBcm (3), w_WB (3)

// BDF: |q| may drift this far from 1 before the state is rescaled (a restart). The error
// weights of q change by as much, relatively: negligible.
constexpr double kQuaternionNormDrift = 1e-3;

std::string where(double t) {
  std::ostringstream s;
  s.precision(9);
  s << "t = " << t << " s";
  return s.str();
}

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

// True when some state moved from `before` to `after` by more than its error tolerance.
bool exceedsTolerance(const Simulator::State& before, const Simulator::State& after,
                      const SimulationSettings& set) {
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (std::abs(after[i] - before[i]) > set.abs_tol + set.rel_tol * std::abs(before[i])) {
      return true;
    }
  }
  return false;
}

bool allFinite(const Simulator::State& v) {
  return std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); });
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

Simulator::Simulator(Scenario scenario) : scenario_(std::move(scenario)) {
  const int n = layoutStates();
  setInitialState(n);
  last_pairs_.resize(scenario_.pairs.size());
  kin_.resize(scenario_.bodies.size());
  const bool discrete = scenario_.settings.integrator == Integrator::kDiscrete;
  contacts_.emplace(scenario_, discrete);
  checkLoads();
  if (discrete) {
    const double h = scenario_.settings.step;
    if (!(h >= kMinDiscreteStep && h <= kMaxDiscreteStep)) {
      std::ostringstream s;
      s << "step " << h << " s is outside [" << kMinDiscreteStep << ", " << kMaxDiscreteStep
        << "] s";
      throw InputError("settings", s.str());
    }
    last_context_.resize(scenario_.pairs.size());
  }
  force_.resize(scenario_.bodies.size());
  torque_.resize(scenario_.bodies.size());
}

// Checks the bodies and pairs and places their states: the free bodies' 13 each, then each
// pair's model states. Returns the state size.
int Simulator::layoutStates() {
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
void Simulator::setInitialState(int n) {
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

BodyKinematics Simulator::kinematics(const State& x, std::size_t i, double t) const {
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
void Simulator::rhs(const State& x, State& dxdt, double t) {
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
void Simulator::bodyRates(std::size_t i, const State& x, State& dxdt) const {
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
double Simulator::normaliseQuaternions(State& x) const {
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
bool Simulator::settle(State& x, double t) {
  normaliseQuaternions(x);
  return settlePairs(x, t);
}

// The blow-up guard after an accepted step (energy_guard.hpp): O(bodies + pairs).
void Simulator::checkEnergy(const State& x, double t) {
  const bool current = kinematicsCurrent(x, t);
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i)
    guard_kin_[i] = current ? kin_[i] : kinematics(x, i, t);
  const std::string message = energy_guard_->check(guard_kin_, last_pairs_, last_loads_, t);
  if (!message.empty()) throw SimulationError(t, StopCause::kBlowUp, where(t) + ", " + message);
}

// Failures that stop the run: non-finite state, too deep a penetration, a blow-up.
void Simulator::check(const State& x, double t) {
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    if (offset_[i] < 0) continue;
    for (int j = 0; j < kBodyStates; ++j) {
      if (std::isfinite(x[static_cast<std::size_t>(offset_[i] + j)])) continue;
      throw SimulationError(t, StopCause::kNonFinite,
                            where(t) + ", body '" + scenario_.bodies[i].name +
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
      s << where(t) << ", pair '" << pair.name << "': mean penetration V/A " << depth
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
std::string Simulator::stiffestPair() const {
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

SimulationError Simulator::stepCollapse(double t, double h, const std::string& detail) const {
  std::ostringstream s;
  s << where(t) << stiffestPair() << ": step size " << h << " s fell below the minimum "
    << scenario_.settings.min_step << " s (contact too stiff for the tolerances, or a "
    << "discontinuity" << detail << ")";
  return SimulationError(t, StopCause::kStepCollapse, s.str());
}

// "body 'name' (velocity)" or "pair 'name' (bristle state zx)" for state index i.
std::string Simulator::stateOwner(std::size_t i) const {
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

// The right-hand side for CVODE: false, and the first non-finite rate remembered, when the
// derivative is not finite (CVODE then retries with a shorter step).
bool Simulator::rhsFinite(const double* x, double* dxdt, double t) {
  rhs_x_.assign(x, x + x0_.size());
  rhs_dxdt_.resize(x0_.size());
  rhs(rhs_x_, rhs_dxdt_, t);
  std::copy(rhs_dxdt_.begin(), rhs_dxdt_.end(), dxdt);
  if (allFinite(rhs_dxdt_)) return true;
  const auto bad =
      std::find_if(rhs_dxdt_.begin(), rhs_dxdt_.end(), [](double d) { return !std::isfinite(d); });
  non_finite_ = stateOwner(static_cast<std::size_t>(bad - rhs_dxdt_.begin()));
  return false;
}

// CVODE's failures in the words of the explicit path: time, pair or body, quantity.
SimulationError Simulator::bdfFailure(const BdfError& e, double t_last) const {
  const double t = std::max(e.time(), t_last);
  if (e.stepCollapse())
    return stepCollapse(t, std::abs(e.stepSize()), "; BDF: " + std::string(e.what()));
  std::ostringstream s;
  if (e.rhsFailed()) {
    s << where(t) << ", " << non_finite_ << ": the rate of change is not finite at every step "
      << "size tried, down to " << std::abs(e.stepSize()) << " s" << non_finite_effect_;
    return SimulationError(t, StopCause::kNonFinite, s.str());
  }
  s << where(t) << stiffestPair() << ": the implicit (BDF) integrator stopped at step size "
    << std::abs(e.stepSize()) << " s: " << e.what();
  return SimulationError(t, StopCause::kIntegratorFailure, s.str());
}

namespace {

// "interrupted by SIGINT at t = 0.0123 s" (strsignal's words would depend on the locale).
SimulationError interrupted(int signal, double t) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : nullptr;
  std::ostringstream s;
  s << "interrupted by " << (name ? name : "signal " + std::to_string(signal)) << " at t = " << t
    << " s";
  return SimulationError(t, StopCause::kInterrupted, s.str());
}

}  // namespace

void Simulator::run(const std::function<void(const Snapshot&)>& on_output,
                    const std::function<void(double)>& on_progress, SimulationSummary& summary) {
  const auto wall_start = std::chrono::steady_clock::now();
  const long rhs_start = rhs_count_, contacts_start = contacts_->queries(),
             skipped_start = contacts_->skipped();
  double t = 0.0;
  long patch_samples = 0, patch_total = 0;
  const OutputFn output = [&](const Snapshot& s) {
    countPatches(s, summary, patch_samples, patch_total);
    on_output(s);
  };
  // Each integrator calls this after every accepted step: the one place an interruption is
  // looked for (a flag read, no system call).
  const ProgressFn progress = [&](double t_now) {
    if (const int signal = io::interruptSignal()) throw interrupted(signal, t_now);
    on_progress(t_now);
  };
  auto finish = [&] {
    summary.patches_mean = patch_samples > 0 ? double(patch_total) / double(patch_samples) : 0.0;
    summary.simulated_time = t;
    summary.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    summary.rhs_evaluations = rhs_count_ - rhs_start;
    summary.contact_evaluations = contacts_->queries() - contacts_start;
    summary.surface_bodies = contacts_->recovered().bodies();
    summary.surface_pairs = contacts_->recovered().pairs();
    impacts_.finish(t);
    summary.impacts = impacts_.impacts();
    summary.sleep_events = sleep_.events();
    summary.sleep_skipped_queries = contacts_->skipped() - skipped_start;
  };

  non_finite_effect_.clear();
  contacts_->setQueryDepths(false);  // a run that stopped in a discrete step may have left it set
  keep_contexts_ = false;
  contacts_->resetCounts();
  sleep_.reset(scenario_);
  State x = x0_;
  State dxdt(x.size());
  rhs(x, dxdt, t);
  settle(x, t);
  rhs(x, dxdt, t);
  guard_kin_.resize(scenario_.bodies.size());
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) guard_kin_[i] = kinematics(x, i, t);
  const Snapshot& first = snapshot(x, t, true);  // with the depths, which the guard's bound uses
  energy_guard_.emplace(scenario_, guard_kin_, first.pairs);
  output(first);
  // An impact settles once the normal speed stays below the speed at which the discrete
  // stepper resolves impacts (at h = 1 ms at least) for five such steps.
  const double scale = std::max(scenario_.settings.step, 1e-3);
  impacts_.reset(scenario_, impactThreshold(scale), 5.0 * scale,
                 scenario_.settings.integrator == Integrator::kDiscrete);
  impacts_.observe(t, kin_, last_pairs_);
  try {
    if (scenario_.settings.integrator == Integrator::kBdf) {
      runBdf(x, t, output, progress, summary);
    } else if (scenario_.settings.integrator == Integrator::kDiscrete) {
      runDiscrete(x, dxdt, t, output, progress, summary);
    } else {
      runDopri5(x, dxdt, t, output, progress, summary);
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
}

// CVODE steps freely (up to max_step) and the outputs are read from each step's interpolating
// polynomial. The discrete updates of the pair states are applied by a restart, and only when
// they move some state by more than its error tolerance: smaller ones (the projection of z
// after the normal turned by a step's worth) are within the integration error, and
// Model::evaluate applies them anyway. The quaternions are rescaled only when |q| drifted by
// kQuaternionNormDrift: kinematics() normalises q, and q̇ = ½ (0, ω) ⊗ q turns q at the right
// rate whatever its length, so the drift changes no physics; a restart at every step's worth of
// drift (the relative tolerance) would keep the BDF at order 1.
void Simulator::runBdf(State& x, double& t, const OutputFn& on_output,
                       const ProgressFn& on_progress, SimulationSummary& summary) {
  const SimulationSettings& set = scenario_.settings;
  const BdfIntegrator::Settings bdf_settings{set.abs_tol,  set.rel_tol,  set.initial_step,
                                             set.max_step, set.min_step, set.duration};
  BdfIntegrator bdf(
      x.size(), [this](double t, const double* x, double* dxdt) { return rhsFinite(x, dxdt, t); },
      bdf_settings, t, x.data());
  const double interval = 1.0 / set.output_rate_hz;
  long next_output = 1;
  State x_out(x.size()), settled(x.size());
  auto count = [&] {
    const BdfIntegrator::Counts c = bdf.counts();
    summary.steps = c.steps;
    summary.rejected_steps = c.rejected;
    summary.jacobian_evaluations = c.jacobians;
  };
  while (t < set.duration) {
    const double t_last = t;
    try {
      t = bdf.step();
    } catch (const BdfError& e) {
      count();
      throw bdfFailure(e, t_last);
    }
    count();
    std::copy(bdf.state(), bdf.state() + x.size(), x.begin());
    // The contacts of the last Newton iterate stand for those of x: it converged to within a
    // tenth of the error tolerance of x (CVODE's convergence test), and a fresh evaluation would
    // cost a third of all contact evaluations.
    check(x, t);
    settled = x;
    settlePairs(settled, t);
    const bool jumped =
        exceedsTolerance(x, settled, set) || normaliseQuaternions(settled) > kQuaternionNormDrift;
    for (;;) {
      const double t_out = std::min(static_cast<double>(next_output) * interval, set.duration);
      if (t_out > t + kOutputTimeSlack * interval) break;
      bdf.interpolate(std::min(t_out, t), x_out.data());
      on_output(snapshot(x_out, t_out, output_depths_));
      ++next_output;
      if (t_out >= set.duration) break;
    }
    if (jumped) bdf.restart(t, settled.data());
    on_progress(t);
  }
}

}  // namespace vcontact::dynamics
