#include "dynamics/restitution.hpp"

#include <algorithm>
#include <cmath>

namespace vcontact::dynamics {

// g(e) = α (1 + e) − ln(1 + α) + ln(1 − α e) falls from g(0) = α − ln(1 + α) > 0 to −∞ at
// e = 1/α, and is concave (g'' = −α² / (1 − α e)² < 0), so Newton's iteration started right of
// the root converges to it monotonically from the right. Its terms cancel to α³ while its slope
// is α², so Newton's root is off by about ε/α (2e-13 at α = 1e-3); below that the relation's
// series e = 1 − 2α/3 + 4α²/9 − 44α³/135 + O(α⁴) (the α⁴ term is about 0.25 α⁴) is closer.
double dampedRestitution(double alpha) {
  if (!(alpha > 0.0)) return 1.0;
  if (alpha < 1e-3) return 1.0 - alpha * (2.0 / 3.0 - alpha * (4.0 / 9.0 - alpha * 44.0 / 135.0));
  const auto g = [alpha](double e) {
    return alpha * (1.0 + e) - std::log1p(alpha) + std::log1p(-alpha * e);
  };
  double e = std::min(1.0, (1.0 - 1e-15) / alpha);
  if (g(e) >= 0.0) return e;  // α ≳ 37: the root is 1/α to the last bit
  for (int i = 0; i < 100; ++i) {
    const double slope = -alpha * alpha * e / (1.0 - alpha * e);
    const double next = e - g(e) / slope;
    if (!(next < e)) break;  // converged: the iteration no longer moves left
    e = next;
  }
  return e;
}

}  // namespace vcontact::dynamics
