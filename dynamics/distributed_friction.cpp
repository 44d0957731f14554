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

// Below x = 1/4 (ε ≤ 1/2 for F, ε ≥ 2 for F and M) the elliptic brackets lose up to
// log10(1/x²) ≈ 1.2 + digits to cancellation and more as x falls; the series in x converges
// like xⁿ there (≤ 30 terms for double precision).
constexpr double kSeriesBelowX = 0.25;
constexpr int kMaxSeriesTerms = 200;
// A term below this fraction of the sum no longer changes it in double precision.
constexpr double kSeriesStop = 1e-2 * std::numeric_limits<double>::epsilon();

void require(bool ok, const char* what, double value) {
  if (ok) return;
  std::ostringstream s;
  s.precision(17);
  s << "distributedFriction: " << what << " (got " << value << ")";
  throw std::invalid_argument(s.str());
}

/// aₙ = (C(2n, n)/4ⁿ)², the coefficients of K = (π/2) Σ aₙ xⁿ (x = k²).
class KCoefficients {
 public:
  double next() {
    const double a = b_ * b_;
    ++n_;
    b_ *= (2.0 * n_ - 1.0) / (2.0 * n_);
    return a;
  }

 private:
  int n_ = 0;
  double b_ = 1.0;  ///< C(2n, n)/4ⁿ
};

/// Σ_{n≥first} termₙ(aₙ, aₙ₋₁, aₙ₋₂, n) x^{n−first}, summed until the terms stop counting.
template <class Term>
double series(double x, int first, Term term) {
  KCoefficients k;
  double a2 = 0.0, a1 = 0.0, a0 = k.next();  // a_{n−2}, a_{n−1}, a_n at n = 0
  double sum = 0.0, power = 1.0;
  for (int n = 0; n < kMaxSeriesTerms; ++n) {
    if (n >= first) {
      const double t = term(a0, a1, a2, n) * power;
      sum += t;
      power *= x;
      if (n > first + 2 && std::abs(t) < kSeriesStop * std::abs(sum)) break;
    }
    a2 = a1;
    a1 = a0;
    a0 = k.next();
  }
  return sum;
}

/// c_n of the force: (1 + x)E − (1 − x)K = (π/2) Σ cₙ xⁿ, c₀ = 0, c₁ = 3/2.
double forceTerm(double an, double an1, double /*an2*/, int n) {
  return an * (2.0 * n / (1.0 - 2.0 * n)) + an1 * ((4.0 - 2.0 * n) / (3.0 - 2.0 * n));
}

/// e_n of the large-ε torque: 2(2x − 1)E + (2 − 3x)(1 − x)K = (π/2) Σ eₙ xⁿ, e₀ = e₁ = 0.
double torqueTerm(double an, double an1, double an2, int n) {
  return an * (2.0 - 2.0 / (1.0 - 2.0 * n)) + an1 * (4.0 / (3.0 - 2.0 * n) - 5.0) + 3.0 * an2;
}

PunchFriction ellipticSpinDominated(double eps) {  // ε ≤ 1, modulus ε
  const double K = std::comp_ellint_1(eps), E = std::comp_ellint_2(eps);
  const double x = eps * eps;
  const double force = eps < std::sqrt(kSeriesBelowX)
                           ? 2.0 * eps / 3.0 * series(x, 1, forceTerm)
                           : 4.0 / (3.0 * std::numbers::pi * eps) * ((1.0 + x) * E - (1.0 - x) * K);
  const double torque = 4.0 / (9.0 * std::numbers::pi) * ((4.0 - 2.0 * x) * E - (1.0 - x) * K);
  return {force, torque};
}

PunchFriction ellipticSlideDominated(double eps) {  // ε ≥ 1, modulus 1/ε
  const double x = 1.0 / (eps * eps);
  if (x < kSeriesBelowX) {
    return {2.0 / 3.0 * series(x, 1, forceTerm), 2.0 / (9.0 * eps) * series(x, 2, torqueTerm)};
  }
  const double K = std::comp_ellint_1(1.0 / eps), E = std::comp_ellint_2(1.0 / eps);
  const double e2 = eps * eps;
  return {4.0 / (3.0 * std::numbers::pi) * ((1.0 + e2) * E - (e2 - 1.0) * K),
          4.0 / (9.0 * std::numbers::pi * eps) *
              (2.0 * e2 * (2.0 - e2) * E + (2.0 * e2 - 3.0) * (e2 - 1.0) * K)};
}

}  // namespace

PunchFriction flatPunchFriction(double eps) {
  require(eps >= 0.0, "epsilon = v/(omega R) must be >= 0", eps);
  if (std::isinf(eps)) return {1.0, 0.0};
  if (eps == 0.0) return {0.0, 2.0 / 3.0};
  // ε = 1: K(1) = ∞ but (1 − ε²)K → 0, E(1) = 1.
  if (eps == 1.0) return {8.0 / (3.0 * std::numbers::pi), 8.0 / (9.0 * std::numbers::pi)};
  return eps <= 1.0 ? ellipticSpinDominated(eps) : ellipticSlideDominated(eps);
}

PunchFriction lumpedPunchFriction(double eps, double g) {
  require(eps >= 0.0, "epsilon = v/(omega R) must be >= 0", eps);
  require(g > 0.0 && std::isfinite(g), "r_gyr/R must be finite and > 0", g);
  if (std::isinf(eps)) return {1.0, 0.0};
  const double v_avg = std::hypot(eps, g);  // in units of ωR
  return {eps / v_avg, g * g / v_avg};
}

DistributedFriction distributedFriction(const volume::ContactVolume& cv,
                                        const volume::ColumnField& field, const PressureLaw& law,
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
  out.cell_area = field.cellArea > 0.0 ? field.cellArea : cv.area / double(count);
  double volume = 0.0;
  for (double d : field.depth) volume += d * out.cell_area;
  require(std::abs(volume - cv.volume) <= kFieldVolumeTolerance * cv.volume,
          "the field does not belong to this contact: sum of delta dS differs from V", volume);

  const Vector3d& n = cv.normal;
  const Vector3d& p_c = cv.centroid;
  const ContactKinematics k = resolve(motion, n);  // MODEL.md §2
  // MODEL.md §3: f_n = kv V (1 + a δ̇_c) clamped ≥ 0.
  const double damping = std::max(0.0, 1.0 + law.a * k.delta_dot);
  const Vector3d& v_t = k.v_t_W;
  const Vector3d w_n = k.omega_n * n;  // ω_t × ρ is along n: no slip in the plate
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
