#pragma once
// Relative motion of the two bodies of a contact pair at the centroid p_c (MODEL.md §2), in
// one place: the simulator, the model's context, distributed friction and the replay of a rig
// record all take it from here. Body A is the payload (MODEL.md's B1), body B the plate or the
// other body (B2); every vector is in the world frame W.

#include <Eigen/Core>

#include "dynamics/rigid_body.hpp"

namespace vcontact::dynamics {

/// Velocity of the material point of body A at p_c minus that of body B, and ω_A − ω_B.
struct RelativeMotion {
  Eigen::Vector3d v_c_W = Eigen::Vector3d::Zero();  ///< m/s
  Eigen::Vector3d w_W = Eigen::Vector3d::Zero();    ///< rad/s
  double t = 0.0;  ///< time, s: of the simulation, or of the record's sample in a replay
};

/// The relative motion resolved along the contact normal n (out of body B into body A).
struct ContactKinematics {
  double delta_dot = 0.0;                           ///< δ̇_c = −v_c·n, m/s (> 0 approaching)
  Eigen::Vector3d v_t_W = Eigen::Vector3d::Zero();  ///< slip v_t = v_c − (v_c·n) n, m/s
  double omega_n = 0.0;                             ///< spin ω_n = ω·n, rad/s
  Eigen::Vector3d omega_t_W = Eigen::Vector3d::Zero();  ///< rolling ω_t = ω − ω_n n, rad/s
};

/// v_c = v_A(p_WC) − v_B(p_WC), ω = ω_A − ω_B (MODEL.md §2), where v_X(p) is the velocity of
/// the material point of body X at p (BodyKinematics::pointVelocity); t is A's.
RelativeMotion relativeMotion(const BodyKinematics& A, const BodyKinematics& B,
                              const Eigen::Vector3d& p_WC);

/// δ̇_c, v_t, ω_n and ω_t of `motion` for the unit normal n_W (MODEL.md §2).
/// @pre |n_W| = 1
ContactKinematics resolve(const RelativeMotion& motion, const Eigen::Vector3d& n_W);

}  // namespace vcontact::dynamics
