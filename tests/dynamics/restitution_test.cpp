// The restitution of the damped contact (dynamics/restitution.hpp) against independent
// solutions of the relation of docs/MODEL.md §5 and its limits.

#include "dynamics/restitution.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics_fixtures.hpp"

namespace vcontact::test {
namespace {

using dynamics::dampedRestitution;

// Roots of α (1 + e) = ln((1 + α)/(1 − α e)) to 20 digits, by mpmath.findroot at 80 digits
// (rounded here to double). The function's error is about 2e-13 where its series and Newton's
// iteration meet (α = 1e-3) and falls away from it: 5e-13 relative is the bound.
TEST(DampedRestitution, MatchesHighPrecisionRoots) {
  const std::vector<std::pair<double, double>> roots = {{1e-6, 0.99999933333377777745},
                                                        {1e-4, 0.99993333777745187753},
                                                        {1e-3, 0.99933377745210843051},
                                                        {1e-2, 0.9933774543987673634},
                                                        {0.3, 0.83286979226560166503}};
  for (const auto& [alpha, e] : roots) {
    EXPECT_NEAR(dampedRestitution(alpha), e, 5e-13 * e) << "alpha " << alpha;
  }
}

// Newton's root against bisection's (tests/dynamics/dynamics_fixtures.hpp) over α from 0.03
// to 1000. The bisection evaluates ln of the ratio, whose rounding (1e-16) moves its root by
// about 1e-16 / α²: 1e-13 at α = 0.03, hence the range and the bound. The relation's residual
// at the function's root, over its slope α² e / (1 − α e) (steep as α e → 1), is the distance
// to the true root: within a few ulps of e, where 1 − α e is resolved in double (α ≲ 30;
// beyond, e is 1/α to the last bit and the residual is the rounding of 1 − α e).
TEST(DampedRestitution, AgreesWithBisection) {
  for (double alpha = 0.03; alpha <= 1e3; alpha *= 1.7) {
    const double e = dampedRestitution(alpha), reference = exactRestitution(alpha);
    EXPECT_NEAR(e, reference, 2e-13 * reference) << "alpha " << alpha;
    const double residual = alpha * (1.0 + e) - std::log1p(alpha) + std::log1p(-alpha * e);
    const double slope = alpha * alpha * e / (1.0 - alpha * e);
    if (alpha < 30.0) {
      EXPECT_LT(std::abs(residual) / slope, 1e-14 * e) << "alpha " << alpha;
    }
  }
}

// The limits: e = 1 without damping, continuous where the series hands over to Newton's
// iteration (α = 1e-3), α e → 1 as α → ∞, and e falling monotonically with α.
TEST(DampedRestitution, Limits) {
  EXPECT_EQ(dampedRestitution(0.0), 1.0);
  EXPECT_EQ(dampedRestitution(-1.0), 1.0);
  // across 2e-9 about 1e-3 e falls by 2e-9 (2/3 − 8α/9) to 1e-17: no step between the two
  EXPECT_NEAR(dampedRestitution(0.999999e-3) - dampedRestitution(1.000001e-3),
              2e-9 * (2.0 / 3.0 - 8e-3 / 9.0), 1e-12);
  EXPECT_NEAR(1e3 * dampedRestitution(1e3), 1.0, 1e-12);
  double last = 1.0;
  for (double alpha = 1e-5; alpha < 1e2; alpha *= 1.3) {
    const double e = dampedRestitution(alpha);
    EXPECT_LT(e, last) << "alpha " << alpha;
    last = e;
  }
}

}  // namespace
}  // namespace vcontact::test
