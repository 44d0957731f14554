#pragma once
// Rigid bodies: free (integrated), fixed, or moving on a prescribed function of time.
//
// Frames: B is the body frame, which is also the frame of its shape; Bcm is its centre of
// mass (p_BBcm in B). A free body's state is p_WBcm, q_WB (unit quaternion), v_WBcm, w_WB.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "dynamics/trajectory.hpp"
#include "geometry/primitives.hpp"

namespace vcontact::volume {
struct RecoveredSurface;  // opaque: volume/contact.hpp makes and describes it
}

namespace vcontact::dynamics {

enum class BodyMotion { kFree, kFixed, kPrescribed };

/// X_WB(t) = [exp(w_W t) R_WB(0),  p_WB(0) + v_W t + A_W sin(2π f t)], or, with a
/// trajectory, the trajectory's pose (X_WB(0) is then unused).
struct PrescribedMotion {
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();          ///< m/s
  Eigen::Vector3d w_W = Eigen::Vector3d::Zero();          ///< rad/s
  Eigen::Vector3d amplitude_W = Eigen::Vector3d::Zero();  ///< m
  double frequency_hz = 0.0;                              ///< Hz
  std::shared_ptr<const Trajectory> trajectory;           ///< interpolated table, or null
};

/// The pose and velocities of a frame that starts at X_W0 and moves by `m` at time t (s).
PathPoint prescribedPath(const Eigen::Isometry3d& X_W0, const PrescribedMotion& m, double t);

struct RigidBody {
  std::string name;
  geometry::Shape shape;
  BodyMotion motion = BodyMotion::kFree;
  double mass = 0.0;                                        ///< kg (free bodies)
  Eigen::Vector3d p_BBcm = Eigen::Vector3d::Zero();         ///< centre of mass in B, m
  Eigen::Matrix3d I_BBcm_B = Eigen::Matrix3d::Zero();       ///< inertia about Bcm, B axes, kg·m²
  Eigen::Isometry3d X_WB0 = Eigen::Isometry3d::Identity();  ///< initial pose
  Eigen::Vector3d v_WBcm0 = Eigen::Vector3d::Zero();        ///< initial velocity of Bcm, m/s
  Eigen::Vector3d w_WB0 = Eigen::Vector3d::Zero();          ///< initial angular velocity, rad/s
  PrescribedMotion prescribed;
  /// A mesh body's recovered surface ("surface": "recovered", docs/SCENARIO.md): its
  /// contact with a half-space is then that of the true sphere or capped cylinder where one
  /// applies. Null: the polyhedron (a mesh body's default, and every primitive).
  std::shared_ptr<const volume::RecoveredSurface> surface;
};

/// Where a body is and how it moves at one instant.
struct BodyKinematics {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d p_WBcm = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_WBcm = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_WB = Eigen::Vector3d::Zero();
  double t = 0.0;  ///< time of this state, s (expression effects may read it)

  /// Velocity of the material point of B at p_W: v_WBcm + w_WB × (p_W − p_WBcm).
  Eigen::Vector3d pointVelocity(const Eigen::Vector3d& p_W) const {
    return v_WBcm + w_WB.cross(p_W - p_WBcm);
  }
};

/// Kinematics of a fixed or prescribed body at time t (s).
BodyKinematics scheduledKinematics(const RigidBody& body, double t);

/// Smallest extent of the shape's bounding box (m); infinity for a half-space.
double characteristicSize(const geometry::Shape& shape);

/// Mass properties from the shape and a density (kg/m³): mass, p_BBcm, I_BBcm_B.
/// @throws InputError for a half-space
void setMassFromDensity(RigidBody& body, double density);

}  // namespace vcontact::dynamics
