// The discrete stepper (Integrator::kDiscrete, docs/DISCRETE.md §3): a fixed
// step h, one contact query per step, the contact wrenches linearised about the step's start
// (discrete_jacobian.hpp) and solved implicitly for the free bodies' new twists:
//
//   M (V⁺ − V) = h [ F_loads + m g − ω × I_W ω + Σ_patches Gᵀ (c + L ξ⁺) ],   ξ⁺ = G V⁺,
//   p⁺ = p + h v⁺,   q⁺ = exp(h ω⁺) q,
//
// a dense solve of 6 × (free bodies) unknowns. The pair states are advanced with the step:
// the bristle deflections implicitly (PatchStep), the others (dwell) by explicit Euler.

#include "dynamics/steppers/discrete_stepper.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstring>
#include <sstream>

#include "geometry/error.hpp"

namespace vcontact::dynamics {
namespace {

constexpr int kBodyStates = MotionEquations::kBodyStates;

// G of a body at lever arm r = p_c − p_cm: the velocity at p_c and ω from the body's twist
// (v_cm, ω), v(p_c) = v_cm + ω × r; Gᵀ moves a wrench at p_c to the centre of mass.
Matrix6d leverMap(const Eigen::Vector3d& r) {
  Matrix6d G = Matrix6d::Identity();
  Eigen::Matrix3d rx;
  rx << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  G.topRightCorner<3, 3>() = -rx;  // ω × r = −[r]× ω
  return G;
}

Vector6d bodyTwist(const BodyKinematics& k) {
  Vector6d V;
  V << k.v_WBcm, k.w_WB;
  return V;
}

// q⁺ = exp(h ω) ⊗ q for a world-frame angular velocity ω, as a rotation vector.
Eigen::Quaterniond rotated(const Eigen::Quaterniond& q, const Eigen::Vector3d& w, double h) {
  const double angle = w.norm() * h;
  if (angle == 0.0) return q;
  return (Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())) * q).normalized();
}

}  // namespace

DiscreteStepper::DiscreteStepper(MotionEquations& equations, ImpactTracker& impacts)
    : eq_(equations),
      scenario_(equations.scenario()),
      impacts_(impacts),
      dopri5_(equations, impacts),
      kin_(equations.bodies()),
      last_pairs_(equations.pairs()) {
  const double h = scenario_.settings.step;
  if (!(h >= kMinDiscreteStep && h <= kMaxDiscreteStep)) {
    std::ostringstream s;
    s << "step " << h << " s is outside [" << kMinDiscreteStep << ", " << kMaxDiscreteStep << "] s";
    throw InputError("settings", s.str());
  }
}

void DiscreteStepper::run(State& x, State& dxdt, double& t, const OutputFn& on_output,
                          const ProgressFn& on_progress, SimulationSummary& summary) {
  const SimulationSettings& set = scenario_.settings;
  for (const ContactPair& p : scenario_.pairs) {
    if (p.friction == FrictionMode::kDistributed) {
      throw InputError("pair '" + p.name + "'",
                       "the discrete integrator has no linearisation of distributed friction; "
                       "use \"friction\": \"lumped\" or the dopri5 or bdf integrator");
    }
  }
  const double interval = 1.0 / set.output_rate_hz;
  long next_output = 1;
  resolve_dt_ = 0.0;
  while (t < set.duration) {
    const double t_target = std::min(static_cast<double>(next_output) * interval, set.duration);
    const bool lands = t_target - t <= set.step * (1.0 + kOutputTimeSlack);
    const double h = lands ? t_target - t : set.step;
    if (eq_.sleep().enabled()) sleepBeforeStep(x, t);
    advance(x, dxdt, t, h, lands ? t_target : t + h, lands, summary);
    ++summary.steps;
    if (lands) {
      on_output(eq_.snapshot(x, t, eq_.outputDepths()));
      ++next_output;
    }
    on_progress(t);
  }
}

