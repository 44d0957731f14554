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

// "fx offset 0.21 N", "fz gain 1.05", "force lags motion by 0.01 s",
// "payload inertia -1 × (m·a, I·α)".
std::string textOf(const std::string& kind, const std::string& output, double value,
                   const std::string& unit) {
  if (kind == "lag")
    return describe(output == "all" ? "force lags motion by" : output + " lags motion by", value,
                    unit);
  if (kind == "inertia") return describe("payload inertia", value, "× (m·a, I·α)");
  return describe(output + " " + kind, value, unit);
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

// x at the fractional index u by Catmull–Rom interpolation (cubic, exact for quadratics),
// the index clamped to the record.
double at(const Eigen::VectorXd& x, double u) {
  const Eigen::Index m = x.size();
  u = std::clamp(u, 0.0, static_cast<double>(m - 1));
  const auto i = std::min(static_cast<Eigen::Index>(u), m - 2);
  const double f = u - static_cast<double>(i);
  auto get = [&](Eigen::Index k) { return x[std::clamp<Eigen::Index>(k, 0, m - 1)]; };
  const double p0 = get(i - 1), p1 = get(i), p2 = get(i + 1), p3 = get(i + 2);
  return p1 + 0.5 * f *
                  (p2 - p0 +
                   f * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + f * (3.0 * (p1 - p2) + p3 - p0)));
}

// Σ over outputs (`only`, or all when "all") of ((y_i − ŷ(i − τ))/σ)² over i in [a, b), τ in
// samples (fractional).
double shiftedChi2(const Comparison& c, double tau, Eigen::Index a, Eigen::Index b,
                   const std::string& only) {
  double sum = 0.0;
  for (const auto& o : c.outputs) {
    if (only != "all" && o.output != only) continue;
    for (Eigen::Index i = a; i < b; ++i) {
      const double e = (o.measured[i] - at(o.predicted, static_cast<double>(i) - tau)) / o.sigma;
      sum += e * e;
    }
  }
  return sum;
}

// The best whole-sample shift, then golden-section search for the fractional one within a
// sample either side (χ²(τ) of a smooth record is unimodal there).
double bestShift(const Comparison& c, int maxLag, Eigen::Index a, Eigen::Index b,
                 const std::string& only) {
  int best = 0;
  double bestChi2 = shiftedChi2(c, 0.0, a, b, only);
  for (int tau = -maxLag; tau <= maxLag; ++tau) {
    const double x = tau == 0 ? bestChi2 : shiftedChi2(c, tau, a, b, only);
    if (x < bestChi2) {
      bestChi2 = x;
      best = tau;
    }
  }
  if (best == 0) return 0.0;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = best - 1.0, hi = best + 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = shiftedChi2(c, x1, a, b, only), f2 = shiftedChi2(c, x2, a, b, only);
  while (hi - lo > 1e-3) {  // a thousandth of a sample
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = shiftedChi2(c, x1, a, b, only);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = shiftedChi2(c, x2, a, b, only);
    }
  }
  const double tau = 0.5 * (lo + hi);
  return shiftedChi2(c, tau, a, b, only) < bestChi2 ? tau : static_cast<double>(best);
}

double meanStep(const Dataset& d) {
  const auto m = static_cast<double>(std::max<std::size_t>(d.size(), 2));
  return (d.samples.back().t - d.samples.front().t) / (m - 1.0);
}

int maxLagOf(const Dataset& d) {
  return std::min(kMaxLagSamples,
                  static_cast<int>(kMaxLagFraction * static_cast<double>(d.size())));
}

void lag(const Dataset& d, const Comparison& c, double n, std::vector<RigFinding>& out) {
  const auto m = static_cast<Eigen::Index>(d.size());
  const int maxLag = maxLagOf(d);
  if (maxLag < 1 || c.outputs.empty()) return;
  const Eigen::Index a = maxLag + 1, b = m - maxLag - 1;  // every shift covers [a, b)
  if (b <= a) return;
  // one lag shared by every output, and, with several outputs, one lag of each alone (a
  // channel's own delay: a filter, a clock of its own)
  std::vector<std::string> which{"all"};
  for (const auto& o : c.outputs) {
    if (c.outputs.size() > 1) which.push_back(o.output);
  }
  for (const auto& only : which) {
    const double tau = bestShift(c, maxLag, a, b, only);
    if (tau == 0.0) continue;
    const double seconds = tau * meanStep(d);
    out.push_back(finding("lag", only, seconds, "s",
                          shiftedChi2(c, 0.0, a, b, only) - shiftedChi2(c, tau, a, b, only), n,
                          textOf("lag", only, seconds, "s")));
  }
}

// k of y = ŷ + k w (w the payload's inertial wrench, every output at once), for each
// differentiation half-width; the one that removes the most χ² is kept (see the header).
void inertia(const Dataset& d, const Comparison& c, double n, std::vector<RigFinding>& out) {
  if (!d.inertia || d.size() < 3) return;
  RigFinding best;
  for (int h : kInertiaHalfWidths) {
    if (h > 1 && 20 * h + 1 > static_cast<int>(d.size())) break;
    const std::map<std::string, Eigen::VectorXd> w = inertialWrench(d, h);
    double rw = 0.0, ww = 0.0;
    for (const auto& o : c.outputs) {
      const Eigen::VectorXd& x = w.at(o.output);
      rw += o.residual.dot(x) / (o.sigma * o.sigma);
      ww += x.squaredNorm() / (o.sigma * o.sigma);
    }
    if (!(ww > 0.0) || rw * rw / ww <= best.chi2Drop) continue;
    best = finding("inertia", "all", rw / ww, "–", rw * rw / ww, n,
                   textOf("inertia", "all", rw / ww, "–"));
    best.halfWidth = h;
  }
  if (best.chi2Drop > 0.0) out.push_back(best);
}

}  // namespace

