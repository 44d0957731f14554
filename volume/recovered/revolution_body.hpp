#pragma once
// A body's recognised surfaces read as a solid of revolution (docs/SURFACES.md, "Solids of
// revolution"): cylinders, cones, spheres and tori sharing one axis, closed by planes
// perpendicular to it, give the profile r(ζ) that volume/analytic/revolution_on_plane.hpp slices.

#include <Eigen/Geometry>
#include <optional>
#include <set>
#include <string>

#include "geometry/surface_recognition.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/analytic/revolution_on_plane.hpp"

namespace vcontact::volume {

struct RevolutionBody {
  /// The profile's frame R in the mesh frame M: z along the common axis, origin on the axis
  /// at the middle of the profile's extent.
  Eigen::Isometry3d X_MR = Eigen::Isometry3d::Identity();
  RevolutionProfile profile;
  /// The largest distance of the used surfaces' vertices to them, m (the fit term).
  double max_residual = 0.0;
  /// One cylinder and the planes that close it: the analytic backend's finite cylinder.
  bool capped_cylinder = false;
};

/// The solid of revolution made by the recognised surfaces `surfaces` (indices into
/// recognition.surfaces; −1 stands for free-form faces), or nothing with `reason` saying why:
/// free-form faces; a surface off the common axis or a plane not perpendicular to it; faces
/// that face the axis (a bore); pieces that do not follow one another along the axis; a step
/// in the radius that no plane closes. The pieces' extents along the axis are those of their
/// faces' vertices. Both ends may be open (the faces beyond them cannot reach the plane).
std::optional<RevolutionBody> revolutionOf(const geometry::TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const std::set<int>& surfaces, std::string& reason);

}  // namespace vcontact::volume
