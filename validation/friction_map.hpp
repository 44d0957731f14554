#pragma once
// The friction map: where the lumped Coulomb + spin + contensou friction (MODEL.md §3) departs
// from pointwise Coulomb friction integrated over the contact (dynamics/distributed_friction.hpp,
// docs/DISTRIBUTED_FRICTION.md), swept over ε = v/(ωR) for combined sliding and spinning.
//
// A body (by default a flat punch) is pressed into a half-space plate; the column method's δ map
// is taken once; for every ε the lumped model and the distributed integral give the friction
// force (in the plate) and the spin torque (along n), and for the flat punch the closed form
// (validation/punch_friction.hpp) gives the exact answer.

#include <optional>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"
#include "validation/punch_friction.hpp"

namespace vcontact::validation {

struct FrictionMapOptions {
  double radius = 0.01;                  ///< m: a 20 mm steel punch
  double load = 10.0;                    ///< N, on the punch
  double mu = 0.2;                       ///< MODEL.md §4
  double kv = 5.17e12;                   ///< N/m³, MODEL.md §4
  double eps_min = 1e-3, eps_max = 1e3;  ///< the sweep's smallest and largest ε > 0
  int per_decade = 4;                    ///< sweep points per decade of ε
  double speed = 1.0;  ///< m/s, the combined slip √(v² + (ωR)²), far above v_ε
  /// Instead of the punch: a mesh, cylinder, box or sphere pressed `depth` into the plate in
  /// its own orientation, with R = √2 r_gyr and no closed form.
  std::optional<geometry::Shape> shape;
  double depth = 2e-6;  ///< m, for `shape`
};

struct FrictionMapRow {
  double eps, v, w;                    ///< –, m/s, rad/s
  double f_lumped, f_dist;             ///< N, friction force magnitudes
  double m_lumped, m_dist;             ///< N·m, spin torque magnitudes
  std::optional<PunchFriction> exact;  ///< F/μN, M/μNR of the flat punch
};

struct FrictionMap {
  std::string description;  ///< the body and its depth, for a heading
  double f_n = 0.0;         ///< N, kv V
  double mu = 0.0;
  double R = 0.0;                    ///< m, the reference length of ε
  double r_gyr = 0.0;                ///< m, of the contact
  double relative_error = 0.0;       ///< of the column grid
  std::vector<FrictionMapRow> rows;  ///< ε = 0, eps_min … eps_max, ε = ∞
};

/// Runs the sweep. @throws InputError naming the quantity ("radius", "load", "mu", "kv",
/// "depth", "speed", "epsilon range", "points per decade", "shape") when an option is out of
/// range, or when the shape does not reach the plate.
FrictionMap frictionMap(const FrictionMapOptions& options);

/// a / b; NaN where the lumped value a is exactly 0 (its force in pure spin, its torque in pure
/// sliding), since the distributed one is then 0 up to the grid's asymmetry or round-off.
double lumpedOverDistributed(double a, double b);

}  // namespace vcontact::validation
