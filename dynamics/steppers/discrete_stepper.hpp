#pragma once
// The discrete stepper (`"integrator": "discrete"`, docs/DISCRETE.md): a fixed step h, one
// contact query per step, the contact wrenches linearised about the step's start
// (discrete_jacobian.hpp) and solved implicitly for the free bodies' new twists, the loads and
// springs linearised by differences (discrete_loads.cpp). Impacts are resolved by
// Dormand–Prince intervals (Dopri5Steps) or by the implicit step itself
// (discrete_impacts.cpp), and bodies at rest put to sleep (discrete_sleep.cpp,
// trackers/sleep.hpp). A step whose linearisation missed the force queried at its end is taken
// again about its end, by Newton iterations (newtonStep), before Dormand–Prince is asked.
//
// Each step is assembled from the equations' latest evaluation (the query that ended the
// previous step) and ends with one more (MotionEquations::rhs at the new state; one more per
// Newton iteration); the stepper writes nothing of the equations' own but the sleeping bodies'
// velocities.

#include <Eigen/LU>
#include <vector>

#include "dynamics/steppers/discrete_jacobian.hpp"
#include "dynamics/steppers/dopri5_stepper.hpp"
#include "dynamics/steppers/stepper.hpp"
#include "dynamics/trackers/impact_tracker.hpp"

namespace vcontact::dynamics {

/// m/s, the normal speed beyond which a contact region is in an impact for a step h
/// (2 |g| h, at least 1 mm/s): the discrete stepper resolves such steps, and every run's
/// impact tracker counts an impact settled below it (simulator.cpp).
double impactThreshold(const Scenario& scenario, double h);

/// One contact patch of one step of the discrete stepper.
struct DiscretePatch {
  std::size_t pair = 0;
  int slot = -1;  ///< its own state slot, −1 when none
  Eigen::Vector3d p_c = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  PatchStep step;
};

class DiscreteStepper final : public Stepper {
 public:
  /// @throws InputError when the scenario's step is outside [kMinDiscreteStep,
  ///         kMaxDiscreteStep]
  DiscreteStepper(MotionEquations& equations, ImpactTracker& impacts);

  /// @throws InputError (before any step) for a pair with distributed friction, which the
  ///         step cannot linearise
  void run(State& x, State& dxdt, double& t, const OutputFn& on_output,
           const ProgressFn& on_progress, SimulationSummary& summary) override;

 private:
  // A contact region in an impact to resolve over a step (impactAhead): its pair, its
  // predicted rebound speed e v_in, and whether the step is to be resolved for it.
  struct FastRegion {
    std::size_t pair = 0;
    double rebound = 0.0;
    bool resolve = false;
  };

  // the plain step and its Newton iterations (discrete_stepper.cpp)
  void plainStep(State& x, double t, double h);
  void newtonStep(State& x, double h);
  void assembleContacts(const State& x, double h, bool about_end);
  void solveAndMove(State& x, const std::vector<BodyKinematics>& start, double h);
  void assemblePatch(std::size_t k, const volume::ContactVolume& cv, int host, int slot,
                     const State& x, double h, bool about_end);
  bool evaluatedAt(std::size_t k, const volume::ContactVolume& cv, const RelativeMotion& motion,
                   const PairState& state) const;
  void solveFlight();
  void updateStates(State& x, double h);
  // loads and springs (discrete_loads.cpp)
  void assembleLoads(double t, double h);
  void loadTerms(std::size_t j, const std::vector<BodyKinematics>& kin, double t,
                 Vector6d out[2]) const;
  // impacts (discrete_impacts.cpp)
  void advance(State& x, State& dxdt, double& t, double h, double t1, bool lands,
               SimulationSummary& summary);
  double impactDuration(std::size_t k, const volume::ContactVolume& cv, double f_n) const;
  double predictedRebound(std::size_t k, double approach) const;
  bool impactAhead(const std::vector<BodyKinematics>& speed_kin, bool approaching_only, double h,
                   std::vector<FastRegion>& fast) const;
  void markImpacts(bool resolved);
  double linearisationMiss(double h) const;
  void relaxNewtonIterate(State& x);
  void resolveInterval(State& x, State& dxdt, double& t, double t1, SimulationSummary& summary);
  void stepImpulses(double h);
  // sleep (discrete_sleep.cpp)
  void sleepBeforeStep(State& x, double t);
  void contactBalance(std::vector<char>& balanced) const;

  MotionEquations& eq_;
  const Scenario& scenario_;
  ImpactTracker& impacts_;
  Dopri5Steps dopri5_;                         ///< the resolved intervals' steps
  std::vector<BodyKinematics>& kin_;           ///< eq_.bodies(): the latest evaluation's bodies
  const std::vector<PairOutput>& last_pairs_;  ///< eq_.pairs(): its pairs' contacts
  // The step's system, kept between steps to avoid allocations.
  std::vector<int> column_;  ///< per body, its first column in the step's system, −1 if not free
  /// Per body, whether the step has no contact patch, load or spring on it (free flight).
  std::vector<char> in_flight_;
  std::vector<DiscretePatch> step_patches_;
  std::size_t step_patch_count_ = 0;
  Eigen::MatrixXd step_matrix_;
  Eigen::PartialPivLU<Eigen::MatrixXd> step_lu_;
  Eigen::VectorXd step_rhs_, step_twist_;
  // The system before its contact patches (inertia, gravity, loads and springs at the step's
  // start), kept for the Newton iterations of the step.
  Eigen::MatrixXd base_matrix_;
  Eigen::VectorXd base_rhs_;
  std::vector<char> base_in_flight_;
  // solveFlight()'s 3 × 3 system of one body's rotation, kept to avoid allocations
  Eigen::MatrixXd flight_matrix_;
  Eigen::PartialPivLU<Eigen::MatrixXd> flight_lu_;
  Eigen::VectorXd flight_rhs_, flight_twist_;
  std::vector<BodyKinematics> next_kin_;  ///< the bodies at the step's end (prescribed ones)
  std::vector<BodyKinematics> load_kin_;  ///< assembleLoads()' perturbed kinematics
  // Impacts: the step's start, kept to take it again by Dormand–Prince when it brought a pair
  // into an impact; the normal impulse of each pair over the latest step; the fast regions of
  // the step under way; the latest accepted step of the resolutions.
  State start_x_, start_dxdt_;
  State previous_x_;  ///< the Newton iteration's previous iterate (relaxNewtonIterate)
  State best_x_;      ///< and its best iterate so far, with that iterate's step impulses
  std::vector<double> best_impulse_;
  std::vector<BodyKinematics> start_kin_;
  std::vector<double> step_impulse_;
  std::vector<FastRegion> fast_regions_;
  double resolve_dt_ = 0.0;
  // The sleep tracker's per-pair inputs (sleepBeforeStep).
  std::vector<char> sleep_contact_, sleep_near_, sleep_balanced_;
};

}  // namespace vcontact::dynamics
