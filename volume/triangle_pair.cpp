#include "volume/triangle_pair.hpp"

#include <algorithm>

#include "volume/exact_predicates.hpp"

namespace vcontact::volume::internal {

using Eigen::Vector3d;

bool certainlyDisjoint(const Vector3d* A, const int* sideA, const Vector3d* B, const int* sideB) {
  const int i = loneCorner(sideA);
  const Vector3d* T1[3] = {&A[i], &A[(i + 1) % 3], &A[(i + 2) % 3]};
  int b[3] = {0, 1, 2};                     // B's corners in T2's order
  if (sideA[i] < 0) std::swap(b[1], b[2]);  // flip T2 so that p1 is on its positive side
  const int sideT2[3] = {sideB[b[0]], sideB[b[1]], sideB[b[2]]};
  const int j = loneCorner(sideT2);
  const Vector3d& p2 = B[b[j]];
  const Vector3d& q2 = B[b[(j + 1) % 3]];
  const Vector3d& r2 = B[b[(j + 2) % 3]];
  if (sideT2[j] < 0) std::swap(T1[1], T1[2]);  // flip T1 so that p2 is on its positive side
  const Vector3d &p1 = *T1[0], &q1 = *T1[1], &r1 = *T1[2];
  return orient3dFiltered(q1, p2, p1, q2) > 0 || orient3dFiltered(p1, p2, r1, r2) > 0;
}

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