std::vector<RigFinding> rigCandidates(const Dataset& dataset, const Comparison& fitted) {
  std::vector<RigFinding> out;
  const auto n = static_cast<double>(std::max<std::size_t>(fitted.count, 2));
  for (const auto& o : fitted.outputs) offsetAndGain(o, n, out);
  lag(dataset, fitted, n, out);
  inertia(dataset, fitted, n, out);
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& x, const auto& y) { return x.deltaBic < y.deltaBic; });
  return out;
}

namespace {

// The record with `finding` taken out: offset subtracted, gain divided out, the inertial
// wrench subtracted, or the force columns shifted back by the lag (interpolated, ends held).
Dataset corrected(const Dataset& dataset, const RigFinding& finding) {
  Dataset out = dataset;
  const double shift = finding.kind == "lag" ? finding.value / meanStep(dataset) : 0.0;
  const std::map<std::string, Eigen::VectorXd> w = finding.kind == "inertia"
                                                       ? inertialWrench(dataset, finding.halfWidth)
                                                       : std::map<std::string, Eigen::VectorXd>{};
  for (const auto& o : dataset.outputs) {
    Eigen::VectorXd& y = out.columns.at(o);
    if (finding.kind == "offset" && o == finding.output) y.array() -= finding.value;
    if (finding.kind == "gain" && o == finding.output) y /= finding.value;
    if (finding.kind == "inertia") y -= finding.value * w.at(o);
    if (finding.kind == "lag" && (finding.output == "all" || o == finding.output)) {
      // y'(i) = y(i + τ)
      const Eigen::VectorXd& src = dataset.columns.at(o);
      for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = at(src, static_cast<double>(i) + shift);
    }
  }
  return out;
}

}  // namespace

RigFinding refineRig(const Dataset& dataset, const NoiseLevels& noise, const FitResult& fitted,
                     const RigFinding& finding, const FitOptions& options) {
  const Dataset fixedRecord = corrected(dataset, finding);
  FitOptions own = options;
  own.designPoints = 0;  // from the optimum the uncorrected record gave
  Replayer replayer(fixedRecord);
  const FitResult refit = fit(replayer, noise, fitted.model, own);
  const std::vector<RigFinding> again = rigCandidates(fixedRecord, refit.comparison);
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
  out.text = textOf(out.kind, out.output, out.value, out.unit);
  return out;
}

namespace {

// dx/dt at sample i: the least-squares slope of x over the samples within ±h of i (cut at the
// record's ends); for h = 1 on an even grid, the central difference.
Eigen::Vector3d slope(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& x,
                      std::size_t i, int h) {
  const std::size_t a = i >= static_cast<std::size_t>(h) ? i - static_cast<std::size_t>(h) : 0;
  const std::size_t b = std::min(t.size() - 1, i + static_cast<std::size_t>(h));
  double tm = 0.0;
  Eigen::Vector3d xm = Eigen::Vector3d::Zero();
  for (std::size_t j = a; j <= b; ++j) tm += t[j], xm += x[j];
  const auto k = static_cast<double>(b - a + 1);
  tm /= k, xm /= k;
  double tt = 0.0;
  Eigen::Vector3d tx = Eigen::Vector3d::Zero();
  for (std::size_t j = a; j <= b; ++j)
    tt += (t[j] - tm) * (t[j] - tm), tx += (t[j] - tm) * (x[j] - xm);
  return tx / tt;
}

}  // namespace

std::map<std::string, Eigen::VectorXd> inertialWrench(const Dataset& d, int halfWidth) {
  const std::size_t m = d.size();
  const PayloadInertia p = d.inertia.value_or(PayloadInertia{});
  std::vector<double> t(m);
  std::vector<Eigen::Vector3d> vc(m), w(m), rc(m);
  for (std::size_t i = 0; i < m; ++i) {
    const Sample& s = d.samples[i];
    t[i] = s.t;
    rc[i] = s.X_BA.linear() * p.com;
    vc[i] = s.v_BA + s.w_BA.cross(rc[i]);
    w[i] = s.w_BA;
  }
  std::map<std::string, Eigen::VectorXd> out;
  for (const auto& c : kWrenchColumns) out[c] = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector3d ac = slope(t, vc, i, halfWidth), alpha = slope(t, w, i, halfWidth);
    const Eigen::Matrix3d& R = d.samples[i].X_BA.linear();
    const Eigen::Matrix3d I = R * p.inertia * R.transpose();
    const Eigen::Vector3d f = p.mass * ac;
    const Eigen::Vector3d tau = I * alpha + w[i].cross(I * w[i]) + rc[i].cross(f);
    for (int k = 0; k < 3; ++k) {
      out[kWrenchColumns[k]][static_cast<Eigen::Index>(i)] = f[k];
      out[kWrenchColumns[k + 3]][static_cast<Eigen::Index>(i)] = tau[k];
    }
  }
  return out;
}

}  // namespace vcontact::validation
