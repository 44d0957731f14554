#pragma once
// Adaptive Gauss–Kronrod (G7/K15) quadrature of a vector-valued integrand, for the analytic
// backend's one-dimensional integrals. Global adaptive: the interval with the largest error
// is bisected until every component meets the relative tolerance (Piessens et al.,
// QUADPACK, 1983, §2.2; nodes and weights from there).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

namespace vcontact::volume {

template <int N>
struct QuadratureResult {
  Eigen::Matrix<double, N, 1> value;
  double relative_error;  ///< max over components of the error estimate / ∫|f_i|
  int evaluations;
};

namespace detail {
inline constexpr std::array<double, 8> kXgk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr std::array<double, 8> kWgk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr std::array<double, 4> kWg = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
}  // namespace detail

/// ∫_a^b f(x) dx for f: double → Eigen::Matrix<double, N, 1>.
/// @param tol relative tolerance per component, against ∫|f_i|
template <int N, class F>
QuadratureResult<N> integrateAdaptive(F&& f, double a, double b, double tol,
                                      int maxIntervals = 200) {
  using Vec = Eigen::Matrix<double, N, 1>;
  struct Piece {
    double a, b;
    Vec k15, abs15, err;
    double score;
    bool operator<(const Piece& o) const { return score < o.score; }
  };
  int evaluations = 0;
  auto rule = [&](double lo, double hi) {
    const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    Piece p{lo, hi, Vec::Zero(), Vec::Zero(), Vec::Zero(), 0.0};
    std::array<Vec, 15> fx;
    fx[7] = f(c);
    for (int j = 0; j < 7; ++j) {
      fx[j] = f(c - h * detail::kXgk[j]);
      fx[14 - j] = f(c + h * detail::kXgk[j]);
    }
    evaluations += 15;
    auto weight = [](int i) { return detail::kWgk[i <= 7 ? i : 14 - i]; };
    Vec g7 = detail::kWg[3] * fx[7];
    for (int j = 1; j < 7; j += 2) g7 += detail::kWg[j / 2] * (fx[j] + fx[14 - j]);
    for (int i = 0; i < 15; ++i) {
      p.k15 += weight(i) * fx[i];
      p.abs15 += weight(i) * fx[i].cwiseAbs();
    }
    // QUADPACK's error estimate (qk15): the raw |K15 − G7| overstates the error of K15 on
    // smooth integrands by orders of magnitude; scale it against resasc = ∫|f − mean| as
    // resasc · min(1, (200 |K15 − G7| / resasc)^{3/2}).
    const Vec mean = 0.5 * p.k15;
    Vec resasc = Vec::Zero();
    for (int i = 0; i < 15; ++i) resasc += weight(i) * (fx[i] - mean).cwiseAbs();
    const Vec raw = (p.k15 - g7).cwiseAbs() * std::abs(h);
    for (int k = 0; k < raw.size(); ++k) {
      const double rs = resasc(k) * std::abs(h);
      p.err(k) = rs > 0.0 ? rs * std::min(1.0, std::pow(200.0 * raw(k) / rs, 1.5)) : raw(k);
    }
    p.k15 *= h;
    p.abs15 *= std::abs(h);
    return p;
  };

  Piece first = rule(a, b);
  const Vec scale = first.abs15.cwiseMax(Vec::Constant(1e-300));
  auto score = [&](Piece& p) { p.score = p.err.cwiseQuotient(scale).maxCoeff(); };
  score(first);
  std::priority_queue<Piece> heap;
  heap.push(first);
  Vec total = first.k15;
  Vec err = first.err;
  int intervals = 1;
  while (err.cwiseQuotient(scale).maxCoeff() > tol && intervals < maxIntervals) {
    Piece worst = heap.top();
    heap.pop();
    const double mid = 0.5 * (worst.a + worst.b);
    Piece left = rule(worst.a, mid), right = rule(mid, worst.b);
    score(left);
    score(right);
    total += left.k15 + right.k15 - worst.k15;
    err += left.err + right.err - worst.err;
    heap.push(left);
    heap.push(right);
    ++intervals;
  }
  // Recompute the sums from the pieces: the running updates accumulate rounding.
  total.setZero();
  err.setZero();
  while (!heap.empty()) {
    total += heap.top().k15;
    err += heap.top().err;
    heap.pop();
  }
  return {total, err.cwiseQuotient(scale).maxCoeff(), evaluations};
}

/// ∫_a^b of a function that goes like (t − e)^{3/2} at a singular end e (a circular segment
/// appearing: its moments grow as its depth to the power 3/2), after t = a + (b − a)u² at a
/// singular a (t = b − (b − a)u² at a singular b; t = a + (b − a)(1 − cos πu)/2 at both), in
/// which it is smooth. `at(anchor, offset)` evaluates at t = anchor + offset, the offset from
/// the nearer singular end, so that an integrand can keep the digits of the small offset.
template <int N, class F>
QuadratureResult<N> integrateSingularEnds(F&& at, double a, double b, bool singA, bool singB,
                                          double tol) {
  using Vec = Eigen::Matrix<double, N, 1>;
  const double len = b - a;
  if (singA && singB) {
    const auto f = [&](double u) -> Vec {
      const double jac = 0.5 * M_PI * len * std::sin(M_PI * u);
      return (u < 0.5 ? at(a, len * std::pow(std::sin(0.5 * M_PI * u), 2))
                      : at(b, -len * std::pow(std::cos(0.5 * M_PI * u), 2))) *
             jac;
    };
    return integrateAdaptive<N>(f, 0.0, 1.0, tol);
  }
  const auto f = [&](double u) -> Vec {
    return (singA ? at(a, len * u * u) : at(b, -len * u * u)) * (2.0 * len * u);
  };
  return integrateAdaptive<N>(f, 0.0, 1.0, tol);
}

}  // namespace vcontact::volume
