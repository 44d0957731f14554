#pragma once
// Helpers shared by the tests: reproducible poses and tensor comparisons.

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "geometry/error.hpp"

namespace vcontact::test {

/// A rigid motion with a rotation about a random axis and a translation whose entries are
/// not exactly representable in binary, from a fixed seed (reproducible).
inline Eigen::Isometry3d randomPose(unsigned seed, double translationScale = 0.37) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Vector3d axis(u(rng), u(rng), u(rng));
  axis.normalize();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI * u(rng), axis).toRotationMatrix();
  X.translation() = translationScale * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

/// Max-norm distance of two matrices relative to the larger max-norm.
template <class A, class B>
double relativeDifference(const A& a, const B& b) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return scale == 0.0 ? 0.0 : (a - b).cwiseAbs().maxCoeff() / scale;
}

/// Rotation taking the frame's z axis onto the unit vector `to`.
inline Eigen::Matrix3d rotationZTo(const Eigen::Vector3d& to) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), to).toRotationMatrix();
}

/// The message of the InputError that `f` throws, or "" when it throws none.
inline std::string inputErrorMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace vcontact::test
