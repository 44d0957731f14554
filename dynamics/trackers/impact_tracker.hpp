#pragma once
// Impacts per pair, from the accepted steps of a run (docs/DISCRETE.md §6): an impact opens at
// the first accepted state at which the pair is in contact and closes at the first state at
// which it is apart again ("separated"), or once its normal relative speed has stayed below
// `settle_speed` for `settle_time` ("settled": the pair now rests on each other), or at the
// end of the run ("open"). The speeds are those of the free flight on either side, along the
// contact's normal at the contact's centroid: the approach speed from the latest state before
// the contact, carried to the first state in contact under gravity alone (exact in free
// flight); the separation speed likewise from the first state apart back to the last one in
// contact. The onset and the separation are placed between their two states by the time the
// mean depth V/A takes to cross at those speeds. The normal impulse is the trapezoid rule of f_n
// over the accepted states, or, for a step of the discrete integrator, the impulse the step applied
// (h times its implicit normal force, which the query at the step's end does not show).
//
// In a discrete run the tracker also records how the stepper took each impact (docs/DISCRETE.md
// §5): the fixed steps of it integrated by Dormand–Prince, the fast steps left to the plain step
// because the predicted rebound fell below the restitution threshold, and that prediction.

#include <string>
#include <vector>

#include "dynamics/scenario.hpp"

namespace vcontact::dynamics {

struct PairOutput;

/// One impact of one pair (SimulationSummary::impacts, summary.json "impacts").
struct ImpactRecord {
  std::string pair;
  double start = 0.0;             ///< s, the first accepted state in contact
  double duration = 0.0;          ///< s, to the first state apart (or the end of the impact)
  double impulse = 0.0;           ///< N s, ∫ f_n dt over the impact
  double approach_speed = 0.0;    ///< m/s, δ̇_c just before the contact (> 0 approaching)
  double separation_speed = 0.0;  ///< m/s, −δ̇_c just after it (0 when settled or open)
  double restitution = 0.0;       ///< separation over approach speed
  std::string outcome;            ///< "separated", "settled" or "open"
  /// Discrete runs only (empty otherwise): "resolved" (its fast steps integrated by
  /// Dormand–Prince), "plain" (left to the plain step: the predicted rebound is below the
  /// restitution threshold), "partly" (some of each) or "slow" (no step fast enough to need it).
  std::string resolution;
  long resolved_steps = 0;  ///< fixed steps of the impact integrated by Dormand–Prince
  long plain_steps = 0;     ///< fast fixed steps of it left to the plain step
  /// m/s, the rebound e v_in predicted at its first fast step, which decided how the stepper
  /// takes it (0: no fast step; a resolution then came from the linearisation check)
  double predicted_rebound = 0.0;
};

class ImpactTracker {
 public:
  /// Settings of a run: `settle_speed` (m/s) and `settle_time` (s) as in the header;
  /// `discrete`: the run records ImpactRecord::resolution.
  void reset(const Scenario& scenario, double settle_speed, double settle_time,
             bool discrete = false);
  /// Discrete runs: a fixed step begins; `resolved`: its interval is integrated by
  /// Dormand–Prince (every impact the step's states show counts it once).
  void beginStep(bool resolved);
  /// Discrete runs: a region of pair k was fast in the step begun last, with a predicted rebound
  /// of `rebound` (m/s), and the plain step takes it.
  void markPlain(std::size_t k, double rebound);
  /// Discrete runs: a region of pair k was fast in the step begun last, predicted to rebound at
  /// `rebound` (m/s), and the step is resolved for it.
  void markResolved(std::size_t k, double rebound);
  /// Whether pair k has an open impact of which a fast step has been left to the plain step.
  bool openAndPlain(std::size_t k) const {
    const Open& o = open_[k];
    return o.active && o.plain_steps > 0;
  }
  /// Whether pair k has an open impact of which a step has been resolved and none left to the
  /// plain step (an impact the plain step took first stays the plain step's when a later step of
  /// it is resolved for a missed linearisation).
  bool openAndResolved(std::size_t k) const {
    return open_[k].active && open_[k].resolved_steps > 0 && open_[k].plain_steps == 0;
  }
  /// The approach speed of pair k's open impact (m/s), 0 without one.
  double openApproach(std::size_t k) const { return open_[k].active ? open_[k].approach : 0.0; }
  /// One accepted state: its time, the bodies' kinematics and the pairs' contacts; with
  /// `step_impulse`, each pair's normal impulse over the step that led to it (N s).
  void observe(double t, const std::vector<BodyKinematics>& kin,
               const std::vector<PairOutput>& pairs,
               const std::vector<double>* step_impulse = nullptr);
  /// Closes the impacts still open at the end of the run (t).
  void finish(double t);
  const std::vector<ImpactRecord>& impacts() const { return impacts_; }

 private:
  struct Open {
    bool active = false;
    bool resting = false;  ///< settled: in contact, no impact open until the pair parts
    double start = 0.0, impulse = 0.0, approach = 0.0;
    double last_t = 0.0, last_fn = 0.0, last_depth = 0.0;  ///< the latest state in contact
    double slow_since = -1.0, impulse_at_slow = 0.0;
    long resolved_steps = 0, plain_steps = 0, counted_step = -1;
    double predicted_rebound = 0.0;
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ(), p = Eigen::Vector3d::Zero();
  };
  double normalSpeed(std::size_t k, const std::vector<BodyKinematics>& kin,
                     const Eigen::Vector3d& p, const Eigen::Vector3d& n) const;
  double gravityAlong(std::size_t k, const Eigen::Vector3d& n) const;
  void close(std::size_t k, double end, double impulse, double separation, const char* outcome);
  void countStep(std::size_t k);

  // What the discrete step under way did with each pair (beginStep, markPlain, markResolved)
  struct StepMark {
    bool plain = false;
    double rebound = 0.0;
  };

  const Scenario* scenario_ = nullptr;
  double settle_speed_ = 0.0, settle_time_ = 0.0;
  double last_t_ = 0.0;
  bool discrete_ = false;
  long step_ = -1;         ///< the discrete step under way (beginStep)
  bool resolved_ = false;  ///< whether it is resolved
  std::vector<StepMark> marks_;
  std::vector<BodyKinematics> last_kin_;  ///< the previous accepted state
  std::vector<Open> open_;
  std::vector<ImpactRecord> impacts_;
};

}  // namespace vcontact::dynamics
