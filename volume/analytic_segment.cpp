#include "volume/analytic_segment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace vcontact::volume::detail {
namespace {

// Each integrand is a trigonometric polynomial Σ_k a_k cos kφ (k ≤ 4):
//   sin²φ                 = 1/2 − cos 2φ/2
//   (1 − cos φ) sin²φ     = 1/2 − cos φ/4 − cos 2φ/2 + cos 3φ/4
//   (1 − cos φ)² sin²φ    = 5/8 − cos φ/2 − cos 2φ/2 + cos 3φ/2 − cos 4φ/8
//   sin⁴φ                 = 3/8 − cos 2φ/2 + cos 4φ/8
// so ∫_0^θ = a_0 θ + Σ_k a_k sin kθ / k, from one sincos and the multiple-angle recurrence.
// For small θ those terms cancel down to the θ³…θ⁷ leading order; there the Taylor series
//   ∫_0^θ = Σ_j (−1)^j θ^{2j+1}/(2j+1)! · Σ_k a_k k^{2j}
// is used instead: its coefficients are exact (k ≤ 4, a_k in eighths) and its terms do not
// cancel. Switching at θ = 0.75 keeps both sides within ~1e-13 relative.
constexpr int kTrigTerms = 5;
using TrigPoly = std::array<double, kTrigTerms>;  // a_0 … a_4
constexpr TrigPoly kSin2 = {0.5, 0.0, -0.5, 0.0, 0.0};
constexpr TrigPoly kOmcSin2 = {0.5, -0.25, -0.5, 0.25, 0.0};
constexpr TrigPoly kOmc2Sin2 = {0.625, -0.5, -0.5, 0.5, -0.125};
constexpr TrigPoly kSin4 = {0.375, 0.0, -0.5, 0.0, 0.125};
constexpr double kSeriesBelow = 0.75;
constexpr int kSeriesTerms = 18;  // (4·0.75)^{37}/37! < 1e-17

double integrateClosed(const TrigPoly& a, double theta,
                       const std::array<double, kTrigTerms>& sinK) {
  double sum = a[0] * theta;
  for (int k = 1; k < kTrigTerms; ++k) sum += a[k] * sinK[k] / k;
  return sum;
}

/// Σ_k a_k k^{2j} for j < kSeriesTerms: the series coefficients, exact in binary.
std::array<double, kSeriesTerms> seriesMoments(const TrigPoly& a) {
  std::array<double, kSeriesTerms> m{};
  for (int j = 0; j < kSeriesTerms; ++j) {
    m[j] = j == 0 ? a[0] : 0.0;
    for (int k = 1; k < kTrigTerms; ++k) m[j] += a[k] * std::pow(static_cast<double>(k), 2 * j);
  }
  return m;
}

double integrateSeries(const std::array<double, kSeriesTerms>& m, double theta) {
  double sum = 0.0, power = theta;  // θ^{2j+1}/(2j+1)!
  for (int j = 0; j < kSeriesTerms; ++j) {
    sum += (j % 2 == 0 ? power : -power) * m[j];
    power *= theta * theta / ((2.0 * j + 2.0) * (2.0 * j + 3.0));
  }
  return sum;
}

}  // namespace

Segment segmentMoments(double R, double theta) {
  double i20, i21, i22, i40;
  if (theta < kSeriesBelow) {
    static const auto m20 = seriesMoments(kSin2), m21 = seriesMoments(kOmcSin2),
                      m22 = seriesMoments(kOmc2Sin2), m40 = seriesMoments(kSin4);
    i20 = integrateSeries(m20, theta);
    i21 = integrateSeries(m21, theta);
    i22 = integrateSeries(m22, theta);
    i40 = integrateSeries(m40, theta);
  } else {
    std::array<double, kTrigTerms> sinK{};
    const double s1 = std::sin(theta), c1 = std::cos(theta);
    double sPrev = 0.0, sCur = s1;
    sinK[1] = s1;
    for (int k = 2; k < kTrigTerms; ++k) {  // sin kθ = 2 cos θ sin (k−1)θ − sin (k−2)θ
      const double next = 2.0 * c1 * sCur - sPrev;
      sPrev = sCur;
      sCur = next;
      sinK[k] = sCur;
    }
    i20 = integrateClosed(kSin2, theta, sinK);
    i21 = integrateClosed(kOmcSin2, theta, sinK);
    i22 = integrateClosed(kOmc2Sin2, theta, sinK);
    i40 = integrateClosed(kSin4, theta, sinK);
  }
  const double R2 = R * R;
  return {2.0 * R2 * i20, 2.0 * R2 * R * i21, 2.0 * R2 * R2 * i22, (2.0 / 3.0) * R2 * R2 * i40};
}

/// θ with d = R(1 − cos θ), accurate for small d; d is clamped to [0, 2R].
double segmentAngle(double R, double d) {
  const double r = std::clamp(d / (2.0 * R), 0.0, 1.0);
  return 2.0 * std::asin(std::sqrt(r));
}

/// ∫_0^θ |A cos φ + B| dφ.
double absCosIntegral(double A, double B, double theta) {
  const auto F = [&](double phi) { return A * std::sin(phi) + B * phi; };
  if (A != 0.0 && std::abs(B) < std::abs(A)) {
    const double phi0 = std::acos(-B / A);  // where A cos φ + B changes sign
    if (phi0 < theta) return std::abs(F(phi0)) + std::abs(F(theta) - F(phi0));
  }
  return std::abs(F(theta));
}

/// Solutions α ∈ (lo, hi) of P cos α + Q sin α = K.
void trigRoots(double P, double Q, double K, double lo, double hi, std::vector<double>& out) {
  const double rho = std::hypot(P, Q);
  if (!(rho > 0.0) || std::abs(K) > rho) return;
  const double phi = std::atan2(Q, P), delta = std::acos(K / rho);
  for (double alpha : {phi - delta, phi + delta}) {
    if (alpha > M_PI) alpha -= 2.0 * M_PI;
    if (alpha < -M_PI) alpha += 2.0 * M_PI;
    if (alpha > lo && alpha < hi) out.push_back(alpha);
  }
}

}  // namespace vcontact::volume::detail
