#include "volume/fast/triangle_pair.hpp"

#include <algorithm>

namespace vcontact::volume::internal {

using Eigen::Vector3d;

bool segmentMeetsBox(const Vector3d& p0, const Vector3d& p1, const Vector3d& c, const Vector3d& h) {
  double t0 = 0.0, t1 = 1.0;
  const Vector3d d = p1 - p0;
  for (int k = 0; k < 3; ++k) {
    const double lo = c[k] - h[k] - p0[k], hi = c[k] + h[k] - p0[k];
    if (d[k] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return false;
      continue;
    }
    double a = lo / d[k], b = hi / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace vcontact::volume::internal
