#pragma once
// A wrench (force and torque) acting on body A (the payload, MODEL.md's B1) at the contact
// centroid p_c (MODEL.md §3). Body B (the plate, B2) receives the opposite wrench there.

#include <Eigen/Core>

namespace vcontact::dynamics {

struct Wrench {
  Eigen::Vector3d f_W = Eigen::Vector3d::Zero();  ///< force on body A, N, world frame
  Eigen::Vector3d tau_W =
      Eigen::Vector3d::Zero();  ///< torque on body A about p_c, N·m, world frame

  Wrench& operator+=(const Wrench& o) {
    f_W += o.f_W;
    tau_W += o.tau_W;
    return *this;
  }
};

}  // namespace vcontact::dynamics
