#include "dynamics/distributed_friction.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace vcontact::dynamics {
namespace {

using Eigen::Vector3d;

// The field belongs to cv when Σ δ dS reproduces V: the columns backend sums the same
// products (in another order), so only round-off separates them (~1e-15 relative).
constexpr double kFieldVolumeTolerance = 1e-9;

void require(bool ok, const char* what, double value) {
  if (ok) return;
  std::ostringstream s;
  s.precision(17);
  s << "distributedFriction: " << what << " (got " << value << ")";
  throw std::invalid_argument(s.str());
}

}  // namespace

DistributedFriction distributedFriction(const volume::ContactVolume& cv,
                                        const volume::DepthField& field, const PressureLaw& law,
                                        const RelativeMotion& motion, double mu, double v_eps) {
  require(cv.inContact(), "the contact volume must be > 0", cv.volume);
  const std::size_t count = field.depth.size();
  require(count > 0 && field.points_W.size() == count,
          "the field needs as many points as depths, at least one", double(count));
  require(std::isfinite(law.kv) && law.kv > 0.0, "kv must be finite and > 0", law.kv);
  require(std::isfinite(law.a) && law.a >= 0.0, "the damping factor a must be finite, >= 0", law.a);
  require(std::isfinite(mu) && mu >= 0.0, "mu must be finite and >= 0", mu);
  require(std::isfinite(v_eps) && v_eps > 0.0, "v_eps must be finite and > 0", v_eps);
  require(motion.v_c_W.allFinite() && motion.w_W.allFinite(), "the motion must be finite",
          motion.v_c_W.norm() + motion.w_W.norm());

  DistributedFriction out;
  out.cells = static_cast<int>(count);
  // The grid's own cell; a field built by hand without one is taken to tile cv.area.
  out.cell_area = field.cell_area > 0.0 ? field.cell_area : cv.area / double(count);
  double volume = 0.0;
  for (double d : field.depth) volume += d * out.cell_area;
  require(std::abs(volume - cv.volume) <= kFieldVolumeTolerance * cv.volume,
          "the field does not belong to this contact: sum of delta dS differs from V", volume);

  const Vector3d& n = cv.n_W;
  const Vector3d& p_c = cv.p_WC;
  // MODEL.md §2: δ̇_c = −v_c·n; §3: f_n = kv V (1 + a δ̇_c) clamped ≥ 0.
  const double damping = std::max(0.0, 1.0 + law.a * -motion.v_c_W.dot(n));
  const Vector3d v_t = motion.v_c_W - motion.v_c_W.dot(n) * n;
  const Vector3d w_n = motion.w_W.dot(n) * n;  // ω_t × ρ is along n: no slip in the plate
  Vector3d force = Vector3d::Zero(), torque = Vector3d::Zero();
  double f_n = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vector3d q = field.points_W[i] - p_c;
    const Vector3d rho = q - q.dot(n) * n;
    const double dF_n = law.kv * field.depth[i] * damping * out.cell_area;  // p dS, N
    const Vector3d dF = -mu * dF_n * dirEps(v_t + w_n.cross(rho), v_eps);
    f_n += dF_n;
    force += dF;
    torque += rho.cross(dF);
  }
  out.f_n = f_n;
  out.wrench = {force, torque};
  return out;
}

}  // namespace vcontact::dynamics
