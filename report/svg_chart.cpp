#include "report/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace vcontact::report {
namespace {

const char* const kPalette[] = {"#1f5fa8", "#d1495b", "#2e8540", "#e08e0b", "#6a4c93", "#00798c"};

// Margins leave room for tick labels (left, bottom), the title (top) and the legend.
constexpr int kLeft = 70, kRight = 20, kTop = 34, kBottom = 46;
// x ticks are planned this far apart (px), so that labels such as "0.125" never touch;
// niceTicks' rounding to 1, 2, 5 × 10^k can bring them to about two thirds of it.
constexpr int kTickSpacing = 70;
// Legend entries: a swatch and a label per slot, as many slots to a row as fit the plot.
constexpr int kLegendSlot = 130, kLegendRow = 14;
// A line series with at most this many points also marks each point (one point draws no line).
constexpr std::size_t kMarkedLine = 20;

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void finish() {
    if (!(lo <= hi)) lo = 0, hi = 1;
    if (hi - lo <= 1e-300 * std::max(1.0, std::abs(hi))) {
      const double pad = lo == 0 ? 1.0 : 0.05 * std::abs(lo);
      lo -= pad;
      hi += pad;
    }
  }
};

std::string fmt(double v) {
  std::ostringstream os;
  os << std::setprecision(4) << v;
  return os.str();
}

struct Frame {
  Axes axes;
  Range xr, yr;
  double px(double x) const {
    return kLeft + (x - xr.lo) / (xr.hi - xr.lo) * (axes.width - kLeft - kRight);
  }
  double py(double y) const {
    return axes.height - kBottom - (y - yr.lo) / (yr.hi - yr.lo) * (axes.height - kTop - kBottom);
  }
};

void openSvg(std::ostringstream& os, const Axes& a) {
  os << "<svg class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << a.width
     << "\" height=\"" << a.height << "\" viewBox=\"0 0 " << a.width << ' ' << a.height
     << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
     << "<title>" << escapeXml(a.title) << "</title>\n"
     << "<text x=\"" << a.width / 2
     << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\" "
        "font-weight=\"bold\">"
     << escapeXml(a.title) << "</text>\n";
}

void drawAxes(std::ostringstream& os, const Frame& f, bool xTicks) {
  const Axes& a = f.axes;
  const double x0 = kLeft, x1 = a.width - kRight, y0 = a.height - kBottom, y1 = kTop;
  os << "<rect x=\"" << x0 << "\" y=\"" << y1 << "\" width=\"" << x1 - x0 << "\" height=\""
     << y0 - y1 << "\" fill=\"none\" stroke=\"#888\"/>\n";
  for (double t : niceTicks(f.yr.lo, f.yr.hi)) {
    const double y = f.py(t);
    os << "<line x1=\"" << x0 << "\" x2=\"" << x1 << "\" y1=\"" << y << "\" y2=\"" << y
       << "\" stroke=\"#eee\"/><text x=\"" << x0 - 4 << "\" y=\"" << y + 4
       << "\" text-anchor=\"end\">" << fmt(t) << "</text>\n";
  }
  if (xTicks) {
    const int target = std::clamp((a.width - kLeft - kRight) / kTickSpacing, 2, 8);
    for (double t : niceTicks(f.xr.lo, f.xr.hi, target)) {
      if (a.integerX && t != std::round(t)) continue;
      const double x = f.px(t);
      os << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << y0 << "\" y2=\"" << y0 + 4
         << "\" stroke=\"#888\"/><text x=\"" << x << "\" y=\"" << y0 + 16
         << "\" text-anchor=\"middle\">" << fmt(t) << "</text>\n";
    }
  }
  os << "<text x=\"" << (x0 + x1) / 2 << "\" y=\"" << a.height - 8 << "\" text-anchor=\"middle\">"
     << escapeXml(a.xLabel) << "</text>\n"
     << "<text transform=\"translate(14," << (y0 + y1) / 2
     << ") rotate(-90)\" text-anchor=\"middle\">" << escapeXml(a.yLabel) << "</text>\n";
}

}  // namespace

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double frac = raw / mag;
  const double step = (frac < 1.5 ? 1 : frac < 3.5 ? 2 : frac < 7.5 ? 5 : 10) * mag;
  // Integer multiples of the step, with a little slack so that a bound that is itself a
  // multiple (−0.3 / 0.1 = −2.9999…) is kept.
  std::vector<double> ticks;
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  // A range narrow against its magnitude (two stages whose chi agree to 1e-15) puts the
  // multiples beyond 2^53, where k + 1 == k: the ends are the only honest ticks then.
  if (!(std::abs(first) < 1e12 && std::abs(last) < 1e12 && last - first <= 1000)) return {lo, hi};
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k == 0.0 ? 0.0 : k * step);
  return ticks;
}

