#include "validation/direct_estimates.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "validation/phases.hpp"
#include "validation/rig.hpp"

namespace vcontact::validation {
namespace {

// Fewest samples an estimate is made from: below, a median or a slope is noise.
constexpr std::size_t kMinSamples = 5;
// A direct estimate is itself a measurement to a few percent (a median of noisy ratios, a slope
// of noisy logarithms): a fitted value within this fraction of the estimate beyond its range
// agrees with it. Without it the bundled `loading` record, which follows the volumetric law
// (p = 1.00045, range 1.00008 .. 1.00086 from its two halves), flagged the law's own p = 1.
constexpr double kEstimateSlack = 0.02;
// F_n below this many σ of f_z is no load to divide by (the ratio is noise).
constexpr double kLoadSigmas = 3.0;
// f_z below this many σ is left out of the log–log slope (log of noise).
constexpr double kSlopeSigmas = 5.0;
// Quantiles of the range of a ratio estimate.
constexpr double kLowQuantile = 0.1, kHighQuantile = 0.9;

std::string str(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

double quantileOf(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

bool isOutput(const Dataset& d, const std::string& name) {
  return std::find(d.outputs.begin(), d.outputs.end(), name) != d.outputs.end();
}

double sigmaOf(const NoiseLevels& noise, const std::string& o) {
  const auto it = noise.find(o);
  return it == noise.end() ? 0.0 : it->second.sigma;
}

// Least-squares slope of y on x.
double slopeOf(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0.0 ? sxy / sxx : std::nan("");
}

std::optional<DirectEstimate> friction(const Dataset& d, const NoiseLevels& noise,
                                       const Prediction& p, const std::vector<Phase>& phases) {
  const bool fx = isOutput(d, "fx"), fy = isOutput(d, "fy");
  if (!fx && !fy) return std::nullopt;
  const auto fz = d.columns.find("fz");
  const double floor = fz != d.columns.end() ? kLoadSigmas * sigmaOf(noise, "fz") : 0.0;
  std::vector<double> ratio;
  DirectEstimate e;
  e.parameter = "coulomb.mu";
  e.unit = "-";
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (phases[i] != Phase::kSliding) continue;
    const auto k = static_cast<Eigen::Index>(i);
    const double f_n = fz != d.columns.end() ? fz->second[k] : p.regime[i].load;
    if (!(f_n > floor)) continue;
    const double f_t = std::hypot(fx ? d.measured("fx")[k] : 0.0, fy ? d.measured("fy")[k] : 0.0);
    if (ratio.empty()) e.t0 = d.samples[i].t;
    e.t1 = d.samples[i].t;
    ratio.push_back(f_t / f_n);
  }
  if (ratio.size() < kMinSamples) return std::nullopt;
  e.value = quantileOf(ratio, 0.5);
  e.low = quantileOf(ratio, kLowQuantile);
  e.high = quantileOf(ratio, kHighQuantile);
  e.samples = ratio.size();
  e.method = "|F_t|/F_n over " + std::to_string(e.samples) + " sliding samples, t = " + str(e.t0) +
             " .. " + str(e.t1) + " s (F_n " +
             (fz != d.columns.end() ? "the record's fz column" : "the replayed load") + ")";
  return e;
}

std::optional<DirectEstimate> normalExponent(const Dataset& d, const NoiseLevels& noise,
                                             const Prediction& p,
                                             const std::vector<Phase>& phases) {
  const auto fz = d.columns.find("fz");
  if (fz == d.columns.end() || !isOutput(d, "fz")) return std::nullopt;
  const double floor = kSlopeSigmas * sigmaOf(noise, "fz");
  struct Point {
    double logV, logD, logF;
  };
  std::vector<Point> pts;
  DirectEstimate e;
  e.parameter = "power_law.p";
  e.unit = "-";
  for (std::size_t i = 0; i < d.size(); ++i) {
    const RegimeSample& r = p.regime[i];
    const double f = fz->second[static_cast<Eigen::Index>(i)];
    if (phases[i] != Phase::kLoading || !(f > floor) || !(r.volume > 0.0) || !(r.depth > 0.0))
      continue;
    if (pts.empty()) e.t0 = d.samples[i].t;
    e.t1 = d.samples[i].t;
    pts.push_back({std::log(r.volume), std::log(r.depth), std::log(f)});
  }
  if (pts.size() < 2 * kMinSamples) return std::nullopt;
  std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.logV < b.logV; });
  auto slopes = [&](std::size_t a, std::size_t b) {
    std::vector<double> v, dd, f;
    for (std::size_t i = a; i < b; ++i) {
      v.push_back(pts[i].logV), dd.push_back(pts[i].logD), f.push_back(pts[i].logF);
    }
    return std::pair{slopeOf(v, f), slopeOf(dd, f)};
  };
  const std::size_t n = pts.size();
  const auto [all, depthExponent] = slopes(0, n);
  const double lower = slopes(0, n / 2).first, upper = slopes(n / 2, n).first;
  if (!std::isfinite(all)) return std::nullopt;
  e.value = all;
  e.low = std::min({all, lower, upper});
  e.high = std::max({all, lower, upper});
  e.samples = n;
  e.method = "log-log slope of fz against V over " + std::to_string(n) +
             " loading samples, t = " + str(e.t0) + " .. " + str(e.t1) + " s (fz grows as d^" +
             str(depthExponent) + "; the volumetric law is V^1)";
  return e;
}

// Correlation of y with x shifted by τ samples (x(i − τ)), over the samples every shift covers.
double shiftedCorrelation(const Eigen::VectorXd& y, const Eigen::VectorXd& x, int tau,
                          Eigen::Index a, Eigen::Index b) {
  double sxy = 0.0, sxx = 0.0, syy = 0.0, mx = 0.0, my = 0.0;
  const auto m = static_cast<double>(b - a);
  for (Eigen::Index i = a; i < b; ++i) mx += x[i - tau] / m, my += y[i] / m;
  for (Eigen::Index i = a; i < b; ++i) {
    const double dx = x[i - tau] - mx, dy = y[i] - my;
    sxy += dx * dy, sxx += dx * dx, syy += dy * dy;
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

void lags(const Dataset& d, const Prediction& p, std::vector<DirectEstimate>& out) {
  const auto n = static_cast<Eigen::Index>(d.size());
  const int maxLag =
      std::min(kMaxLagSamples, static_cast<int>(kMaxLagFraction * static_cast<double>(d.size())));
  const Eigen::Index a = maxLag + 1, b = n - maxLag - 1;
  if (maxLag < 1 || b - a < static_cast<Eigen::Index>(kMinSamples)) return;
  const double dt = (d.samples.back().t - d.samples.front().t) / static_cast<double>(n - 1);
  for (const auto& o : d.outputs) {
    const Eigen::VectorXd& y = d.measured(o);
    const Eigen::VectorXd x = p.column(o);
    std::vector<double> c;
    for (int tau = -maxLag; tau <= maxLag; ++tau) c.push_back(shiftedCorrelation(y, x, tau, a, b));
    const auto best = static_cast<std::size_t>(std::max_element(c.begin(), c.end()) - c.begin());
    if (!(c[best] > 0.0)) continue;
    double shift = static_cast<double>(best) - maxLag;
    if (best > 0 && best + 1 < c.size()) {  // the parabola's vertex through the peak
      const double den = c[best - 1] - 2.0 * c[best] + c[best + 1];
      if (den < 0.0) shift += 0.5 * (c[best - 1] - c[best + 1]) / den;
    }
    DirectEstimate e;
    e.parameter = "lag " + o;
    e.unit = "s";
    e.value = shift * dt;
    e.low = e.value - dt;
    e.high = e.value + dt;
    e.samples = static_cast<std::size_t>(b - a);
    e.t0 = d.samples.front().t;
    e.t1 = d.samples.back().t;
    e.method =
        "peak of the cross-correlation of measured and fitted " + o + " (r = " + str(c[best]) + ")";
    out.push_back(std::move(e));
  }
}

// The value the model gives the estimate's parameter: its own, or the neutral value of an
// effect it lacks (power_law.p = 1 when the normal law is kv V alone: a normal force, and no
// stage that relaxes or damps it); NaN: not comparable.
double fittedValue(const dynamics::Model& m, const DirectEstimate& e) {
  const auto names = m.parameterNames();
  if (std::find(names.begin(), names.end(), e.parameter) != names.end())
    return m.parameter(e.parameter);
  using dynamics::Stage;
  if (e.parameter == "power_law.p" && m.hasStage(Stage::kNormalForce) &&
      !m.hasStage(Stage::kNormalRelaxation) && !m.hasStage(Stage::kNormalDamping))
    return 1.0;
  return std::nan("");
}

// The χ² change of each phase and output with the parameter moved to the estimate (see the
// header), as "rest +120 (t = 0 .. 0.17 s), tz +30": the parts that rise.
std::string pullOf(const Dataset& d, const FitResult& fit, const DirectEstimate& e) {
  dynamics::Model moved = fit.model;
  const auto specs = moved.parameterSpecs();
  const auto names = moved.parameterNames();
  const auto at = std::find(names.begin(), names.end(), e.parameter);
  if (at == names.end()) return {};
  const auto& spec = specs[static_cast<std::size_t>(at - names.begin())];
  moved.setParameter(e.parameter, std::clamp(e.value, spec.lower, spec.upper));
  Replayer replayer(d);
  const Prediction p = replayer.run(moved);
  if (p.nonFinite) return {};
  const std::vector<Phase> phases = phasesOf(fit.prediction.regime, phaseHalfWindow(d.size()));
  std::map<std::string, double> byPart;  // "sliding (81 samples)", "tz"
  std::map<std::string, std::size_t> count;
  for (const auto& o : fit.comparison.outputs) {
    const Eigen::VectorXd y = p.column(o.output);
    for (Eigen::Index i = 0; i < y.size(); ++i) {
      const double before = o.residual[i] / o.sigma, after = (o.measured[i] - y[i]) / o.sigma;
      const double change = after * after - before * before;
      const std::string phase(phaseName(phases[static_cast<std::size_t>(i)]));
      byPart["phase " + phase] += change;
      byPart["output " + o.output] += change;
      if (o.output == fit.comparison.outputs.front().output) ++count[phase];
    }
  }
  // largest rise first: what pulls the fit away from the estimate most
  std::vector<std::pair<double, std::string>> parts;
  for (const auto& [part, change] : byPart) parts.emplace_back(-change, part);
  std::sort(parts.begin(), parts.end());
  std::ostringstream s;
  s << "at " << e.parameter << " = " << str(e.value) << " the chi2 would change by";
  std::string pulling;
  for (const auto& [negative, part] : parts) {
    const double change = -negative;
    std::string label = part;
    if (part.rfind("phase ", 0) == 0)
      label += " (" + std::to_string(count[part.substr(6)]) + " samples)";
    s << ' ' << label << ' ' << (change >= 0.0 ? "+" : "") << str(change) << ';';
    if (change > 0.0) pulling += (pulling.empty() ? "" : ", ") + part;
  }
  s << " pulled away, most first, by: " << (pulling.empty() ? "nothing (a poor optimum)" : pulling);
  return s.str();
}

}  // namespace

std::size_t phaseHalfWindow(std::size_t samples) {
  constexpr std::size_t kMinWindowSamples = 5;  // see diagnose.cpp's moving chi
  constexpr double kWindowFraction = 0.01;
  return std::max(kMinWindowSamples,
                  static_cast<std::size_t>(kWindowFraction * static_cast<double>(samples))) /
         2;
}

std::vector<DirectEstimate> directEstimates(const Dataset& dataset, const NoiseLevels& noise,
                                            const Prediction& prediction) {
  std::vector<DirectEstimate> out;
  if (dataset.size() != prediction.regime.size()) return out;
  const std::vector<Phase> phases = phasesOf(prediction.regime, phaseHalfWindow(dataset.size()));
  if (auto e = friction(dataset, noise, prediction, phases)) out.push_back(*e);
  if (auto e = normalExponent(dataset, noise, prediction, phases)) out.push_back(*e);
  lags(dataset, prediction, out);
  return out;
}

void compareWithFit(const Dataset& dataset, FitResult& fit,
                    std::vector<DirectEstimate>& estimates) {
  for (auto& e : estimates) {
    if (e.parameter.rfind("lag ", 0) == 0) continue;  // evidence for the rig, not a parameter
    e.fitted = fittedValue(fit.model, e);
    if (std::isnan(e.fitted)) continue;
    const double slack = kEstimateSlack * std::abs(e.value);
    e.far = e.fitted < e.low - slack || e.fitted > e.high + slack;
    if (!e.far) continue;
    e.pull = pullOf(dataset, fit, e);
    std::ostringstream s;
    s << e.parameter << " = " << str(e.fitted) << " is far from its direct estimate "
      << str(e.value) << " (" << str(e.low) << " .. " << str(e.high) << ", " << e.method << ")";
    if (!e.pull.empty()) s << ": " << e.pull;
    fit.warnings.push_back(s.str());
  }
}

std::vector<DirectEstimate> estimatesBeside(const Dataset& dataset, const NoiseLevels& noise,
                                            FitResult& fit) {
  std::vector<DirectEstimate> estimates = directEstimates(dataset, noise, fit.prediction);
  compareWithFit(dataset, fit, estimates);
  return estimates;
}

}  // namespace vcontact::validation
