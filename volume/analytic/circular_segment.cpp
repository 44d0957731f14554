#include "volume/analytic/circular_segment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/error.hpp"

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

// The four series' coefficients Σ_k a_k k^{2j} (exact in binary), and Σ_k |a_k| k^{2j},
// which bounds them.
struct SeriesTable {
  std::array<std::array<double, kSeriesTerms>, 4> m{}, bound{};
};

SeriesTable seriesTable() {
  SeriesTable t;
  const std::array<TrigPoly, 4> polys = {kSin2, kOmcSin2, kOmc2Sin2, kSin4};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < kSeriesTerms; ++j) {
      t.m[i][j] = j == 0 ? polys[i][0] : 0.0;
      t.bound[i][j] = j == 0 ? std::abs(polys[i][0]) : 0.0;
      for (int k = 1; k < kTrigTerms; ++k) {
        const double kk = std::pow(static_cast<double>(k), 2 * j);
        t.m[i][j] += polys[i][k] * kk;
        t.bound[i][j] += std::abs(polys[i][k]) * kk;
      }
    }
  return t;
}

// The four series at once, sharing the powers θ^{2j+1}/(2j+1)!, and no further than their
// terms can change a sum: from the third term on each is at most 9/20 of the one before
// (|m_{j+1}| ≤ 16 bound_j, 16θ² < 9 below θ = 0.75, (2j + 2)(2j + 3) ≥ 20), so once the next
// one's bound is below 2⁻⁶⁰ of every sum, none of the rest is half an ulp of it and the sums
// are those of all kSeriesTerms terms, bit for bit.
std::array<double, 4> integrateSeries(double theta) {
  static const SeriesTable t = seriesTable();
  std::array<double, 4> sum{};
  double power = theta;  // θ^{2j+1}/(2j+1)!
  for (int j = 0; j < kSeriesTerms; ++j) {
    const double signedPower = j % 2 == 0 ? power : -power;
    for (int i = 0; i < 4; ++i) sum[i] += signedPower * t.m[i][j];
    power *= theta * theta / ((2.0 * j + 2.0) * (2.0 * j + 3.0));
    if (j >= 1 && j + 1 < kSeriesTerms) {
      bool negligible = true;
      for (int i = 0; i < 4; ++i)
        negligible = negligible && power * t.bound[i][j + 1] < 0x1p-60 * std::abs(sum[i]);
      if (negligible) break;
    }
  }
  return sum;
}

// The same four series by Horner's rule in θ², with the coefficients (−1)^j m_j/(2j+1)!
// and no more terms than θ needs: n terms leave at most 2·4^{2n} θ^{2n+1}/(2n+1)! (|m_j| ≤ 2·16^j),
// which is below 2⁻⁵⁶ of the smallest of the four sums (θ⁷/28, that of (1 − cos φ)² sin²φ)
// for θ up to θ_n. Not bit for bit the series above: for the curved pieces, which have no
// earlier results to keep.
struct HornerTable {
  std::array<std::array<double, kSeriesTerms>, 4> c{};
  std::array<double, kSeriesTerms + 1> upTo{};  // θ_n: n terms suffice below it
};

HornerTable hornerTable() {
  const SeriesTable t = seriesTable();
  HornerTable h;
  double factorial = 1.0;  // (2j + 1)!
  for (int j = 0; j < kSeriesTerms; ++j) {
    if (j > 0) factorial *= (2.0 * j) * (2.0 * j + 1.0);
    for (int i = 0; i < 4; ++i) h.c[i][j] = (j % 2 == 0 ? 1.0 : -1.0) * t.m[i][j] / factorial;
  }
  double f = 1.0;  // (2n + 1)!
  for (int n = 1; n <= kSeriesTerms; ++n) {
    f *= (2.0 * n) * (2.0 * n + 1.0);
    h.upTo[n] =
        n < 4 ? 0.0
              : std::pow(std::ldexp(f, -56) / (56.0 * std::pow(4.0, 2 * n)), 1.0 / (2.0 * n - 6.0));
  }
  h.upTo[kSeriesTerms] = kSeriesBelow;  // the design of kSeriesTerms
  return h;
}

