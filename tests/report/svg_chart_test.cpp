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
  EXPECT_EQ(count(svg, "<circle"), 3u) << "the NaN sample is skipped";
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_NE(svg.find("model &lt;fit&gt;"), std::string::npos);
}

TEST(SvgChart, BarChartHasOneBarPerValue) {
  const std::string svg = barChart({"chi per stage", "", "chi"}, {"bare", "+contensou"},
                                   {4.1, 1.02}, 1.0, "noise level");
  EXPECT_EQ(count(svg, "class=\"bar\""), 2u);
  EXPECT_NE(svg.find("noise level"), std::string::npos);
}

}  // namespace
}  // namespace vcontact::report
