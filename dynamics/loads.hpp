#pragma once
// External loads on a body and spring–dampers between two bodies (docs/SCENARIO.md,
// "Loads" and "Springs"): what a rig engineer adds to the contacts to drive a part.
//
// - A constant wrench, or one interpolated from a table (t, f, τ), acting at a body point.
// - A spring–damper to a prescribed target pose: the body frame B is pulled towards the
//   target frame T, the body point P towards where P would be were B at T, with stiffness
//   and damping per axis of T, an optional torsional part on the rotation vector from B to T,
//   and limits |f| ≤ f_max, |τ| ≤ τ_max (a compliant, force-limited drive).
// - A spring–damper between two bodies: linear between one point on each (rest length, k, c,
//   along the line joining them) and torsional on the rotation vector of the relative
//   rotation away from its initial value. The two bodies get equal and opposite wrenches.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/rigid_body.hpp"
#include "dynamics/wrench.hpp"

namespace vcontact::dynamics {

/// Rows (t, f_W, τ_W), interpolated linearly, held before the first and after the last.
struct WrenchTable {
  std::vector<double> t;  ///< s, strictly increasing
  std::vector<Eigen::Vector3d> f_W, tau_W;
  Wrench at(double t) const;
};

struct TargetDrive {
  Eigen::Isometry3d X_WT0 = Eigen::Isometry3d::Identity();        ///< target at t = 0
  PrescribedMotion motion;                                        ///< how the target moves
  Eigen::Vector3d stiffness = Eigen::Vector3d::Zero();            ///< N/m per axis of T
  Eigen::Vector3d damping = Eigen::Vector3d::Zero();              ///< N s/m per axis of T
  Eigen::Vector3d torsional_stiffness = Eigen::Vector3d::Zero();  ///< N m/rad per axis of T
  Eigen::Vector3d torsional_damping = Eigen::Vector3d::Zero();    ///< N m s/rad per axis of T
  double max_force = std::numeric_limits<double>::infinity();     ///< N
  double max_torque = std::numeric_limits<double>::infinity();    ///< N m
};

enum class LoadKind { kConstant, kTable, kDrive };

struct ExternalLoad {
  std::string name;
  std::size_t body = 0;
  Eigen::Vector3d p_BP = Eigen::Vector3d::Zero();  ///< application point in B, m
  LoadKind kind = LoadKind::kConstant;
  Wrench constant;                           ///< kConstant: world frame
  std::shared_ptr<const WrenchTable> table;  ///< kTable
  TargetDrive drive;                         ///< kDrive
};

struct BodySpring {
  std::string name;
  std::size_t a = 0, b = 0;                                       ///< body indices
  Eigen::Vector3d p_AP = Eigen::Vector3d::Zero();                 ///< attachment on a, in A, m
  Eigen::Vector3d p_BQ = Eigen::Vector3d::Zero();                 ///< attachment on b, in B, m
  double rest_length = 0.0;                                       ///< m
  double stiffness = 0.0;                                         ///< N/m
  double damping = 0.0;                                           ///< N s/m
  double torsional_stiffness = 0.0;                               ///< N m/rad
  double torsional_damping = 0.0;                                 ///< N m s/rad
  Eigen::Quaterniond q_AB_rest = Eigen::Quaterniond::Identity();  ///< relative rotation at rest
};

/// A load's or spring's wrench at one instant: the force and the couple on the body (body a
/// for a spring) with the force acting at p_W. A spring's body b gets −f at q_W and −τ.
struct LoadOutput {
  Wrench wrench;                                  ///< on the body: force, and the couple
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< where the force acts, m
  Eigen::Vector3d q_W = Eigen::Vector3d::Zero();  ///< spring: where −f acts on body b
};

/// The load's wrench on its body, whose kinematics are `k`, at time t (s).
LoadOutput loadWrench(const ExternalLoad& load, const BodyKinematics& k, double t);

/// The spring's wrench on body a (kinematics ka) and, opposite, on b (kb).
LoadOutput springWrench(const BodySpring& spring, const BodyKinematics& ka,
                        const BodyKinematics& kb);

/// The elastic energy of a spring (J): ½ k (L − L0)² + ½ k_rot |φ|².
double springEnergy(const BodySpring& spring, const BodyKinematics& ka, const BodyKinematics& kb);

}  // namespace vcontact::dynamics
