#include "validation/residuals.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vcontact::validation {
namespace {

// MAD → σ for a normal distribution: 1/Φ⁻¹(3/4).
constexpr double kMadToSigma = 1.4826;
// A noiseless column (synthetic, or printed with all digits) estimates σ̂ = 0; floor it at
// the relative resolution of a 12-digit CSV cell so that chi stays finite.
constexpr double kRelativeSigmaFloor = 1e-12;

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

double estimateNoise(const Eigen::VectorXd& y) {
  assert(y.size() >= 3);
  std::vector<double> d;
  for (Eigen::Index i = 1; i + 1 < y.size(); ++i) d.push_back(y[i + 1] - 2.0 * y[i] + y[i - 1]);
  const double m = median(d);
  for (double& v : d) v = std::abs(v - m);
  const double sigma = kMadToSigma * median(d) / std::sqrt(6.0);
  const double floor = kRelativeSigmaFloor * std::max(y.cwiseAbs().maxCoeff(), 1.0);
  return std::max(sigma, floor);
}

NoiseLevels noiseLevels(const Dataset& dataset) {
  NoiseLevels levels;
  for (const auto& o : dataset.outputs) {
    const auto it = dataset.noise.find(o);
    levels[o] = it != dataset.noise.end() ? NoiseLevel{it->second, false}
                                          : NoiseLevel{estimateNoise(dataset.measured(o)), true};
  }
  return levels;
}

Comparison compare(const Dataset& dataset, const Prediction& prediction, const NoiseLevels& noise) {
  Comparison c;
  for (const auto& o : dataset.outputs) {
    OutputResiduals r;
    r.output = o;
    r.measured = dataset.measured(o);
    r.predicted = prediction.column(o);
    r.residual = r.measured - r.predicted;
    r.sigma = noise.at(o).sigma;
    const double n = static_cast<double>(r.residual.size());
    r.rms = std::sqrt(r.residual.squaredNorm() / n);
    const double chi2 = (r.residual / r.sigma).squaredNorm();
    r.chi = std::sqrt(chi2 / n);
    c.chi2 += chi2;
    c.count += static_cast<std::size_t>(r.residual.size());
    c.outputs.push_back(std::move(r));
  }
  c.chi = std::sqrt(c.chi2 / static_cast<double>(c.count));
  return c;
}

double bic(const Comparison& c, std::size_t k) {
  return c.chi2 + static_cast<double>(k) * std::log(static_cast<double>(c.count));
}

}  // namespace vcontact::validation
