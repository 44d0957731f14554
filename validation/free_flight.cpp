#include "validation/free_flight.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "volume/contact.hpp"

namespace vcontact::validation {
namespace {

// Rotation vector of R (log map), |θ| ≤ π.
Eigen::Vector3d logRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d expRotation(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

// d/dt of (R_BA, ω_A) under Euler's equations, ω_A in the payload's axes: Ṙ = R [ω_A]×,
// I ω̇_A = −ω_A × I ω_A.
struct Rotation {
  Eigen::Matrix3d R;
  Eigen::Vector3d w_A;
};

Rotation rate(const Rotation& s, const Eigen::Matrix3d& I_A, const Eigen::Matrix3d& I_A_inv) {
  Eigen::Matrix3d W;
  W << 0, -s.w_A.z(), s.w_A.y(), s.w_A.z(), 0, -s.w_A.x(), -s.w_A.y(), s.w_A.x(), 0;
  return {s.R * W, -I_A_inv * s.w_A.cross(I_A * s.w_A)};
}

Rotation axpy(const Rotation& s, double h, const Rotation& k) {
  return {s.R + h * k.R, s.w_A + h * k.w_A};
}

// Orthonormalises R (nearest rotation by its SVD).
Eigen::Matrix3d orthonormal(const Eigen::Matrix3d& R) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

const PayloadInertia& massProperties(const Dataset& d) { return d.inertia.value(); }

// The attitude at each sample time t_i − t_0 of a torque-free rotation from (R0, ω0), for i < n.
std::vector<Eigen::Matrix3d> rotations(const Dataset& d, std::size_t n, const Eigen::Matrix3d& R0,
                                       const Eigen::Vector3d& w0_B) {
  std::vector<Eigen::Matrix3d> out(n);
  Eigen::Matrix3d R = R0;
  Eigen::Vector3d w = w0_B;
  out[0] = R;
  for (std::size_t i = 1; i < n; ++i) {
    advanceTorqueFree(R, w, massProperties(d).inertia, d.samples[i].t - d.samples[i - 1].t);
    out[i] = R;
  }
  return out;
}

// Residuals log(R_meas_i R_pred_iᵀ) of the rotation (δ on R_0, ω_0) over the first n samples.
Eigen::VectorXd attitudeResiduals(const Dataset& d, std::size_t n, const Eigen::Matrix3d& R0,
                                  const Eigen::Matrix<double, 6, 1>& x) {
  const auto R = rotations(d, n, expRotation(x.head<3>()) * R0, x.tail<3>());
  Eigen::VectorXd r(static_cast<Eigen::Index>(3 * n));
  for (std::size_t i = 0; i < n; ++i)
    r.segment<3>(static_cast<Eigen::Index>(3 * i)) =
        logRotation(d.samples[i].X_BA.linear() * R[i].transpose());
  return r;
}

// Gauss–Newton on (δθ_0, ω_0) with a central-difference Jacobian; ω_0 starts from the mean
// rotation rate over the free samples.
Eigen::Matrix<double, 6, 1> fitRotation(const Dataset& d, std::size_t n,
                                        const Eigen::Matrix3d& R0) {
  Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
  const auto& s = d.samples;
  x.tail<3>() = logRotation(s[n - 1].X_BA.linear() * R0.transpose()) / (s[n - 1].t - s[0].t);
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Eigen::VectorXd r = attitudeResiduals(d, n, R0, x);
    Eigen::MatrixXd J(r.size(), 6);
    for (int k = 0; k < 6; ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[k]));
      Eigen::Matrix<double, 6, 1> xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      J.col(k) = (attitudeResiduals(d, n, R0, xp) - attitudeResiduals(d, n, R0, xm)) / (2 * h);
    }
    const Eigen::Matrix<double, 6, 1> step = J.colPivHouseholderQr().solve(-r);
    x += step;
    if (step.norm() < 1e-12 * (1.0 + x.norm())) break;
  }
  return x;
}

// Least squares of p_cm(τ) = a + b τ + ½ g τ² over the first n samples (τ = t − t_0):
// returns a, b and the RMS residual.
struct Parabola {
  Eigen::Vector3d a, b;
  double rms;
};

Parabola fitParabola(const Dataset& d, std::size_t n, const std::vector<Eigen::Vector3d>& p) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(n), 2);
  Eigen::MatrixXd y(static_cast<Eigen::Index>(n), 3);
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = d.samples[i].t - d.samples[0].t;
    const auto r = static_cast<Eigen::Index>(i);
    A(r, 0) = 1.0;
    A(r, 1) = tau;
    y.row(r) = (p[i] - 0.5 * d.gravity_B * tau * tau).transpose();
  }
  const Eigen::MatrixXd c = A.colPivHouseholderQr().solve(y);
  const double rms = std::sqrt((A * c - y).squaredNorm() / static_cast<double>(n));
  return {c.row(0).transpose(), c.row(1).transpose(), rms};
}

}  // namespace

