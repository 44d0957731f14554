#include "volume/contact_volume.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vcontact::volume {
namespace {

/// |‖n‖ − 1| a unit normal may show after normalisation and a rotation: a few ulps; 1e-12
/// leaves room for the products of up to a few thousand roundings.
constexpr double kUnitTolerance = 1e-12;

}  // namespace

ContactVolume assembleContactVolume(double V, const Eigen::Vector3d& p_c,
                                    const Eigen::Matrix3d& Sigma, const Eigen::Vector3d& n,
                                    double area, double depth, Method method) {
  assert(V > 0.0 && std::abs(n.norm() - 1.0) < kUnitTolerance);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = 0.5 * (Sigma + Sigma.transpose());
  const Eigen::Matrix3d P = I - n * n.transpose();
  const Eigen::Matrix3d S_s = P * S * P;
  ContactVolume cv;
  cv.volume = V;
  cv.p_WC = p_c;
  cv.n_W = n;
  cv.J_v = S.trace() * I - S;
  cv.J_s = S_s.trace() * I - S_s;
  cv.area = area;
  cv.depth = depth;
  cv.r_gyr = std::sqrt(std::max(0.0, n.dot(cv.J_s * n)) / V);
  cv.method = method;
  return cv;
}

ContactVolume contactFromMoments(const geometry::Moments& M, const Eigen::Vector3d& p_Wo,
                                 const Eigen::Vector3d& n, double area, double depth,
                                 Method method) {
  return assembleContactVolume(M.m0, p_Wo + M.centroid(), M.centralSecondMoment(), n, area, depth,
                               method);
}

ContactVolume contactFromMoments(const geometry::Moments& M, const Eigen::Vector3d& p_Fo,
                                 const Eigen::Isometry3d& X_WF, const Eigen::Vector3d& n,
                                 double area, double depth, Method method) {
  const Eigen::Matrix3d R_WF = X_WF.linear();
  return assembleContactVolume(M.m0, X_WF * p_Fo + R_WF * M.centroid(),
                               R_WF * M.centralSecondMoment() * R_WF.transpose(), n, area, depth,
                               method);
}

ContactVolume swapped(ContactVolume cv) {
  cv.n_W = -cv.n_W;
  return cv;
}

ContactPatches swapped(ContactPatches contact) {
  for (ContactVolume& patch : contact.patches) patch = swapped(patch);
  contact.aggregate = swapped(contact.aggregate);
  return contact;
}

void sortPatches(std::vector<ContactVolume>& patches) {
  std::sort(patches.begin(), patches.end(), [](const ContactVolume& l, const ContactVolume& r) {
    if (l.volume != r.volume) return l.volume > r.volume;
    return std::lexicographical_compare(l.p_WC.begin(), l.p_WC.end(), r.p_WC.begin(), r.p_WC.end());
  });
}

const char* representationName(Representation representation) {
  switch (representation) {
    case Representation::kSphere:
      return "sphere";
    case Representation::kCylinder:
      return "cylinder";
    case Representation::kRevolution:
      return "revolution";
    case Representation::kRevolutionInBore:
      return "revolution_in_bore";
    case Representation::kRefined:
      return "refined";
    case Representation::kShape:
      break;
  }
  return "mesh";
}

ContactPatches singlePatch(const ContactVolume& cv) {
  ContactPatches contact;
  contact.aggregate = cv;
  if (cv.inContact()) contact.patches.push_back(cv);
  return contact;
}

}  // namespace vcontact::volume