// One step from the contacts of the latest query (at x): assemble, solve, update x.
void DiscreteStepper::plainStep(State& x, double t, double h) {
  const std::size_t nb = scenario_.bodies.size();
  int n = 0;
  column_.resize(nb);
  next_kin_.resize(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    const bool integrated =
        eq_.bodyOffset(i) >= 0 && !eq_.sleep().asleep(i);  // a sleeping body stays put
    column_[i] = integrated ? n : -1;
    if (integrated) n += 6;
    next_kin_[i] =
        eq_.bodyOffset(i) >= 0 ? kin_[i] : scheduledKinematics(scenario_.bodies[i], t + h);
  }
  step_matrix_.setZero(n, n);
  step_rhs_.setZero(n);
  // explicit parts: loads and springs, gravity, gyroscopic torque; the mass matrix
  eq_.loadWrenches(t);
  for (std::size_t i = 0; i < nb; ++i) {
    if (column_[i] < 0) continue;
    const RigidBody& body = scenario_.bodies[i];
    const Eigen::Matrix3d R = kin_[i].X_WB.linear();
    const Eigen::Matrix3d I_W = R * body.I_BBcm_B * R.transpose();
    const Eigen::Vector3d& w = kin_[i].w_WB;
    const int c = column_[i];
    step_matrix_.block<3, 3>(c, c) = body.mass * Eigen::Matrix3d::Identity();
    step_matrix_.block<3, 3>(c + 3, c + 3) = I_W;
    step_rhs_.segment<3>(c) =
        body.mass * kin_[i].v_WBcm + h * (eq_.force(i) + body.mass * scenario_.gravity_W);
    step_rhs_.segment<3>(c + 3) = I_W * w + h * (eq_.torque(i) - w.cross(I_W * w));
  }
  assembleLoads(t, h);
  in_flight_.assign(nb, 1);
  for (const ExternalLoad& l : scenario_.loads) in_flight_[l.body] = 0;
  for (const BodySpring& s : scenario_.springs) in_flight_[s.a] = in_flight_[s.b] = 0;
  if (scenario_.settings.impacts != ImpactMode::kImplicit) {  // for newtonStep
    base_matrix_ = step_matrix_;
    base_rhs_ = step_rhs_;
    base_in_flight_ = in_flight_;
  }
  assembleContacts(x, h, false);
  solveAndMove(x, kin_, h);
}

// The step again from its start (x = the start's state) with the contacts of the latest query,
// at the end of the step before: a Newton iteration of the implicit step (docs/DISCRETE.md §5).
// The bodies' inertia, gravity, gyroscopic torque, loads and springs are the start's, as in
// plainStep; each patch is linearised about the latest query's pose and twist, which lie h ξ
// beyond the start.
void DiscreteStepper::newtonStep(State& x, double h) {
  step_matrix_ = base_matrix_;
  step_rhs_ = base_rhs_;
  in_flight_ = base_in_flight_;
  // the free bodies' twists after the solve are taken at the poses the patches are linearised
  // about (stepImpulses, updateStates), as plainStep takes them at the start's
  for (std::size_t i = 0; i < next_kin_.size(); ++i) {
    if (eq_.bodyOffset(i) >= 0) next_kin_[i] = kin_[i];
  }
  assembleContacts(x, h, true);
  solveAndMove(x, start_kin_, h);
}

// Every patch of the latest query into the step's system (assemblePatch).
void DiscreteStepper::assembleContacts(const State& x, double h, bool about_end) {
  step_patch_count_ = 0;
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const PairOutput& out = last_pairs_[k];
    if (eq_.sleep().frozen(k)) continue;  // neither body in the system: it would add nothing
    if (eq_.slots(k) == 1) {
      assemblePatch(k, out.cv, 0, 0, x, h, about_end);
      continue;
    }
    for (std::size_t i = 0; i < out.patches.size(); ++i) {
      assemblePatch(k, out.patches[i].cv, eq_.match(k).host[i], out.patches[i].slot, x, h,
                    about_end);
    }
  }
}

