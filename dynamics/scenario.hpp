#pragma once
// A simulation scenario in memory: bodies, contact pairs with their models, gravity and
// integration settings. File formats live in formats/scenario_file (docs/SCENARIO.md).

#include <optional>
#include <string>
#include <vector>

#include "dynamics/loads.hpp"
#include "dynamics/model.hpp"
#include "dynamics/rigid_body.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::dynamics {

/// How a pair's friction force and spin torque are formed (docs/SCENARIO.md).
enum class FrictionMode {
  kLumped,       ///< MODEL.md §3: at the centroid, shared by the Contensou factors
  kDistributed,  ///< pointwise Coulomb friction over the columns δ map (DISTRIBUTED_FRICTION.md)
};

/// The fixed column grid of a distributed-friction pair, lines per side
/// (docs/DISTRIBUTED_FRICTION.md, "The grid"): 64 puts ~3,200 columns on a round face, whose V and
/// spin torque are then within 3.5e-3 of the exact ones, at ~0.4 ms per evaluation (~100× the exact
/// clip).
constexpr int kDefaultColumnResolution = 64;
/// Bounds of that resolution: below 8 lines a face is a few dozen columns (errors of ~10 %);
/// 512 is the adaptive method's own ceiling (~30 ms per evaluation of a face).
constexpr int kMinColumnResolution = 8;
constexpr int kMaxColumnResolution = 512;

/// State slots of a pair whose bodies can touch in several regions (docs/SCENARIO.md,
/// "Contact patches"): one per patch followed (trackers/patch_tracker.hpp), up to this many.
constexpr int kDefaultMaxPatches = 4;
/// Bounds of that count: each slot carries the model's states in the integrator.
constexpr int kMinMaxPatches = 1;
constexpr int kMaxMaxPatches = 16;

struct ContactPair {
  std::string name;   ///< for output ("ball-plate")
  std::size_t a = 0;  ///< index of body A (the payload) in Scenario::bodies
  std::size_t b = 0;  ///< index of body B (the plate)
  Model model;
  std::optional<volume::Method> method;  ///< default: volume::defaultMethod
  /// kDistributed needs method columns and a model that passes
  /// Model::checkDistributedFriction (the scenario reader checks both).
  FrictionMode friction = FrictionMode::kLumped;
  /// kDistributed only: lines per side of the column grid, fixed (no refinement) so that one
  /// evaluation costs the same at every right-hand side; in [kMinColumnResolution,
  /// kMaxColumnResolution].
  int column_resolution = kDefaultColumnResolution;
  /// State slots for the pair's contact patches, in [kMinMaxPatches, kMaxMaxPatches]. A pair
  /// that can touch in one region only (an analytic primitive, two convex shapes, distributed
  /// friction) uses one slot and the single-region contact whatever this says; with one slot
  /// the patches are lumped into that region (the aggregate).
  int max_patches = kDefaultMaxPatches;
};

/// The time integrator (docs/SCENARIO.md "Integrators").
enum class Integrator {
  kDopri5,    ///< explicit Dormand–Prince 5(4), Boost.Odeint: cheap steps, step ≲ 3.3/|λ_max|
  kBdf,       ///< implicit variable-order BDF, SUNDIALS CVODE: steps set by accuracy alone
  kDiscrete,  ///< linearly implicit fixed step, one contact query per step (docs/DISCRETE.md)
};

/// Bounds of the discrete stepper's step SimulationSettings::step, s: below 1 µs the
/// error-controlled integrators are the cheaper choice; above 10 ms free flight steps over
/// millimetre contacts and the explicit gyroscopic term loses accuracy.
constexpr double kMinDiscreteStep = 1e-6;
constexpr double kMaxDiscreteStep = 1e-2;

/// What the discrete integrator does with an impact shorter than its step (docs/DISCRETE.md §5).
enum class ImpactMode {
  /// resolve an impact whose predicted rebound reaches SimulationSettings::restitution_threshold;
  /// the plain step takes the others (and dissipates them)
  kAuto,
  kResolve,  ///< integrate every such step's interval by Dormand–Prince, then resume fixed steps
  kImplicit  ///< the plain linearly implicit step throughout (dissipates every impact)
};

/// m/s, the default SimulationSettings::restitution_threshold (docs/DISCRETE.md §5).
constexpr double kDefaultRestitutionThreshold = 0.05;

/// Sleeping islands of the discrete stepper (dynamics/trackers/sleep.hpp, docs/SLEEP.md); dopri5
/// and bdf ignore them (an error-controlled integrator freezes nothing).
struct SleepSettings {
  bool enabled = true;
  /// m/s: a body is quiet while its material points stay within speed × time of where they
  /// were when its quiet spell began (a mean speed; docs/SLEEP.md derives the default
  /// from the creep and the hop of resting parts).
  double speed = 1e-3;
  double time = 0.05;  ///< s: an island sleeps once all its bodies have been quiet this long
};

struct SimulationSettings {
  Integrator integrator = Integrator::kDopri5;
  double duration = 1.0;           ///< s
  double output_rate_hz = 1000.0;  ///< Hz, output every 1/rate s (and at t = 0)
  double abs_tol = 1e-9;           ///< absolute error per step, state units (m, m/s, rad, ...)
  double rel_tol = 1e-6;           ///< relative error per step
  double initial_step = 1e-6;      ///< s
  double max_step = 1e-3;          ///< s, so that no contact is stepped over in free flight
  double min_step = 1e-13;         ///< s; a step-size collapse below this stops the run
  /// s, the fixed step of Integrator::kDiscrete, in [kMinDiscreteStep, kMaxDiscreteStep]
  /// (shortened only to land on output times and the end).
  double step = 1e-3;
  /// Integrator::kDiscrete only ("impacts": "auto", "resolve" or "implicit").
  ImpactMode impacts = ImpactMode::kAuto;
  /// m/s, ImpactMode::kAuto only: the least predicted rebound speed e v_in of an impact worth
  /// resolving (a rebound slower than this hops less than v² / 2g, 0.13 mm at the default).
  double restitution_threshold = kDefaultRestitutionThreshold;
  /// Integrator::kDiscrete only ("sleep": false or {"speed", "time"}).
  SleepSettings sleep;
  /// Stop when a pair's mean penetration V/A exceeds this fraction of the smaller body's size.
  double max_penetration_fraction = 0.1;
};

struct Scenario {
  std::vector<RigidBody> bodies;
  std::vector<ContactPair> pairs;
  std::vector<ExternalLoad> loads;  ///< external forces and drives on bodies
  std::vector<BodySpring> springs;  ///< spring–dampers between two bodies
  Eigen::Vector3d gravity_W = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< m/s²
  SimulationSettings settings;
};

}  // namespace vcontact::dynamics
