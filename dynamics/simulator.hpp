#pragma once
// Time integration of a Scenario: Newton–Euler equations of the free bodies under gravity
// and the contact wrenches of every pair, plus the pair states, error-controlled with the
// scenario's tolerances, by one of three integrators (SimulationSettings::integrator):
//
// - Dormand–Prince 5(4), Boost.Odeint (runge_kutta_dopri5, FSAL). After each accepted step the
//   quaternions are renormalised and every pair state is settled (Model::settle: z projected
//   onto the contact plane, reset on loss of contact, dwell jumps). Steps are shortened to
//   land on output times, so outputs are exact states, not interpolations.
// - Variable-order BDF, SUNDIALS CVODE (bdf_integrator.hpp), for stiff friction states. Steps
//   are free and outputs come from each step's interpolating polynomial. The settle updates
//   restart the integrator when they move a state by more than its tolerance; smaller ones are
//   within the integration error and are applied by every reader of the state anyway.
// - The discrete stepper (docs/DISCRETE.md; simulator_discrete*.cpp): a linearly
//   implicit step of fixed size about each pair's contact Jacobians (discrete_jacobian.hpp),
//   with impacts resolved by Dormand–Prince intervals or by the implicit step itself, and
//   bodies at rest put to sleep (sleep.hpp).
//
// What a run hands out (Snapshot, SimulationSummary, SimulationError) is in
// simulation_output.hpp, for the writers that need not see the Simulator.
//
// Every right-hand side takes the pairs' contacts from PairContacts (pair_contacts.hpp): the
// broad phase screens them (a pair whose boxes do not overlap gets the empty contact without a
// query), the rest are queried, pairs of sleeping bodies keep their latest contact.
//
// Any run stops with a SimulationError naming time, pair or body and the quantity on: a
// non-finite state or rate, a mean penetration V/A beyond a set fraction of a body, a step
// size below the minimum (or another failure of CVODE, in words), or kinetic energy far beyond
// what the scenario can supply (a blow-up, dynamics/energy_guard.hpp).

#include <Eigen/LU>
#include <atomic>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/discrete_jacobian.hpp"
#include "dynamics/energy_guard.hpp"
#include "dynamics/impact_tracker.hpp"
#include "dynamics/pair_contacts.hpp"
#include "dynamics/patch_tracker.hpp"
#include "dynamics/scenario.hpp"
#include "dynamics/simulation_output.hpp"
#include "dynamics/sleep.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {

class BdfError;
class Dopri5Control;

/// One contact patch of one step of the discrete stepper (simulator_discrete.cpp).
struct DiscretePatch {
  std::size_t pair = 0;
  int slot = -1;  ///< its own state slot, −1 when none
  Eigen::Vector3d p_c = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  PatchStep step;
};

/// A one-slot pair's latest model evaluation in contact (Simulator::evaluatePair, discrete
/// runs): its context and the motion it was made at. The discrete step linearises about it
/// instead of evaluating the model again at the same contact, motion and state.
struct EvaluationContext {
  ContactContext ctx;  ///< ctx.cv points into Simulator's last_pairs_
  RelativeMotion motion;
  bool valid = false;  ///< the pair was in contact at that evaluation
};

class Simulator {
 public:
  /// @throws InputError when a free body has no positive mass or inertia, or a pair names a
  ///         body out of range
  explicit Simulator(Scenario scenario);

  const Scenario& scenario() const { return scenario_; }

  /// Runs to settings.duration, calling on_output at every output time (t = 0 included) and
  /// on_progress after each accepted step. The summary is filled even when the run stops.
  /// After each accepted step the run also looks whether it was asked to stop
  /// (io::interruptSignal, set by a signal handler or a front end) and stops then with
  /// StopCause::kInterrupted.
  /// @throws SimulationError on a failure or an interruption; output up to then has been
  ///   delivered
  void run(const std::function<void(const Snapshot&)>& on_output,
           const std::function<void(double t)>& on_progress, SimulationSummary& summary);

  /// Whether the output snapshots carry the exact depth of the pairs whose force evaluations
  /// leave it out (`fast`; ContactVolume::depth NaN otherwise): a second query of each such pair
  /// at every output time, several times the cost of a step's query. On by default; a caller
  /// that writes no depth (no pair files) turns it off. The snapshot at t = 0 has it always.
  void setOutputDepths(bool on) { output_depths_ = on; }

