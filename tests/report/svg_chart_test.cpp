// The report's SVG charts: tick choice, escaping, one drawn element per series and window,
// non-finite samples skipped rather than written as "nan".

#include "report/svg_chart.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vcontact::report {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(SvgChart, NiceTicksAreRoundAndCoverTheRange) {
  EXPECT_EQ(niceTicks(0, 10), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const std::vector<double> expected = {-0.3, -0.2, -0.1, 0, 0.1, 0.2, 0.3};
  const auto ticks = niceTicks(-0.3, 0.3, 6);
  ASSERT_EQ(ticks.size(), expected.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-15);
  const auto t = niceTicks(1e-6, 7e-6);
  EXPECT_NEAR(t.front(), 1e-6, 1e-18);
  EXPECT_NEAR(t.back(), 7e-6, 1e-18);
}

// Two stages whose log10 chi agree to the last bits (diagnose of drive from the bare model):
// the multiples of the step lie beyond 2^53, where counting them never ended.
TEST(SvgChart, NiceTicksOfARangeNarrowAgainstItsMagnitudeAreItsEnds) {
  const double lo = 2.1875, hi = std::nextafter(std::nextafter(lo, 3.0), 3.0);
  EXPECT_EQ(niceTicks(lo, hi), (std::vector<double>{lo, hi}));
}

TEST(SvgChart, EscapesText) {
  EXPECT_EQ(escapeXml("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
}

TEST(SvgChart, LineChartDrawsEverySeriesAndWindow) {
  Series a{"measured", {0, 1, 2, 3}, {0, 1, 4, 9}, "", false};
  Series b{"model <fit>", {0, 1, 2, 3}, {0, 1, NAN, 9}, "", true};
  const std::string svg =
      lineChart({"fx", "t [s]", "f [N]", 600, 240}, {a, b}, {{1.0, 2.0, "chi 7"}});
  EXPECT_EQ(count(svg, "<svg class=\"chart\""), 1u);
  EXPECT_EQ(count(svg, "class=\"series\""), 2u);
  EXPECT_EQ(count(svg, "class=\"window\""), 1u);
  // the marker series' 3 finite points, and the short line's 4 points marked on it
  EXPECT_EQ(count(svg, "<circle"), 3u + 4u) << "the NaN sample is skipped";
  EXPECT_EQ(count(svg, "class=\"marks\""), 1u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_NE(svg.find("model &lt;fit&gt;"), std::string::npos);
}

// A chart of one stage: its points drawn (a line of one point is invisible), the x ticks whole
// stage numbers only.
TEST(SvgChart, AStageChartOfOneStageShowsItsPointsAndWholeTicks) {
  Axes axes{"chi", "stage", "log10 chi", 600, 240};
  axes.integerX = true;
  const std::string svg = lineChart(axes, {{"fitted", {1}, {1.98}, "", false}});
  EXPECT_EQ(count(svg, "<circle"), 1u);
  EXPECT_NE(svg.find(">1</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">0.95</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">1.05</text>"), std::string::npos);
}

// A 350 px regime panel: x ticks planned 70 px apart, no closer than 50 px after rounding (a
// label of five characters is about 30 px wide at 11 px; before, 0.02 steps put 11 labels in
// 260 px and they ran together), and three legend entries on three rows, not beyond the
// right edge.
TEST(SvgChart, ANarrowPanelKeepsTicksApartAndWrapsItsLegend) {
  const std::vector<double> x = {0.0, 0.1, 0.2};
  const std::string svg =
      lineChart({"panel", "speed", "r", 350, 260},
                {{"fx", x, x, "", true}, {"fy", x, x, "", true}, {"tz", x, x, "", true}});
  const std::size_t ticks = count(svg, "stroke=\"#888\"/><text");  // x ticks only
  EXPECT_GE(ticks, 2u);
  EXPECT_LE(ticks, 1u + (350 - 90) / 50);  // 50 px: the closest niceTicks can place them
  for (const char* row : {"y=\"49\">fx<", "y=\"63\">fy<", "y=\"77\">tz<"})
    EXPECT_NE(svg.find(row), std::string::npos) << row;
}

TEST(SvgChart, BarChartHasOneBarPerValue) {
  const std::string svg = barChart({"chi per stage", "", "chi"}, {"bare", "+contensou"},
                                   {4.1, 1.02}, 1.0, "noise level");
  EXPECT_EQ(count(svg, "class=\"bar\""), 2u);
  EXPECT_NE(svg.find("noise level"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::report
