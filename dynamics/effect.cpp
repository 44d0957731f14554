#include "dynamics/effect.hpp"

#include <algorithm>

namespace vcontact::dynamics {

double contactArea(const volume::ContactVolume& cv) {
  if (cv.area > 0.0) return cv.area;
  return cv.depth > 0.0 ? cv.volume / cv.depth : 0.0;
}

// dir_ε(v) = v / max(|v|, v_ε)   (MODEL.md §3)
Eigen::Vector3d dirEps(const Eigen::Vector3d& v, double v_eps) {
  return v / std::max(v.norm(), v_eps);
}

// sgn_ε(ω) = ω / max(|ω|, v_ε / r_gyr); 0 when r_gyr = 0 (no lever arm for spin).
double sgnEps(double omega, double v_eps, double r_gyr) {
  if (r_gyr <= 0.0) return 0.0;
  return omega / std::max(std::abs(omega), v_eps / r_gyr);
}

Eigen::Vector3d saturate(const Eigen::Vector3d& x, double max_norm) {
  const double norm = x.norm();
  return norm > max_norm ? Eigen::Vector3d(x * (max_norm / norm)) : x;
}

double saturate(double x, double max_abs) { return std::clamp(x, -max_abs, max_abs); }

Eigen::Matrix3d planeProjector(const Eigen::Vector3d& n) {
  return Eigen::Matrix3d::Identity() - n * n.transpose();
}

const std::vector<StateSlot>& Effect::stateSlots() const {
  static const std::vector<StateSlot> kNone;
  return kNone;
}

void Effect::initialiseParameters(const std::vector<ParameterSpec>& specs) {
  values_.clear();
  for (const auto& s : specs) values_.push_back(s.default_value);
}

}  // namespace vcontact::dynamics