  /// The per-step shortcuts (docs/DISCRETE.md §4.4; on by default), which change no number of
  /// a run: the discrete step linearises about the evaluation of the query that ended the
  /// previous step instead of evaluating the model again, solves free flight body by body
  /// without the whole system's LU, and the readers of an accepted state (the checks, the
  /// settle, the output) take the right-hand side's kinematics instead of converting the
  /// quaternions again. Off: the general path everywhere, for the tests that compare the two
  /// to the bit and the benchmarks' before and after in one run.
  void setStepShortcuts(bool on) { shortcuts_ = on; }

  /// Whether a right-hand side's pairs (their contact queries and models) are evaluated side
  /// by side by TBB, in the arena the run is called from (all cores by default; a
  /// tbb::task_arena or tbb::global_control around run() sets the count). On by default.
  /// The results are identical to the bit either way and whatever the thread count: each
  /// pair's evaluation reads only the bodies' kinematics and writes only its own output, and
  /// the wrenches are summed onto the bodies afterwards, pair by pair in order.
  void setParallelPairs(bool on) { parallel_pairs_ = on; }

  using State = std::vector<double>;

 private:
  // Output times k / rate are reached by shortened steps; a step that ends within this
  // fraction of the output interval of it counts as landing on it (round-off of t + dt).
  static constexpr double kOutputTimeSlack = 1e-9;

