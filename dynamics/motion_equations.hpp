#pragma once
// The equations of motion of a Scenario, as every integrator sees them (steppers/stepper.hpp):
//
// - the state: each free body's 13 states (p_WBcm, q_WB as w x y z, v_WBcm, ω_WB), then each
//   pair's model states, slot by slot (patchSlots); x0 from the bodies' initial poses and
//   velocities, the pair states at zero;
// - its right-hand side: Newton–Euler in W under gravity, the loads' and springs' wrenches
//   (loads.hpp) and the contact wrenches of every pair, and the pairs' state rates;
// - the discrete updates of an accepted state (settle: quaternions rescaled, Model::settle of
//   every slot, the patch trackers told where the patches are);
// - the checks that stop a run (check), and the output snapshot.
//
// Every right-hand side takes the pairs' contacts from PairContacts (pair_contacts.hpp): the
// broad phase screens them (a pair whose boxes do not overlap gets the empty contact without a
// query), the rest are queried, pairs of sleeping bodies keep their latest contact. The pairs
// are evaluated side by side (TBB) and their wrenches summed pair by pair in order, so that
// results are identical to the bit whatever the thread count.
//
// The checks stop a run with a SimulationError naming time, pair or body and the quantity: a
// non-finite state, a mean penetration V/A beyond a set fraction of a body, or kinetic energy
// far beyond what the scenario can supply (a blow-up, dynamics/trackers/energy_guard.hpp).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/pair_contacts.hpp"
#include "dynamics/scenario.hpp"
#include "dynamics/simulation_output.hpp"
#include "dynamics/trackers/energy_guard.hpp"
#include "dynamics/trackers/patch_tracker.hpp"
#include "dynamics/trackers/sleep.hpp"

namespace vcontact::dynamics {

/// A one-slot pair's latest model evaluation in contact (discrete runs): its context and the
/// motion it was made at. The discrete step linearises about it instead of evaluating the model
/// again at the same contact, motion and state.
struct EvaluationContext {
  ContactContext ctx;  ///< ctx.cv points into the equations' latest pair outputs
  RelativeMotion motion;
  bool valid = false;  ///< the pair was in contact at that evaluation
};

class MotionEquations {
 public:
  using State = std::vector<double>;
  static constexpr int kBodyStates = 13;  ///< p (3), q (w, x, y, z), v (3), ω (3)

  /// For the discrete integrator, the pairs' evaluations may keep their contexts
  /// (setKeepContexts) and each pair its latest contact (PairContacts::setReuse).
  /// @throws InputError when a free body has no positive mass or inertia, a pair names a body
  ///         out of range or no method handles it, or a load or spring names no body
  explicit MotionEquations(Scenario scenario);
  // PairContacts holds a reference to scenario_: the equations stay where they were made.
  MotionEquations(const MotionEquations&) = delete;
  MotionEquations& operator=(const MotionEquations&) = delete;

  const Scenario& scenario() const { return scenario_; }
  const State& initialState() const { return x0_; }

  // --- The equations ---------------------------------------------------------------------

  /// ẋ at (x, t). Afterwards bodies(), pairs() and loads() are those of this evaluation.
  void rhs(const State& x, State& dxdt, double t);
  /// Whether (x, t) is the state of the latest right-hand side, to the bit.
  bool isLatest(const State& x) const { return x == last_x_; }
  /// Discrete updates after an accepted step; true when the derivative must be re-evaluated.
  bool settle(State& x, double t);
  /// settle() without the quaternions: the pair states only (and the patch trackers).
  bool settlePairs(State& x, double t);
  /// Rescales every free body's quaternion to unit length; returns the largest | |q| − 1 |.
  double normaliseQuaternions(State& x) const;
  /// Body `body`'s kinematics at (x, t): its states, or its schedule when not free.
  BodyKinematics kinematics(const State& x, std::size_t body, double t) const;
  /// The failures that stop a run at an accepted state (x, t), the latest evaluation's
  /// contacts standing for those of x: a non-finite state, too deep a penetration, a blow-up.
  /// @throws SimulationError
  void check(const State& x, double t);
  /// The output at (x, t) (a right-hand side first unless x is the latest state); with
  /// `depths`, the exact depths the force evaluations left out are filled in (a second query
  /// of each pair in contact that lacks one). Valid until the next call.
  const Snapshot& snapshot(const State& x, double t, bool depths);

  // --- A run ---------------------------------------------------------------------------------

  /// A new run: the per-run modes and counts start again (the sleep tracker, the recovered
  /// pairs' counts, the first non-finite effect).
  void beginRun();
  /// The first output of a run at its settled initial state (x, t), with the depths, and the
  /// blow-up guard set from it.
  const Snapshot& firstOutput(const State& x, double t);
  long rhsCount() const { return rhs_count_; }

  // --- The words of a failure ----------------------------------------------------------------

  /// A step size h below the minimum at t, the stiffest pair named.
  SimulationError stepCollapse(double t, double h, const std::string& detail) const;
  /// ", pair 'name' (normal force F N)" for the pair with the largest normal force at the
  /// latest evaluation; empty when nothing touches.
  std::string stiffestPair() const;
  /// "body 'name' (velocity)" or "pair 'name' (bristle state zx)" for state index i.
  std::string stateOwner(std::size_t i) const;
  /// "; first non-finite force: pair …, effect …" once an effect's wrench was not finite at a
  /// finite contact during the run; empty otherwise.
  const std::string& nonFiniteEffect() const { return non_finite_effect_; }

  // --- What the discrete stepper reads and writes between right-hand sides --------------------

