#include "volume/contact_volume.hpp"

#include <cmath>

#include "geometry/error.hpp"

namespace vcontact::volume {

std::string methodName(Method method) {
  switch (method) {
    case Method::kAnalytic:
      return "analytic";
    case Method::kHalfspace:
      return "halfspace";
    case Method::kCgal:
      return "cgal";
    case Method::kFast:
      return "fast";
    case Method::kColumns:
      return "columns";
  }
  return "unknown";
}

Method parseMethod(const std::string& name) {
  for (Method m :
       {Method::kAnalytic, Method::kHalfspace, Method::kCgal, Method::kFast, Method::kColumns}) {
    if (methodName(m) == name) return m;
  }
  throw InputError("--method", "unknown method '" + name +
                                   "'; expected analytic, halfspace, cgal, fast or columns");
}

ContactVolume assembleContactVolume(double V, const Eigen::Vector3d& p_c,
                                    const Eigen::Matrix3d& Sigma, const Eigen::Vector3d& n,
                                    double area, double depth, Method method) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = 0.5 * (Sigma + Sigma.transpose());
  const Eigen::Matrix3d P = I - n * n.transpose();
  const Eigen::Matrix3d S_s = P * S * P;
  ContactVolume cv;
  cv.volume = V;
  cv.centroid = p_c;
  cv.normal = n;
  cv.J_v = S.trace() * I - S;
  cv.J_s = S_s.trace() * I - S_s;
  cv.area = area;
  cv.depth = depth;
  cv.r_gyr = std::sqrt(std::max(0.0, n.dot(cv.J_s * n)) / V);
  cv.method = method;
  return cv;
}

ContactVolume swapped(ContactVolume cv) {
  cv.normal = -cv.normal;
  return cv;
}

}  // namespace vcontact::volume
