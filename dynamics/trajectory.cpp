#include "dynamics/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/error.hpp"

namespace vcontact::dynamics {
namespace {

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Below this angle (rad) the Jacobians use their Taylor series: the closed forms lose about
// 1/θ² of relative precision, and the series' next terms are below θ² ≈ 1e-12.
constexpr double kSmallAngle = 1e-6;

Eigen::Quaterniond expMap(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < kSmallAngle) {
    return Eigen::Quaterniond(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle));
}

// The three-point slope at row i of values y over times t: the interval slopes weighted by the
// other interval's length (exact for a quadratic); the adjacent slope at either end.
template <class Slope>
Eigen::Vector3d threePoint(const std::vector<double>& t, std::size_t i, const Slope& slope) {
  const std::size_t n = t.size();
  if (i == 0) return slope(0);
  if (i + 1 == n) return slope(n - 2);
  const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
  return (h1 * slope(i - 1) + h0 * slope(i)) / (h0 + h1);
}

}  // namespace

Eigen::Vector3d rotationVector(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // the short way, angle ≤ π
  const double s = q.vec().norm();
  if (s < kSmallAngle) return 2.0 * q.vec();
  return 2.0 * std::atan2(s, q.w()) * q.vec() / s;
}

Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& r) {
  const double a = r.norm();
  const Eigen::Matrix3d R = hat(r);
  if (a < kSmallAngle) return Eigen::Matrix3d::Identity() - 0.5 * R + R * R / 6.0;
  return Eigen::Matrix3d::Identity() - (1.0 - std::cos(a)) / (a * a) * R +
         (a - std::sin(a)) / (a * a * a) * R * R;
}

Eigen::Matrix3d rightJacobianInverse(const Eigen::Vector3d& r) {
  const double a = r.norm();
  const Eigen::Matrix3d R = hat(r);
  const double c =
      a < kSmallAngle ? 1.0 / 12.0 : 1.0 / (a * a) - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
  return Eigen::Matrix3d::Identity() + 0.5 * R + c * R * R;
}

Trajectory::Trajectory(TrajectoryRows rows, Interpolation interpolation)
    : rows_(std::move(rows)), interpolation_(interpolation) {
  const std::size_t n = rows_.t.size();
  if (n == 0) throw InputError("trajectory", "expected at least one row");
  if (rows_.p_WB.size() != n || rows_.q_WB.size() != n ||
      (!rows_.v_WBo.empty() && rows_.v_WBo.size() != n) ||
      (!rows_.w_WB.empty() && rows_.w_WB.size() != n)) {
    throw InputError("trajectory", "columns of different lengths");
  }
  if (interpolation_ == Interpolation::kLinear && (!rows_.v_WBo.empty() || !rows_.w_WB.empty())) {
    throw InputError("trajectory",
                     "velocity columns need cubic interpolation (a linear one sets the "
                     "velocities from the rows)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && !(rows_.t[i] > rows_.t[i - 1])) {
      throw InputError("trajectory", "row " + std::to_string(i + 1) +
                                         ": times must increase strictly from row to row");
    }
    rows_.q_WB[i].normalize();
    // consecutive quaternions on the same half of the sphere: the short way between rows
    if (i > 0 && rows_.q_WB[i].dot(rows_.q_WB[i - 1]) < 0.0) {
      rows_.q_WB[i].coeffs() = -rows_.q_WB[i].coeffs();
    }
  }
  if (interpolation_ == Interpolation::kCubic) estimateTangents();
}

// Tangents at the rows for the cubic curves: the given velocities, or three-point estimates
// from the interval slopes (position) and the intervals' constant slerp rates (orientation).
void Trajectory::estimateTangents() {
  const std::vector<double>& t = rows_.t;
  const std::size_t n = t.size();
  dp_ = rows_.v_WBo;
  w_ = rows_.w_WB;
  if (n < 2) {
    dp_.assign(n, Eigen::Vector3d::Zero());
    w_.assign(n, Eigen::Vector3d::Zero());
    return;
  }
  const auto slope = [&](std::size_t i) -> Eigen::Vector3d {
    return (rows_.p_WB[i + 1] - rows_.p_WB[i]) / (t[i + 1] - t[i]);
  };
  // slerp rate of interval i, world frame: R_i Log(q_i⁻¹ q_i+1) / h (the axis is the same in
  // the frames of both ends)
  const auto rate = [&](std::size_t i) -> Eigen::Vector3d {
    const Eigen::Vector3d r = rotationVector(rows_.q_WB[i].conjugate() * rows_.q_WB[i + 1]);
    return rows_.q_WB[i] * r / (t[i + 1] - t[i]);
  };
  if (dp_.empty()) {
    for (std::size_t i = 0; i < n; ++i) dp_.push_back(threePoint(t, i, slope));
  }
  if (w_.empty()) {
    for (std::size_t i = 0; i < n; ++i) w_.push_back(threePoint(t, i, rate));
  }
}

PathPoint Trajectory::at(double t) const {
  const std::vector<double>& ts = rows_.t;
  PathPoint out;
  if (t < ts.front() || t >= ts.back()) {  // held: the first or last pose, at rest
    const std::size_t i = t < ts.front() ? 0 : ts.size() - 1;
    out.X_WB.linear() = rows_.q_WB[i].toRotationMatrix();
    out.X_WB.translation() = rows_.p_WB[i];
    return out;
  }
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()) - 1;
  return position(i, t);
}

// The pose and velocities at t in interval i, [t_i, t_i+1).
PathPoint Trajectory::position(std::size_t i, double t) const {
  const double h = rows_.t[i + 1] - rows_.t[i];
  const double s = (t - rows_.t[i]) / h;
  const Eigen::Vector3d& p0 = rows_.p_WB[i];
  const Eigen::Vector3d& p1 = rows_.p_WB[i + 1];
  const Eigen::Quaterniond& q0 = rows_.q_WB[i];
  const Eigen::Vector3d phi = rotationVector(q0.conjugate() * rows_.q_WB[i + 1]);
  PathPoint out;
  Eigen::Vector3d r, r_dot;  // rotation vector from q0 in its own frame, and its rate
  if (interpolation_ == Interpolation::kLinear) {
    out.X_WB.translation() = p0 + s * (p1 - p0);
    out.v_WBo = (p1 - p0) / h;
    r = s * phi;
    r_dot = phi / h;
  } else {
    // Hermite basis and its derivative in s
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
                 h11 = s3 - s2;
    const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -d00, d11 = 3 * s2 - 2 * s;
    out.X_WB.translation() = h00 * p0 + h10 * h * dp_[i] + h01 * p1 + h11 * h * dp_[i + 1];
    out.v_WBo = (d00 * p0 + d10 * h * dp_[i] + d01 * p1 + d11 * h * dp_[i + 1]) / h;
    // end slopes of r: the body-frame angular velocities, the one at the far end through
    // J_r(φ)⁻¹ (ω_body = J_r(r) ṙ)
    const Eigen::Vector3d r0 = q0.conjugate() * w_[i];
    const Eigen::Vector3d r1 =
        rightJacobianInverse(phi) * (rows_.q_WB[i + 1].conjugate() * w_[i + 1]);
    r = h01 * phi + h10 * h * r0 + h11 * h * r1;
    r_dot = (d01 * phi + d10 * h * r0 + d11 * h * r1) / h;
  }
  const Eigen::Quaterniond q = q0 * expMap(r);
  out.X_WB.linear() = q.toRotationMatrix();
  out.w_WB = q * (rightJacobian(r) * r_dot);
  return out;
}

}  // namespace vcontact::dynamics