  /// The bodies' kinematics of the latest right-hand side (the discrete stepper zeroes the
  /// velocities of the bodies that fall asleep).
  std::vector<BodyKinematics>& bodies() { return kin_; }
  const std::vector<BodyKinematics>& bodies() const { return kin_; }
  /// The pairs' contacts and results of the latest right-hand side.
  const std::vector<PairOutput>& pairs() const { return last_pairs_; }
  /// Every load's and spring's wrench at bodies(), summed into force() and torque() from zero.
  void loadWrenches(double t);
  const Eigen::Vector3d& force(std::size_t body) const { return force_[body]; }
  const Eigen::Vector3d& torque(std::size_t body) const { return torque_[body]; }
  /// The start of free body i's states, −1 when it is not free.
  int bodyOffset(std::size_t i) const { return offset_[i]; }
  /// The start of pair k's states: slots(k) × Model::stateLayout().size() of them.
  int pairOffset(std::size_t k) const { return pair_offset_[k]; }
  int slots(std::size_t k) const { return slots_[k]; }
  /// Pair k's patches' slots at the latest evaluation (several slots only).
  const PatchMatch& match(std::size_t k) const { return matches_[k]; }
  /// Free body i's inverse inertia about its centre of mass, body axes.
  const Eigen::Matrix3d& inverseInertia(std::size_t i) const { return I_inv_B_[i]; }
  PairContacts& contacts() { return *contacts_; }
  const PairContacts& contacts() const { return *contacts_; }
  SleepTracker& sleep() { return sleep_; }
  const SleepTracker& sleep() const { return sleep_; }
  /// Whether the pairs' evaluations keep their contexts (context()): the discrete step's query,
  /// whose evaluation is the next step's start; not the Dormand–Prince stages of a resolved
  /// interval.
  void setKeepContexts(bool on) { keep_contexts_ = on; }
  /// Pair k's latest kept evaluation (keep_contexts only).
  const EvaluationContext& context(std::size_t k) const { return last_context_[k]; }

  // --- Options (Simulator's setters) ---------------------------------------------------------

  void setOutputDepths(bool on) { output_depths_ = on; }
  bool outputDepths() const { return output_depths_; }
  void setStepShortcuts(bool on) { shortcuts_ = on; }
  bool shortcuts() const { return shortcuts_; }
  void setParallelPairs(bool on) { parallel_pairs_ = on; }

 private:
  int layoutStates();
  void setInitialState(int n);
  void bodyRates(std::size_t i, const State& x, State& dxdt) const;
  void applyLoads(double t);
  void checkLoads() const;
  void checkEnergy(const State& x, double t);
  bool kinematicsCurrent(const State& x, double t) const;
  void evaluatePairs(const State& x, State& dxdt);
  void evaluatePair(std::size_t k, const State& x, State& dxdt);
  void evaluatePatches(std::size_t k, const volume::ContactPatches& contact, const State& x,
                       State& dxdt);
  void applyPair(std::size_t k);
  void addWrench(const ContactPair& pair, const Eigen::Vector3d& p_c, const Wrench& w);
  void noteNonFinite(std::size_t k, const volume::ContactVolume& cv, const ContactResult& r);
  void fillDepths(std::size_t k, PairOutput& out);

  Scenario scenario_;
  std::vector<int> offset_;       ///< start of each free body's 13 states, −1 if not free
  std::vector<int> pair_offset_;  ///< start of each pair's states: slots × Model::stateLayout
  std::vector<int> slots_;        ///< state slots of each pair (patchSlots)
  std::vector<PatchTracker> trackers_;    ///< per pair, its patches' slots (several slots only)
  std::vector<PatchMatch> matches_;       ///< per pair, the slots at the latest evaluation
  std::vector<double> size_;              ///< characteristic size of each body, m
  std::vector<Eigen::Matrix3d> I_inv_B_;  ///< inverse inertia about Bcm, B axes, 1/(kg·m²)
  // Scratch space of rhs(), kept to avoid allocations in the integrator's loop.
  std::vector<BodyKinematics> kin_;
  std::vector<Eigen::Vector3d> force_, torque_;
  State x0_;
  State last_x_;                        ///< the state of the latest right-hand-side evaluation
  double rhs_t_ = 0.0;                  ///< s, the time of the latest right-hand side
  std::vector<PairOutput> last_pairs_;  ///< the pairs' contacts of the latest evaluation
  std::vector<LoadOutput> last_loads_;  ///< the loads' and springs' wrenches, same evaluation
  /// The pairs' contacts: broad phase, caches, δ maps, recovered surfaces, the discrete
  /// stepper's latest contacts (pair_contacts.hpp); the only caller of the contact query.
  std::optional<PairContacts> contacts_;
  SleepTracker sleep_;  ///< sleeping islands (trackers/sleep.hpp); updated by the discrete stepper
  std::optional<EnergyGuard> energy_guard_;  ///< set by firstOutput()
  std::vector<BodyKinematics> guard_kin_;    ///< checkEnergy()'s scratch
  /// The first effect whose wrench was not finite at a finite contact, and when ("" if none).
  std::string non_finite_effect_;
  std::vector<EvaluationContext> last_context_;  ///< per pair, keep_contexts only
  bool keep_contexts_ = false;                   ///< setKeepContexts()
  bool output_depths_ = true;                    ///< setOutputDepths()
  bool shortcuts_ = true;                        ///< setStepShortcuts()
  bool parallel_pairs_ = true;                   ///< setParallelPairs()
  bool fixed_ready_ = false;  ///< kin_ holds the fixed bodies' kinematics (rhs())
  long rhs_count_ = 0;
  Snapshot output_;      ///< snapshot()'s result, reused from one output time to the next
  State snapshot_dxdt_;  ///< snapshot()'s scratch for the rates of an interpolated state
};

}  // namespace vcontact::dynamics