std::size_t firstContact(const Dataset& d) {
  for (std::size_t i = 0; i < d.size(); ++i) {
    const volume::ContactPatches c =
        volume::computeContact(d.payload, d.samples[i].X_BA, d.plate, d.X_BP);
    if (c.aggregate.inContact()) return i;
  }
  return d.size();
}

double clearance(const Dataset& d, const Eigen::Isometry3d& X_BA) {
  if (!std::holds_alternative<geometry::HalfSpace>(d.plate))
    return std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3d n = d.X_BP.linear().col(2);
  const double plane = n.dot(d.X_BP.translation());
  const Eigen::Vector3d c = X_BA.translation();
  const Eigen::Matrix3d& R = X_BA.linear();
  const Eigen::Vector3d n_A = R.transpose() * n;  // the plate normal in the payload's axes
  if (const auto* s = std::get_if<geometry::Sphere>(&d.payload))
    return n.dot(c) - plane - s->radius;
  if (const auto* b = std::get_if<geometry::Box>(&d.payload))
    return n.dot(c) - plane - 0.5 * b->size.cwiseProduct(n_A.cwiseAbs()).sum();
  if (const auto* y = std::get_if<geometry::Cylinder>(&d.payload)) {
    const double along = std::abs(n_A.z());
    return n.dot(c) - plane - 0.5 * y->length * along -
           y->radius * std::sqrt(std::max(0.0, 1.0 - along * along));
  }
  const auto& m = std::get<geometry::Mesh>(d.payload).mesh;
  return n.dot(c) - plane + (m->vertices * n_A).minCoeff();
}

void advanceTorqueFree(Eigen::Matrix3d& R_BA, Eigen::Vector3d& w_B, const Eigen::Matrix3d& I_A,
                       double dt) {
  constexpr double kMaxSubstep = 1e-4;  // s: RK4's error ~ (|ω| h)^5 stays below 1e-12 rad
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(dt) / kMaxSubstep)));
  const double h = dt / steps;
  const Eigen::Matrix3d I_inv = I_A.inverse();
  Rotation s{R_BA, R_BA.transpose() * w_B};
  for (int k = 0; k < steps; ++k) {
    const Rotation k1 = rate(s, I_A, I_inv);
    const Rotation k2 = rate(axpy(s, h / 2, k1), I_A, I_inv);
    const Rotation k3 = rate(axpy(s, h / 2, k2), I_A, I_inv);
    const Rotation k4 = rate(axpy(s, h, k3), I_A, I_inv);
    s.R += h / 6 * (k1.R + 2 * k2.R + 2 * k3.R + k4.R);
    s.w_A += h / 6 * (k1.w_A + 2 * k2.w_A + 2 * k3.w_A + k4.w_A);
    s.R = orthonormal(s.R);
  }
  R_BA = s.R;
  w_B = s.R * s.w_A;
}

FlightState initialState(const Dataset& d) {
  FlightState f;
  const Eigen::Vector3d& com = massProperties(d).com;
  const Sample& s0 = d.samples.front();
  f.X_BA = s0.X_BA;
  f.w_BA = s0.w_BA;
  f.v_BAcm = s0.v_BA + s0.w_BA.cross(s0.X_BA.linear() * com);
  if (!d.velocityFromPositions && !d.omegaFromAttitude) return f;
  const std::size_t n = firstContact(d);
  f.estimated = true;
  f.samplesUsed = n;
  const Eigen::Matrix3d R0 = s0.X_BA.linear();
  const Eigen::Matrix<double, 6, 1> x = fitRotation(d, n, R0);
  const auto R = rotations(d, n, expRotation(x.head<3>()) * R0, x.tail<3>());
  f.attitudeRms = std::sqrt(attitudeResiduals(d, n, R0, x).squaredNorm() / static_cast<double>(n));
  std::vector<Eigen::Vector3d> p_cm(n);
  for (std::size_t i = 0; i < n; ++i)
    p_cm[i] = d.samples[i].X_BA.translation() + d.samples[i].X_BA.linear() * com;
  const Parabola fit = fitParabola(d, n, p_cm);
  f.positionRms = fit.rms;
  f.X_BA.linear() = R.front();
  f.X_BA.translation() = fit.a - R.front() * com;
  f.v_BAcm = fit.b;
  f.w_BA = x.tail<3>();
  // a velocity column the record has is kept (its estimate still gave the attitude's fit)
  if (!d.omegaFromAttitude) f.w_BA = s0.w_BA;
  if (!d.velocityFromPositions) f.v_BAcm = s0.v_BA + f.w_BA.cross(f.X_BA.linear() * com);
  return f;
}

}  // namespace vcontact::validation
