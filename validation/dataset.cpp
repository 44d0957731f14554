#include "validation/dataset.hpp"

#include <cassert>

namespace vcontact::validation {

void differentiatePositions(std::vector<Sample>& s) {
  const std::size_t n = s.size();
  assert(n >= 3);
  auto p = [&](std::size_t i) { return s[i].X_BA.translation(); };
  for (std::size_t i = 0; i < n; ++i) {
    // Three-point stencil on (i−1, i, i+1), or the nearest three at an end; the derivative
    // of the interpolating parabola at t_i.
    const std::size_t a = i == 0 ? 0 : (i == n - 1 ? n - 3 : i - 1);
    const double t0 = s[a].t, t1 = s[a + 1].t, t2 = s[a + 2].t, t = s[i].t;
    const double l0 = ((t - t1) + (t - t2)) / ((t0 - t1) * (t0 - t2));
    const double l1 = ((t - t0) + (t - t2)) / ((t1 - t0) * (t1 - t2));
    const double l2 = ((t - t0) + (t - t1)) / ((t2 - t0) * (t2 - t1));
    s[i].v_BA = l0 * p(a) + l1 * p(a + 1) + l2 * p(a + 2);
  }
}

void differentiateAttitudes(std::vector<Sample>& s) {
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i == 0 ? 0 : i - 1, hi = i + 1 == n ? i : i + 1;
    const Eigen::AngleAxisd delta(s[hi].X_BA.linear() * s[lo].X_BA.linear().transpose());
    s[i].w_BA = delta.angle() * delta.axis() / (s[hi].t - s[lo].t);
  }
}

}  // namespace vcontact::validation
