#pragma once
// A solid of revolution against a half-space by closed-form slices (docs/SURFACES.md,
// "Solids of revolution"): the solid is given by its profile r(ζ) along the z axis of its
// frame R, in pieces that are constant (a cylinder), linear (a cone) or circular arcs (a
// sphere, a torus), closed by planes perpendicular to the axis wherever the radius jumps and
// at both ends. Every slice perpendicular to the axis is a disc of radius r(ζ) that the
// plane's trace cuts into a circular segment whose area, centroid and second moments are
// closed forms; they are integrated over the profile by adaptive Gauss–Kronrod quadrature
// (volume/kernels/quadrature.hpp), with breakpoints at the pieces' ends and where a slice's segment
// appears, becomes the whole disc or passes the axis. The finite cylinder of the analytic
// backend is the one-piece profile.

#include <Eigen/Geometry>
#include <vector>

#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// One piece of a profile, over ζ ∈ [z0, z1] (z0 < z1, metres):
/// - kConstant: r = r0 (a cylinder);
/// - kLinear: r from r0 at z0 to r1 at z1 (a cone);
/// - kArc: r = rho_c + sign·√(a² − (ζ − z_c)²), with |ζ − z_c| ≤ a on the piece (a sphere:
///   rho_c = 0, sign +1; a torus: rho_c its major radius, a its minor radius, sign +1 on the
///   outer half of its tube, −1 on the inner half). r0 and r1 are not read.
struct ProfilePiece {
  enum class Kind { kConstant, kLinear, kArc };
  Kind kind = Kind::kConstant;
  double z0 = 0.0, z1 = 0.0;
  double r0 = 0.0, r1 = 0.0;
  double rho_c = 0.0, z_c = 0.0, a = 0.0, sign = 1.0;
};

/// The pieces in ascending ζ, each beginning where the one before ends. Planes perpendicular
/// to the axis are implied where the radius jumps between two pieces and at both ends.
using RevolutionProfile = std::vector<ProfilePiece>;

/// The radius of a piece at ζ (clamped into the piece).
double profileRadius(const ProfilePiece& piece, double zeta);

/// The largest radius of the profile, m (at a piece's end or an arc's crest).
double largestRadius(const RevolutionProfile& profile);

/// The finite cylinder of radius `radius` and length `length` centred on R's origin.
RevolutionProfile cylinderProfile(double radius, double length);

/// ContactVolume of the solid (pose X_WR, axis the z axis of R) and the half-space H (solid
/// z_H ≤ 0), to a relative accuracy of 1e-9 or better (relative_error: the quadrature's
/// estimate). `area` is the solid's intersection with H seen along the plane's normal, exact
/// for a convex profile.
/// @throws InputError on an empty profile or pieces that are not contiguous and ascending
ContactVolume revolutionHalfspace(const RevolutionProfile& profile, const Eigen::Isometry3d& X_WR,
                                  const Eigen::Isometry3d& X_WH);

/// revolutionHalfspace with the contact's connected regions: one per run of wetted slices
/// along the axis (a dumbbell lying on the plane touches it with both balls, a stepped shaft
/// tilted onto it with its two collars), each a full ContactVolume of its own slices, ends and
/// steps, in sortPatches order; the aggregate is revolutionHalfspace's. One run (every convex
/// profile, an axis along the normal): the aggregate is the only patch.
ContactPatches revolutionHalfspacePatches(const RevolutionProfile& profile,
                                          const Eigen::Isometry3d& X_WR,
                                          const Eigen::Isometry3d& X_WH);

}  // namespace vcontact::volume
