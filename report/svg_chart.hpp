#pragma once
// Small, dependency-free SVG charts for the self-contained HTML report: line charts (with
// shaded windows), scatter plots and bar charts, with "nice" axis ticks. Each chart is one
// <svg class="chart"> element with a title, axis labels and a legend, sized in CSS pixels.

#include <string>
#include <vector>

namespace vcontact::report {

struct Series {
  std::string label;
  std::vector<double> x, y;
  std::string colour;    ///< CSS colour; empty picks from the palette
  bool markers = false;  ///< draw points instead of a line
};

/// An x-interval shaded behind the data (e.g. a window where the model fails).
struct Window {
  double x0, x1;
  std::string label;
};

struct Axes {
  std::string title, xLabel, yLabel;
  int width = 720, height = 300;  ///< px
  bool integerX = false;          ///< x is a count (stage 1, 2, …): whole-number ticks only
};

/// Line (or marker) chart of several series against shared axes.
std::string lineChart(const Axes& axes, const std::vector<Series>& series,
                      const std::vector<Window>& windows = {});

/// Vertical bars, one per label, with the value printed above each.
std::string barChart(const Axes& axes, const std::vector<std::string>& labels,
                     const std::vector<double>& values, double referenceLine = 0.0,
                     const std::string& referenceLabel = "");

/// Tick positions covering [lo, hi] with about `target` steps of 1, 2 or 5 × 10^k.
std::vector<double> niceTicks(double lo, double hi, int target = 5);

/// Escapes &, <, >, " for text and attributes.
std::string escapeXml(const std::string& text);

}  // namespace vcontact::report
