#pragma once
// What a run of the Simulator hands out, for the writers and readers above it (report/,
// validation/, python/, the CLI) without the Simulator itself: a Snapshot per output time
// (the bodies, every pair's contact, patches and wrench, the loads), the SimulationSummary of
// the run, the SimulationError it stops with, and the state slots of a pair (patchSlots), which
// say how many patch columns its files have.

#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/loads.hpp"
#include "dynamics/model.hpp"
#include "dynamics/pair_state.hpp"
#include "dynamics/recovered_pairs.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/scenario.hpp"
#include "dynamics/trackers/impact_tracker.hpp"
#include "dynamics/trackers/sleep.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::dynamics {

/// Why a run stopped, for a program reading its summary (the message says it in words).
enum class StopCause {
  kNonFinite,          ///< a state or its rate is NaN or infinite
  kStepCollapse,       ///< the step size fell below SimulationSettings::min_step
  kPenetration,        ///< a pair's mean penetration exceeds max_penetration_fraction
  kIntegratorFailure,  ///< another failure of the integrator (CVODE), in its words
  kBlowUp,      ///< the free bodies gained energy no input gave them (trackers/energy_guard.hpp)
  kInterrupted  ///< the user asked the run to stop (SIGINT, SIGTERM: io/interrupt.hpp)
};

/// "non_finite_state", "step_size_collapse", "penetration_beyond_bound", "integrator_failure",
/// "blow_up", "interrupted".
const char* stopCauseName(StopCause cause);

/// "t = 0.0123 s" (9 digits): how a SimulationError's message says when the run stopped.
std::string stopTime(double t);

class SimulationError : public std::runtime_error {
 public:
  SimulationError(double t, StopCause cause, const std::string& message)
      : std::runtime_error(message), time_(t), cause_(cause) {}
  double time() const { return time_; }  ///< s, where the run stopped
  StopCause cause() const { return cause_; }

 private:
  double time_;
  StopCause cause_;
};

/// One contact patch of a pair at one instant (pairs with several state slots).
struct PatchOutput {
  volume::ContactVolume cv;
  ContactResult result;  ///< wrench on body A at the patch's centroid
  PairState state;       ///< the states it read (its slot's, or its host slot's)
  int slot = -1;         ///< its own state slot, −1 when it has none (PatchMatch)
};

/// Per pair at one instant.
struct PairOutput {
  volume::ContactVolume cv;  ///< the single-region contact (ContactPatches::aggregate)
  /// The pair's total wrench on body A at cv.p_WC (the patches' wrenches moved there), the
  /// sum of the patches' f_n and the s and μ_max of the largest patch; the rates of slot 0.
  ContactResult result;
  PairState state;                   ///< the states of slot 0
  std::vector<PatchOutput> patches;  ///< pairs with several slots only, in the query's order
  int patch_count = 0;               ///< patches of the query (0 when apart)
  int without_slot = 0;              ///< of those, the ones with no slot of their own
};

struct Snapshot {
  double t = 0.0;                      ///< s
  std::vector<BodyKinematics> bodies;  ///< one per Scenario::bodies
  std::vector<PairOutput> pairs;       ///< one per Scenario::pairs
  std::vector<LoadOutput> loads;       ///< one per Scenario::loads, then one per spring
};

struct SimulationSummary {
  double simulated_time = 0.0;  ///< s
  double wall_time = 0.0;       ///< s
  long steps = 0;               ///< accepted steps
  long rejected_steps = 0;
  long rhs_evaluations = 0;
  long contact_evaluations = 0;   ///< volume queries (the pairs the broad phase let through, at
                                  ///< every right-hand-side evaluation)
  long jacobian_evaluations = 0;  ///< BDF: difference-quotient Jacobians (their right-hand
                                  ///< sides are in rhs_evaluations); 0 for Dormand–Prince
  int patches_max = 0;            ///< most patches of one pair at an output time
  double patches_mean = 0.0;      ///< mean patch count over the output times of pairs in contact
  long patches_without_slot = 0;  ///< patches without a slot of their own, summed over outputs
  /// The bodies with a recovered surface and the pairs with one of them (RecoveredPairs);
  /// empty when no body has "surface": "recovered".
  std::vector<SurfaceBodyUse> surface_bodies;
  std::vector<SurfacePairUse> surface_pairs;
  /// The impacts of the pairs (dynamics/trackers/impact_tracker.hpp); dopri5 and discrete runs.
  std::vector<ImpactRecord> impacts;
  /// Discrete runs: the steps whose interval was integrated by Dormand–Prince to resolve an
  /// impact or a missed linearisation, and the accepted Dormand–Prince steps they took
  /// (docs/DISCRETE.md §5); of those steps, the ones for a missed linearisation alone, and the
  /// contact queries all of them made.
  long resolved_steps = 0;
  long resolution_substeps = 0;
  long resolved_for_linearisation = 0;
  long resolution_queries = 0;
  /// Discrete runs: the Newton iterations of plain steps whose linearisation missed (one query
  /// each), taken before such a step is resolved.
  long newton_iterations = 0;
  /// Discrete runs with sleep (dynamics/trackers/sleep.hpp): the bodies falling asleep and waking,
  /// in order, and the contact queries not made because a pair's bodies slept.
  std::vector<SleepEvent> sleep_events;
  long sleep_skipped_queries = 0;
  double realTimeFactor() const { return wall_time > 0.0 ? simulated_time / wall_time : 0.0; }
};

/// The state slots of pair p of scenario s (docs/SCENARIO.md, "Contact patches"): one for
/// a pair that touches in one region only (distributed friction, the analytic method, two
/// convex shapes), p.max_patches otherwise.
/// @throws InputError when that count is outside [kMinMaxPatches, kMaxMaxPatches]
int patchSlots(const Scenario& s, const ContactPair& p);

}  // namespace vcontact::dynamics
