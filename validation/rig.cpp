#include "validation/rig.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vcontact::validation {
namespace {

std::string unitOf(const std::string& output) { return output[0] == 'f' ? "N" : "N·m"; }

std::string describe(const std::string& what, double value, const std::string& unit) {
  std::ostringstream s;
  s.precision(3);
  s << what << ' ' << value;
  if (!unit.empty() && unit != "–") s << ' ' << unit;
  return s.str();
}

RigFinding finding(std::string kind, std::string output, double value, std::string unit,
                   double drop, double n, std::string text) {
  return {std::move(kind),     std::move(output), value, std::move(unit), drop,
          -drop + std::log(n), std::move(text)};
}

void offsetAndGain(const OutputResiduals& o, double n, std::vector<RigFinding>& out) {
  const Eigen::VectorXd& r = o.residual;
  const Eigen::VectorXd& y = o.predicted;
  const double s2 = o.sigma * o.sigma;
  const double c = r.mean();
  out.push_back(finding("offset", o.output, c, unitOf(o.output),
                        static_cast<double>(r.size()) * c * c / s2, n,
                        describe(o.output + " offset", c, unitOf(o.output))));
  const double yy = y.squaredNorm();
  if (yy <= 0.0) return;
  const double ry = r.dot(y);
  out.push_back(finding("gain", o.output, 1.0 + ry / yy, "–", ry * ry / (s2 * yy), n,
                        describe(o.output + " gain", 1.0 + ry / yy, "–")));
}

// Σ over outputs of ((y_i − ŷ_{i−τ})/σ)² over i in [a, b).
double shiftedChi2(const Comparison& c, int tau, Eigen::Index a, Eigen::Index b) {
  double sum = 0.0;
  for (const auto& o : c.outputs) {
    for (Eigen::Index i = a; i < b; ++i) {
      const double e = (o.measured[i] - o.predicted[i - tau]) / o.sigma;
      sum += e * e;
    }
  }
  return sum;
}

void lag(const Dataset& d, const Comparison& c, double n, std::vector<RigFinding>& out) {
  const auto m = static_cast<Eigen::Index>(d.size());
  const int maxLag = std::min(kMaxLagSamples, static_cast<int>(kMaxLagFraction * m));
  if (maxLag < 1 || c.outputs.empty()) return;
  const Eigen::Index a = maxLag, b = m - maxLag;  // every shift covers [a, b)
  const double zero = shiftedChi2(c, 0, a, b);
  int best = 0;
  double bestChi2 = zero;
  for (int tau = -maxLag; tau <= maxLag; ++tau) {
    const double x = tau == 0 ? zero : shiftedChi2(c, tau, a, b);
    if (x < bestChi2) {
      bestChi2 = x;
      best = tau;
    }
  }
  if (best == 0) return;
  const double dt = (d.samples.back().t - d.samples.front().t) / static_cast<double>(m - 1);
  const double seconds = best * dt;
  out.push_back(finding("lag", "all", seconds, "s", zero - bestChi2, n,
                        describe("force lags motion by", seconds, "s")));
}

}  // namespace

std::vector<RigFinding> rigCandidates(const Dataset& dataset, const Comparison& fitted) {
  std::vector<RigFinding> out;
  const auto n = static_cast<double>(std::max<std::size_t>(fitted.count, 2));
  for (const auto& o : fitted.outputs) offsetAndGain(o, n, out);
  lag(dataset, fitted, n, out);
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& x, const auto& y) { return x.deltaBic < y.deltaBic; });
  return out;
}

RigFinding refineRig(const Dataset& dataset, const NoiseLevels& noise, const FitResult& fitted,
                     const RigFinding& finding, const FitOptions& options) {
  Dataset corrected = dataset;
  const auto m = static_cast<Eigen::Index>(dataset.size());
  const double dt = (dataset.samples.back().t - dataset.samples.front().t) /
                    static_cast<double>(std::max<Eigen::Index>(m - 1, 1));
  const int shift = finding.kind == "lag" ? static_cast<int>(std::lround(finding.value / dt)) : 0;
  for (const auto& o : dataset.outputs) {
    Eigen::VectorXd& y = corrected.columns.at(o);
    if (finding.kind == "offset" && o == finding.output) y.array() -= finding.value;
    if (finding.kind == "gain" && o == finding.output) y /= finding.value;
    if (finding.kind == "lag") {  // y'(i) = y(i + τ), the ends held
      const Eigen::VectorXd& src = dataset.columns.at(o);
      for (Eigen::Index i = 0; i < m; ++i)
        y[i] = src[std::clamp<Eigen::Index>(i + shift, 0, m - 1)];
    }
  }
  FitOptions own = options;
  own.designPoints = 0;  // from the optimum the uncorrected record gave
  Replayer replayer(corrected);
  const FitResult refit = fit(replayer, noise, fitted.model, own);
  const std::vector<RigFinding> again = rigCandidates(corrected, refit.comparison);
  RigFinding out = finding;
  out.remainingChi2 = refit.comparison.chi2;
  for (const auto& a : again) {
    if (a.kind != finding.kind || a.output != finding.output) continue;
    out.value = finding.kind == "gain" ? finding.value * a.value : finding.value + a.value;
    out.remainingChi2 -= a.chi2Drop;
    break;
  }
  const auto n = static_cast<double>(std::max<std::size_t>(fitted.comparison.count, 2));
  out.chi2Drop = fitted.comparison.chi2 - out.remainingChi2;
  out.deltaBic = -out.chi2Drop + std::log(n);
  const std::string what =
      finding.kind == "lag" ? "force lags motion by" : finding.output + " " + finding.kind;
  out.text = describe(what, out.value, out.unit);
  return out;
}

}  // namespace vcontact::validation
