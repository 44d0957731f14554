#pragma once
// The analytic backend: a sphere, cylinder or box against a half-space, by closed form
// (sphere; box as an exact polyhedral clip) or by adaptive quadrature of closed-form slice
// moments (cylinder in any orientation), to a relative accuracy of 1e-9 or better.

#include <Eigen/Geometry>

#include "geometry/primitives.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// True when analyticContact handles the pair (a bounded primitive and a half-space,
/// in either order).
bool analyticSupports(const geometry::Shape& a, const geometry::Shape& b);

/// ContactVolume of A (the payload) and B (the plate or other body), one a half-space and the other
/// a sphere, cylinder or box. No contact gives volume 0.
/// @throws InputError when the pair is not supported (see analyticSupports)
ContactVolume analyticContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                              const geometry::Shape& b, const Eigen::Isometry3d& X_WB);

ContactVolume sphereHalfspace(double radius, const Eigen::Isometry3d& X_WS,
                              const Eigen::Isometry3d& X_WH);
ContactVolume cylinderHalfspace(double radius, double length, const Eigen::Isometry3d& X_WC,
                                const Eigen::Isometry3d& X_WH);
ContactVolume boxHalfspace(const Eigen::Vector3d& size, const Eigen::Isometry3d& X_WB,
                           const Eigen::Isometry3d& X_WH);

}  // namespace vcontact::volume