// The step's system solved, and x (the start's state) moved over h: the pair states, then the
// bodies from the start's poses and velocities `start`.
void DiscreteStepper::solveAndMove(State& x, const std::vector<BodyKinematics>& start, double h) {
  const std::size_t nb = scenario_.bodies.size();
  if (eq_.shortcuts() && step_matrix_.rows() == 6 && step_patch_count_ == 0 &&
      scenario_.loads.empty() && scenario_.springs.empty()) {
    solveFlight();
  } else {
    step_lu_.compute(step_matrix_);
    step_twist_ = step_lu_.solve(step_rhs_);
  }
  for (std::size_t i = 0; i < nb; ++i) {
    if (column_[i] < 0) continue;
    next_kin_[i].v_WBcm = step_twist_.segment<3>(column_[i]);
    next_kin_[i].w_WB = step_twist_.segment<3>(column_[i] + 3);
  }
  updateStates(x, h);
  for (std::size_t i = 0; i < nb; ++i) {
    if (column_[i] < 0) continue;
    double* s = &x[static_cast<std::size_t>(eq_.bodyOffset(i))];
    const Eigen::Vector3d v = next_kin_[i].v_WBcm, w = next_kin_[i].w_WB;
    const Eigen::Quaterniond q = rotated(Eigen::Quaterniond(s[3], s[4], s[5], s[6]), w, h);
    // In free flight the force is constant over the step (gravity), so the trapezoid rule
    // moves the centre of mass exactly; in contact the displacement is h v⁺, with which (1.3)
    // linearised the stiffness (docs/DISCRETE.md §1).
    const Eigen::Vector3d u = in_flight_[i] ? Eigen::Vector3d(0.5 * (start[i].v_WBcm + v)) : v;
    const double next[kBodyStates] = {s[0] + h * u.x(),
                                      s[1] + h * u.y(),
                                      s[2] + h * u.z(),
                                      q.w(),
                                      q.x(),
                                      q.y(),
                                      q.z(),
                                      v.x(),
                                      v.y(),
                                      v.z(),
                                      w.x(),
                                      w.y(),
                                      w.z()};
    std::copy(next, next + kBodyStates, s);
  }
}

// The one free body of the scenario in free flight (no patch, load or spring in the step):
// the system diag(m I, I_W) is solved by blocks, v⁺ = b_v / m and I_W ω⁺ = b_ω by the same
// partial-pivoting LU. These are the numbers of the 6 × 6 LU to the bit: its elimination and
// triangular solves only add or subtract products with the zero blocks, which change no
// nonzero value, and divide by m exactly as here (tested, discrete_shortcuts_test.cpp). Not
// for several bodies: Eigen's triangular solve sums the columns beyond its panel of 8 in
// another order, so a body's numbers in a 12 × 12 system differ from its own 6 × 6 ones in
// the last bits.
void DiscreteStepper::solveFlight() {
  step_twist_.resize(step_rhs_.size());
  flight_rhs_.resize(3);
  for (std::size_t i = 0; i < column_.size(); ++i) {
    const int c = column_[i];
    if (c < 0) continue;
    step_twist_.segment<3>(c) = step_rhs_.segment<3>(c) / scenario_.bodies[i].mass;
    flight_matrix_ = step_matrix_.block<3, 3>(c + 3, c + 3);
    flight_rhs_ = step_rhs_.segment<3>(c + 3);
    flight_lu_.compute(flight_matrix_);
    flight_twist_ = flight_lu_.solve(flight_rhs_);
    step_twist_.segment<3>(c + 3) = flight_twist_;
  }
}