std::array<double, 4> integrateSeriesHorner(double theta) {
  static const HornerTable h = hornerTable();
  int n = 4;
  while (n < kSeriesTerms && theta > h.upTo[n]) ++n;
  const double t2 = theta * theta;
  std::array<double, 4> sum{};
  for (int j = n - 1; j >= 0; --j)
    for (int i = 0; i < 4; ++i) sum[i] = sum[i] * t2 + h.c[i][j];
  for (double& x : sum) x *= theta;
  return sum;
}

}  // namespace

namespace {
Segment segmentMoments(double R, double theta, bool horner) {
  double i20, i21, i22, i40;
  if (theta < kSeriesBelow) {
    const std::array<double, 4> i = horner ? integrateSeriesHorner(theta) : integrateSeries(theta);
    i20 = i[0];
    i21 = i[1];
    i22 = i[2];
    i40 = i[3];
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

}  // namespace

Segment segmentMoments(double R, double theta) { return segmentMoments(R, theta, false); }

Segment shallowSegmentMoments(double R, double theta) { return segmentMoments(R, theta, true); }

/// θ with d = R(1 − cos θ), accurate for small d; d is clamped to [0, 2R].
double segmentAngle(double R, double d) {
  const double r = std::clamp(d / (2.0 * R), 0.0, 1.0);
  return 2.0 * std::asin(std::sqrt(r));
}

/// ∫_0^θ |A cos φ + B| dφ.
double absCosIntegral(double A, double B, double theta, double sinTheta, double cosTheta) {
  const double atTheta = A * sinTheta + B * theta;  // the antiderivative A sin φ + B φ
  // A cos φ + B changes sign at φ₀ = acos(−B/A), before θ when cos θ < −B/A
  if (A != 0.0 && std::abs(B) < std::abs(A) && cosTheta < -B / A) {
    const double phi0 = std::acos(-B / A);
    const double at0 = A * std::sqrt(1.0 - (B / A) * (B / A)) + B * phi0;
    return std::abs(at0) + std::abs(atTheta - at0);
  }
  return std::abs(atTheta);
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

double linearSlope(const ProfilePiece& p) { return (p.r1 - p.r0) / (p.z1 - p.z0); }

PieceAt pieceAt(const ProfilePiece& p, double t) {
  switch (p.kind) {
    case ProfilePiece::Kind::kConstant:
      return {t, p.r0, 1.0, 0.0};
    case ProfilePiece::Kind::kLinear: {
      const double k = linearSlope(p);
      return {t, p.r0 + k * (t - p.z0), 1.0, k};
    }
    case ProfilePiece::Kind::kArc:
      break;
  }
  const double c = std::cos(t), s = std::sin(t);
  return {p.z_c + p.a * s, std::max(0.0, p.rho_c + p.sign * p.a * c), p.a * c, -p.sign * p.a * s};
}

namespace {

double arcAngle(const ProfilePiece& p, double zeta) {
  return std::asin(std::clamp((zeta - p.z_c) / p.a, -1.0, 1.0));
}

}  // namespace

double parameterOf(const ProfilePiece& p, double zeta) {
  return p.kind == ProfilePiece::Kind::kArc ? arcAngle(p, zeta) : zeta;
}

void checkProfile(const RevolutionProfile& profile, const char* where) {
  if (profile.empty()) throw InputError(where, "the profile has no piece");
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const ProfilePiece& p = profile[i];
    if (!(p.z1 > p.z0) || (i > 0 && p.z0 != profile[i - 1].z1))
      throw InputError(where, "piece " + std::to_string(i) +
                                  " is empty or does not begin where the one before it ends");
  }
}

}  // namespace vcontact::volume::detail

namespace vcontact::volume {

double profileRadius(const ProfilePiece& piece, double zeta) {
  return detail::pieceAt(piece, detail::parameterOf(piece, std::clamp(zeta, piece.z0, piece.z1))).r;
}

double largestRadius(const RevolutionProfile& profile) {
  double r = 0.0;
  for (const ProfilePiece& p : profile) {
    r = std::max({r, profileRadius(p, p.z0), profileRadius(p, p.z1)});
    if (p.kind == ProfilePiece::Kind::kArc && p.z0 <= p.z_c && p.z_c <= p.z1)
      r = std::max(r, profileRadius(p, p.z_c));
  }
  return r;
}

}  // namespace vcontact::volume
