#include "validation/selection.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace vcontact::validation {
namespace {

// Held-out χ² of one block [a, b) after a fit without it.
// @param shared  a replayer of the record whose geometry the fold's copy shares
double foldChi2(const Replayer& shared, const NoiseLevels& noise, const dynamics::Model& fitted,
                FitOptions options, std::size_t a, std::size_t b) {
  const Dataset& dataset = shared.dataset();
  options.heldOut.assign(dataset.size(), false);
  std::fill(options.heldOut.begin() + static_cast<std::ptrdiff_t>(a),
            options.heldOut.begin() + static_cast<std::ptrdiff_t>(b), true);
  options.designPoints = 0;
  options.polished = 1;
  Replayer replayer = shared;
  const FitResult r = fit(replayer, noise, fitted, options);
  double sum = 0.0;
  for (const auto& o : r.comparison.outputs) {
    for (std::size_t i = a; i < b; ++i) {
      const double e = o.residual[static_cast<Eigen::Index>(i)] / o.sigma;
      sum += e * e;
    }
  }
  return sum;
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

// Periodogram peak of r (mean spacing dt): frequency and share of Σ (r − mean)².
std::pair<double, double> dominantFrequency(const Eigen::VectorXd& r, double dt) {
  const Eigen::Index n = r.size();
  const Eigen::VectorXd x = r.array() - r.mean();
  const double total = x.squaredNorm();
  if (n < 8 || !(total > 0.0) || !(dt > 0.0)) return {0.0, 0.0};
  double bestPower = 0.0;
  Eigen::Index bestK = 0;
  for (Eigen::Index k = 1; k < n / 2; ++k) {
    const double w = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    // X_k = Σ x_i e^{−iwi}, the phase advanced by one rotation per sample (no trig per sample)
    const std::complex<double> step = std::polar(1.0, -w);
    std::complex<double> phase = 1.0, X = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      X += x[i] * phase;
      phase *= step;
    }
    // a sinusoid's share of Σ x²: 2 |X_k|² / n (Parseval, both ± k)
    const double power = 2.0 * std::norm(X) / static_cast<double>(n);
    if (power > bestPower) {
      bestPower = power;
      bestK = k;
    }
  }
  return {static_cast<double>(bestK) / (static_cast<double>(n) * dt), bestPower / total};
}

}  // namespace

double heldOutChi2(const Dataset& dataset, const NoiseLevels& noise, const dynamics::Model& fitted,
                   const FitOptions& options) {
  const std::size_t n = dataset.size();
  std::vector<double> chi2(kCvBlocks, 0.0);
  Replayer shared(dataset);
  shared.run(fitted);  // the contact volumes, once for the five folds
  tbb::parallel_for(0, kCvBlocks, [&](int k) {
    const std::size_t a = n * static_cast<std::size_t>(k) / kCvBlocks;
    const std::size_t b = n * static_cast<std::size_t>(k + 1) / kCvBlocks;
    chi2[static_cast<std::size_t>(k)] = foldChi2(shared, noise, fitted, options, a, b);
  });
  double sum = 0.0;
  for (double c : chi2) sum += c;
  return sum;
}

std::vector<RegimeColumn> regimeColumns(const std::vector<RegimeSample>& regime) {
  std::vector<RegimeColumn> c = {{"sliding speed |v_t|", {}},
                                 {"spin ratio r_gyr|ω_n|/|v_t|", {}},
                                 {"time without tangential motion", {}},
                                 {"rest before this motion", {}},
                                 {"penetration rate δ̇_c", {}},
                                 {"normal load f_n", {}}};
  for (const auto& r : regime) {
    c[0].values.push_back(r.speed);
    c[1].values.push_back(r.spin_ratio);
    c[2].values.push_back(r.time_at_rest);
    c[3].values.push_back(r.preceding_rest);
    c[4].values.push_back(r.penetration_rate);
    c[5].values.push_back(r.load);
  }
  return c;
}

ResidualDescription describeResidual(const Dataset& dataset, const FitResult& fitted) {
  ResidualDescription d;
  const Comparison& c = fitted.comparison;
  if (c.outputs.empty() || dataset.size() < 2) return d;
  d.noiseShare = c.chi2 > 0.0 ? static_cast<double>(c.count) / c.chi2 : 1.0;
  const auto worst = std::max_element(c.outputs.begin(), c.outputs.end(),
                                      [](const auto& a, const auto& b) { return a.chi < b.chi; });
  d.output = worst->output;
  const double dt = (dataset.samples.back().t - dataset.samples.front().t) /
                    static_cast<double>(dataset.size() - 1);
  const auto [f, share] = dominantFrequency(worst->residual, dt);
  if (share >= kRingShare) {
    d.frequency = f;
    d.frequencyShare = share;
  }
  std::vector<double> magnitude;
  for (Eigen::Index i = 0; i < worst->residual.size(); ++i)
    magnitude.push_back(std::abs(worst->residual[i] / worst->sigma));
  for (const auto& col : regimeColumns(fitted.prediction.regime)) {
    const auto [lo, hi] = std::minmax_element(col.values.begin(), col.values.end());
    if (col.values.empty() || *lo == *hi) continue;  // does not vary: no correlation
    d.correlation.emplace_back(col.name, pearson(magnitude, col.values));
  }
  return d;
}

}  // namespace vcontact::validation