// Patch (contact cv of pair k, states of slot `host`, its own slot `slot` or −1) into the
// step's system: body A gets Gᵀ_A (c + L ξ⁺), body B the opposite at the same point.
// about_end: cv and the bodies' kinematics are the end of an earlier iterate (newtonStep).
void DiscreteStepper::assemblePatch(std::size_t k, const volume::ContactVolume& cv, int host,
                                    int slot, const State& x, double h, bool about_end) {
  if (!cv.inContact()) return;
  const ContactPair& pair = scenario_.pairs[k];
  in_flight_[pair.a] = in_flight_[pair.b] = 0;
  if (step_patch_count_ == step_patches_.size()) step_patches_.emplace_back();
  DiscretePatch& dp = step_patches_[step_patch_count_++];
  dp.pair = k;
  dp.slot = slot;
  dp.p_c = cv.p_WC;
  dp.n = cv.n_W;
  const int size = pair.model.stateLayout().size();
  const PairState state =
      PairState::unpack(&x[static_cast<std::size_t>(eq_.pairOffset(k) + host * size)], size);
  const RelativeMotion motion = relativeMotion(kin_[pair.a], kin_[pair.b], cv.p_WC);
  if (eq_.shortcuts() && evaluatedAt(k, cv, motion, state)) {
    dp.step.start = last_pairs_[k].result;
    linearisePatch(pair.model, eq_.context(k).ctx, motion, h, dp.step, about_end);
  } else {
    linearisePatch(pair.model, cv, motion, state, h, dp.step, about_end);
  }
  const std::size_t body[2] = {pair.a, pair.b};
  const double sign[2] = {1.0, -1.0};  // ξ = G_A V_A − G_B V_B; B gets the opposite wrench
  Matrix6d G[2];
  for (int j = 0; j < 2; ++j) G[j] = leverMap(cv.p_WC - kin_[body[j]].p_WBcm);
  for (int r = 0; r < 2; ++r) {
    const int row = column_[body[r]];
    if (row < 0) continue;
    const Matrix6d GtL = sign[r] * h * G[r].transpose() * dp.step.L;
    step_rhs_.segment<6>(row) += sign[r] * h * G[r].transpose() * dp.step.c;
    for (int c = 0; c < 2; ++c) {
      const int col = column_[body[c]];
      const Matrix6d block = GtL * (sign[c] * G[c]);
      if (col >= 0) {
        step_matrix_.block<6, 6>(row, col) -= block;
      } else {
        step_rhs_.segment<6>(row) += block * bodyTwist(next_kin_[body[c]]);
      }
    }
  }
}

// Whether the latest evaluation of pair k (evaluatePair, one slot) was made at contact cv,
// motion and state, to the bit: then its result and context are the step's start. They are
// unless a settle moved the state by less than its re-evaluation tolerance, or the pair has
// several slots.
bool DiscreteStepper::evaluatedAt(std::size_t k, const volume::ContactVolume& cv,
                                  const RelativeMotion& motion, const PairState& state) const {
  const EvaluationContext& e = eq_.context(k);
  if (!e.valid || &cv != &last_pairs_[k].cv) return false;
  const auto same = [](const auto& a, const auto& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
  };
  const int size = scenario_.pairs[k].model.stateLayout().size();
  double before[PairState::kCapacity], now[PairState::kCapacity];
  last_pairs_[k].state.pack(before, size);
  state.pack(now, size);
  return same(e.motion.v_c_W, motion.v_c_W) && same(e.motion.w_W, motion.w_W) &&
         e.motion.t == motion.t &&
         std::memcmp(before, now, sizeof(double) * static_cast<std::size_t>(size)) == 0;
}

// The pair states over the step: explicit Euler from the start's rates, the bristle states
// from their implicit update at the solved twists. A slot without a patch keeps its states
// (settle resets them when the contact is gone).
void DiscreteStepper::updateStates(State& x, double h) {
  for (std::size_t j = 0; j < step_patch_count_; ++j) {
    const DiscretePatch& dp = step_patches_[j];
    if (dp.slot < 0) continue;
    const ContactPair& pair = scenario_.pairs[dp.pair];
    const int size = pair.model.stateLayout().size();
    double* s = &x[static_cast<std::size_t>(eq_.pairOffset(dp.pair) + dp.slot * size)];
    PairState state = PairState::unpack(s, size);
    for (int i = 0; i < size; ++i) state[i] += h * dp.step.start.rates[i];
    if (const ImplicitStates& next = dp.step.implicit; next.any()) {
      const BodyKinematics& A = next_kin_[pair.a];
      const BodyKinematics& B = next_kin_[pair.b];
      const RelativeMotion m = relativeMotion(A, B, dp.p_c);
      Vector6d xi;
      xi << m.v_c_W, m.w_W;
      state.vector(next.offset) = next.z_c + next.Z * xi;
      state[next.offset + 3] = next.theta_c + (next.Theta * xi)(0);
    }
    state.pack(s, size);
  }
}

}  // namespace vcontact::dynamics