std::string lineChart(const Axes& axes, const std::vector<Series>& series,
                      const std::vector<Window>& windows) {
  Frame f{axes, {}, {}};
  for (const auto& s : series) {
    for (double x : s.x) f.xr.add(x);
    for (double y : s.y) f.yr.add(y);
  }
  f.xr.finish();
  f.yr.finish();
  if (axes.integerX) {  // room at the ends: the few points are marks, not on the frame
    f.xr.lo -= 0.5, f.xr.hi += 0.5;
    const double pad = 0.1 * (f.yr.hi - f.yr.lo);
    f.yr.lo -= pad, f.yr.hi += pad;
  }
  std::ostringstream os;
  os << std::setprecision(6);
  openSvg(os, axes);
  for (const auto& w : windows) {
    const double a = f.px(std::max(w.x0, f.xr.lo)), b = f.px(std::min(w.x1, f.xr.hi));
    os << "<rect class=\"window\" x=\"" << a << "\" y=\"" << kTop << "\" width=\""
       << std::max(1.0, b - a) << "\" height=\"" << axes.height - kTop - kBottom
       << "\" fill=\"#f6c0c0\" opacity=\"0.6\"><title>" << escapeXml(w.label)
       << "</title></rect>\n";
  }
  drawAxes(os, f, true);
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const std::string colour = s.colour.empty() ? kPalette[k % 6] : s.colour;
    const std::size_t n = std::min(s.x.size(), s.y.size());
    // Long series are thinned to about two points per horizontal pixel.
    const std::size_t stride =
        std::max<std::size_t>(1, n / (2 * static_cast<std::size_t>(axes.width)));
    if (s.markers || n <= kMarkedLine) {
      os << "<g class=\"" << (s.markers ? "series" : "marks") << "\" fill=\"" << colour
         << "\" fill-opacity=\"" << (s.markers ? 0.6 : 1.0) << "\">";
      for (std::size_t i = 0; i < n; i += stride) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        os << "<circle cx=\"" << f.px(s.x[i]) << "\" cy=\"" << f.py(s.y[i]) << "\" r=\""
           << (s.markers ? 1.8 : 3.5) << "\"/>";
      }
      os << "</g>\n";
    }
    if (!s.markers) {
      os << "<polyline class=\"series\" fill=\"none\" stroke=\"" << colour
         << "\" stroke-width=\"1.3\" points=\"";
      for (std::size_t i = 0; i < n; i += stride) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        os << f.px(s.x[i]) << ',' << f.py(s.y[i]) << ' ';
      }
      os << "\"/>\n";
    }
    const std::size_t perRow =
        static_cast<std::size_t>(std::max(1, (axes.width - kLeft - kRight - 8) / kLegendSlot));
    const auto col = static_cast<int>(k % perRow), row = static_cast<int>(k / perRow);
    os << "<rect x=\"" << kLeft + 8 + kLegendSlot * col << "\" y=\"" << kTop + 6 + kLegendRow * row
       << "\" width=\"10\" height=\"10\" fill=\"" << colour << "\"/><text x=\""
       << kLeft + 22 + kLegendSlot * col << "\" y=\"" << kTop + 15 + kLegendRow * row << "\">"
       << escapeXml(s.label) << "</text>\n";
  }
  os << "</svg>\n";
  return os.str();
}

std::string barChart(const Axes& axes, const std::vector<std::string>& labels,
                     const std::vector<double>& values, double referenceLine,
                     const std::string& referenceLabel) {
  Frame f{axes, {}, {}};
  f.xr.lo = 0;
  f.xr.hi = static_cast<double>(std::max<std::size_t>(1, labels.size()));
  f.yr.add(0.0);
  for (double v : values) f.yr.add(v);
  if (referenceLine != 0.0) f.yr.add(referenceLine);
  f.yr.hi *= 1.12;  // room for the value labels
  f.yr.finish();
  std::ostringstream os;
  os << std::setprecision(6);
  openSvg(os, axes);
  drawAxes(os, f, false);
  const double slot = (axes.width - kLeft - kRight) / f.xr.hi;
  for (std::size_t i = 0; i < labels.size() && i < values.size(); ++i) {
    const double x = kLeft + slot * (static_cast<double>(i) + 0.15);
    const double top = f.py(std::max(values[i], 0.0)), base = f.py(std::min(values[i], 0.0));
    os << "<rect class=\"bar\" x=\"" << x << "\" y=\"" << top << "\" width=\"" << 0.7 * slot
       << "\" height=\"" << std::max(0.5, base - top) << "\" fill=\"" << kPalette[i % 6]
       << "\"><title>" << escapeXml(labels[i]) << ": " << fmt(values[i]) << "</title></rect>\n"
       << "<text x=\"" << x + 0.35 * slot << "\" y=\"" << top - 4 << "\" text-anchor=\"middle\">"
       << fmt(values[i]) << "</text>\n"
       << "<text x=\"" << x + 0.35 * slot << "\" y=\"" << axes.height - kBottom + 16
       << "\" text-anchor=\"middle\">" << escapeXml(labels[i]) << "</text>\n";
  }
  if (referenceLine != 0.0) {
    const double y = f.py(referenceLine);
    os << "<line x1=\"" << kLeft << "\" x2=\"" << axes.width - kRight << "\" y1=\"" << y
       << "\" y2=\"" << y << "\" stroke=\"#333\" stroke-dasharray=\"4 3\"/><text x=\""
       << axes.width - kRight - 4 << "\" y=\"" << y - 4 << "\" text-anchor=\"end\">"
       << escapeXml(referenceLabel) << "</text>\n";
  }
  os << "</svg>\n";
  return os.str();
}

}  // namespace vcontact::report
