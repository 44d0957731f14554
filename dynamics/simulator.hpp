#pragma once
// Time integration of a Scenario: the run loop over three parts,
//
// - the equations of motion (motion_equations.hpp): the state's layout, its right-hand side
//   (the bodies under gravity, loads, springs and the contact wrenches of every pair, the
//   pairs' contacts from PairContacts, pair_contacts.hpp), the settle after an accepted step,
//   the checks that stop a run and the output snapshot;
// - one stepper (steppers/stepper.hpp), the integrator the scenario names
//   (SimulationSettings::integrator): Dormand–Prince (steppers/dopri5_stepper.hpp), BDF
//   (steppers/bdf_stepper.hpp) or the discrete stepper (steppers/discrete_stepper.hpp);
// - the trackers every run reports from (trackers/): impacts (impact_tracker.hpp), the
//   patches' counts; the blow-up guard and the sleeping islands are the equations' own
//   (energy_guard.hpp, sleep.hpp), the patches' slots each pair's (patch_tracker.hpp).
//
// The run loop settles the initial state, writes the first output, hands the state to the
// stepper, looks after each accepted step whether it was asked to stop, and fills the summary
// whether or not the run finished. What a run hands out (Snapshot, SimulationSummary,
// SimulationError) is in simulation_output.hpp, for the writers that need not see the
// Simulator.
//
// Any run stops with a SimulationError naming time, pair or body and the quantity on: a
// non-finite state or rate, a mean penetration V/A beyond a set fraction of a body, a step
// size below the minimum (or another failure of CVODE, in words), or kinetic energy far beyond
// what the scenario can supply (a blow-up, dynamics/trackers/energy_guard.hpp).

#include <functional>
#include <memory>
#include <vector>

#include "dynamics/motion_equations.hpp"
#include "dynamics/scenario.hpp"
#include "dynamics/simulation_output.hpp"
#include "dynamics/trackers/impact_tracker.hpp"

namespace vcontact::dynamics {

class Stepper;

class Simulator {
 public:
  /// @throws InputError when a free body has no positive mass or inertia, a pair names a body
  ///         out of range or no method handles it, a load or spring names no body, or the
  ///         integrator refuses the settings (a discrete step out of range)
  explicit Simulator(Scenario scenario);

  const Scenario& scenario() const { return equations_.scenario(); }

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
  void setOutputDepths(bool on) { equations_.setOutputDepths(on); }

  /// The per-step shortcuts (docs/DISCRETE.md §4.4; on by default), which change no number of
  /// a run: the discrete step linearises about the evaluation of the query that ended the
  /// previous step instead of evaluating the model again, solves free flight body by body
  /// without the whole system's LU, and the readers of an accepted state (the checks, the
  /// settle, the output) take the right-hand side's kinematics instead of converting the
  /// quaternions again. Off: the general path everywhere, for the tests that compare the two
  /// to the bit and the benchmarks' before and after in one run.
  void setStepShortcuts(bool on) { equations_.setStepShortcuts(on); }

  /// Whether a right-hand side's pairs (their contact queries and models) are evaluated side
  /// by side by TBB, in the arena the run is called from (all cores by default; a
  /// tbb::task_arena or tbb::global_control around run() sets the count). On by default.
  /// The results are identical to the bit either way and whatever the thread count: each
  /// pair's evaluation reads only the bodies' kinematics and writes only its own output, and
  /// the wrenches are summed onto the bodies afterwards, pair by pair in order.
  void setParallelPairs(bool on) { equations_.setParallelPairs(on); }

  using State = std::vector<double>;

  ~Simulator();

 private:
  MotionEquations equations_;
  ImpactTracker impacts_;
  std::unique_ptr<Stepper> stepper_;
};

}  // namespace vcontact::dynamics