  using OutputFn = std::function<void(const Snapshot&)>;
  using ProgressFn = std::function<void(double t)>;
  void runDopri5(State& x, State& dxdt, double& t, const OutputFn& on_output,
                 const ProgressFn& on_progress, SimulationSummary& summary);
  void runBdf(State& x, double& t, const OutputFn& on_output, const ProgressFn& on_progress,
              SimulationSummary& summary);
  void runDiscrete(State& x, State& dxdt, double& t, const OutputFn& on_output,
                   const ProgressFn& on_progress, SimulationSummary& summary);
  void discreteStep(State& x, double t, double h);
  void assemblePatch(std::size_t k, const volume::ContactVolume& cv, int host, int slot,
                     const State& x, double h);
  bool evaluatedAt(std::size_t k, const volume::ContactVolume& cv, const RelativeMotion& motion,
                   const PairState& state) const;
  void solveFlight();
  void updateDiscreteStates(State& x, double h);
  void discreteInterval(State& x, State& dxdt, double& t, double h, double t1, bool lands,
                        SimulationSummary& summary);
  double impactThreshold(double h) const;
  double impactDuration(std::size_t k, const volume::ContactVolume& cv, double f_n) const;
  // A contact region in an impact to resolve over a step (impactAhead): its pair, its
  // predicted rebound speed e v_in, and whether the step is to be resolved for it.
  struct FastRegion {
    std::size_t pair = 0;
    double rebound = 0.0;
    bool resolve = false;
  };
  double predictedRebound(std::size_t k, double approach) const;
  bool impactAhead(const std::vector<BodyKinematics>& speed_kin, bool approaching_only, double h,
                   std::vector<FastRegion>& fast) const;
  void markImpacts(bool resolved);
  bool linearisationMissed(double h) const;
  void resolveInterval(State& x, State& dxdt, double& t, double t1, SimulationSummary& summary);
  // A Dormand–Prince attempt of dt from (x, t) for runDopri5 and resolveInterval: a rejection is
  // counted, leaves the smaller step in dt and throws when it falls below min_step.
  bool tryDopri5(Dopri5Control& control, State& x, State& dxdt, double& t, double& dt,
                 SimulationSummary& summary);
  // After an accepted Dormand–Prince step: the contacts at x, the checks, the pair states'
  // discrete updates and the impact tracker.
  void afterDopri5Step(State& x, State& dxdt, double t);
  void stepImpulses(double h);
  void sleepBeforeStep(State& x, double t);
  void contactBalance(std::vector<char>& balanced) const;
  void assembleLoads(double t, double h);
  void loadTerms(std::size_t j, const std::vector<BodyKinematics>& kin, double t,
                 Vector6d out[2]) const;
  int layoutStates();
  void setInitialState(int n);
  void rhs(const State& x, State& dxdt, double t);
  void fillDepths(std::size_t k, PairOutput& out);
  void evaluatePairs(const State& x, State& dxdt);
  void evaluatePair(std::size_t k, const State& x, State& dxdt);
  void applyPair(std::size_t k);
  void evaluatePatches(std::size_t k, const volume::ContactPatches& contact, const State& x,
                       State& dxdt);
  void addWrench(const ContactPair& pair, const Eigen::Vector3d& p_c, const Wrench& w);
  void noteNonFinite(std::size_t k, const volume::ContactVolume& cv, const ContactResult& r);
  void countPatches(const Snapshot& s, SimulationSummary& summary, long& samples,
                    long& total) const;
  void checkLoads() const;
  void applyLoads(double t);
  void bodyRates(std::size_t i, const State& x, State& dxdt) const;
  bool rhsFinite(const double* x, double* dxdt, double t);
  const Snapshot& snapshot(const State& x, double t, bool depths);
  BodyKinematics kinematics(const State& x, std::size_t body, double t) const;
  bool kinematicsCurrent(const State& x, double t) const;
  bool settle(State& x, double t);
  bool settlePairs(State& x, double t);
  double normaliseQuaternions(State& x) const;
  void check(const State& x, double t);
  void checkEnergy(const State& x, double t);
  std::string stiffestPair() const;
  std::string stateOwner(std::size_t index) const;
  SimulationError stepCollapse(double t, double h, const std::string& detail) const;
  SimulationError bdfFailure(const BdfError& e, double t_last) const;

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
  State last_x_;  ///< the state of the latest right-hand-side evaluation
  // The per-pair contacts of the latest right-hand-side evaluation (at last_x_).
  std::vector<PairOutput> last_pairs_;
  std::optional<EnergyGuard> energy_guard_;  ///< set by run() from the state at t = 0
  std::vector<BodyKinematics> guard_kin_;    ///< checkEnergy()'s scratch
  std::vector<LoadOutput> last_loads_;       ///< the loads' and springs' wrenches, same evaluation
  /// The pairs' contacts: broad phase, caches, δ maps, recovered surfaces, the discrete
  /// stepper's latest contacts (pair_contacts.hpp); the only caller of the contact query.
  std::optional<PairContacts> contacts_;
  State rhs_x_, rhs_dxdt_;  ///< rhsFinite()'s copies of CVODE's vectors
  std::string non_finite_;  ///< the state whose rate was last found not finite
  /// The first effect whose wrench was not finite at a finite contact, and when ("" if none).
  std::string non_finite_effect_;
  double rhs_t_ = 0.0;  ///< s, the time of the right-hand side being evaluated
  // The discrete stepper (simulator_discrete.cpp): the evaluations' contexts per pair, and the
  // step's system, kept between steps to avoid allocations.
  std::vector<EvaluationContext> last_context_;  ///< per pair, discrete runs only
  /// The force evaluations keep their contexts (last_context_): the discrete step's query, whose
  /// evaluation is the next step's start; not the Dormand–Prince stages of a resolved interval.
  bool keep_contexts_ = false;
  bool output_depths_ = true;  ///< setOutputDepths()
  bool shortcuts_ = true;      ///< setStepShortcuts()
  bool fixed_ready_ = false;   ///< kin_ holds the fixed bodies' kinematics (rhs())
  std::vector<int> column_;  ///< per body, its first column in the step's system, −1 if not free
  /// Per body, whether the step has no contact patch, load or spring on it (free flight).
  std::vector<char> in_flight_;
  std::vector<DiscretePatch> step_patches_;
  std::size_t step_patch_count_ = 0;
  Eigen::MatrixXd step_matrix_;
  Eigen::PartialPivLU<Eigen::MatrixXd> step_lu_;
  Eigen::VectorXd step_rhs_, step_twist_;
  // solveFlight()'s 3 × 3 system of one body's rotation, kept to avoid allocations
  Eigen::MatrixXd flight_matrix_;
  Eigen::PartialPivLU<Eigen::MatrixXd> flight_lu_;
  Eigen::VectorXd flight_rhs_, flight_twist_;
  std::vector<BodyKinematics> next_kin_;  ///< the bodies at the step's end (prescribed ones)
  std::vector<BodyKinematics> load_kin_;  ///< assembleLoads()' perturbed kinematics
  // Impacts (simulator_discrete_impacts.cpp): the step's start, kept to take it again by
  // Dormand–Prince when it brought a pair into an impact; the normal impulse of each pair over
  // the latest discrete step; the latest accepted step of the resolutions.
  State start_x_, start_dxdt_;
  std::vector<BodyKinematics> start_kin_;
  std::vector<double> step_impulse_;
  std::vector<FastRegion> fast_regions_;  ///< the fast regions of the step under way
  double resolve_dt_ = 0.0;
  ImpactTracker impacts_;
  // Sleeping islands (simulator_sleep.cpp): the tracker, its per-pair inputs, and the queries
  // a frozen pair's kept contact replaced.
  SleepTracker sleep_;
  std::vector<char> sleep_contact_, sleep_near_, sleep_balanced_;
  long rhs_count_ = 0;
  bool parallel_pairs_ = true;  ///< setParallelPairs()
  Snapshot output_;             ///< snapshot()'s result, reused from one output time to the next
  State snapshot_dxdt_;         ///< snapshot()'s scratch for the rates of an interpolated state
};

}  // namespace vcontact::dynamics
