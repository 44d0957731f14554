#pragma once
// Shared fixtures of the per-effect tests: a contact volume with a normal off the coordinate
// axes, and the model's state slots by effect.

#include <Eigen/Geometry>

#include "dynamics/model.hpp"
#include "support/test_support.hpp"
#include "volume/analytic/primitive_on_plane.hpp"

namespace vcontact::dynamics::test {

// Closed forms evaluated once in double precision: a few ulps of the largest term.
constexpr double kRoundOff = 1e-12;

// A sphere of radius 10 mm pressed 20 µm into a plate whose normal is not a coordinate axis.
inline volume::ContactVolume sphereContact() {
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = vcontact::test::rotationZTo(Eigen::Vector3d(0.3, -0.2, 0.9).normalized());
  Eigen::Isometry3d X_WS = X_WH;
  X_WS.translation() = X_WH * Eigen::Vector3d(0.0, 0.0, 0.01 - 20e-6);
  return volume::sphereHalfspace(0.01, X_WS, X_WH);
}

inline Eigen::Vector3d tangent(const Eigen::Vector3d& n_W) { return n_W.unitOrthogonal(); }

/// Offset of effect `id`'s first state in `model`'s pair state.
inline int stateOffset(const Model& model, const std::string& id) {
  return model.stateLayout().offsetOf(id);
}

}  // namespace vcontact::dynamics::test
