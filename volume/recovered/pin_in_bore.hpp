#pragma once
// A solid of revolution (a pin) in the cylindrical bore of another body, by slices across the
// pin's axis (docs/SURFACES.md, "Two meshes: a pin in a bore"). The bore's axis is parallel to
// the pin's: in the slice at ζ the pin is a disc of radius r(ζ) (RevolutionProfile) and the
// bore a circle of radius R whose centre c(ζ) lies at e = |c(ζ)| from the pin's axis. The
// other body's material there is the plane less the bore's disc, between the planes across
// the axis that close it (the block's faces), so the interference in the slice is the pin's
// disc less the lens of the two circles. The circles cross on the chord ξ = x₀ (ξ along
// u = c/e from the pin's axis), x₀ = (r² − R² + e²)/(2e): on ξ > x₀ the disc lies inside the
// bore, and on ξ ≤ x₀ the bore's disc lies inside the pin's, so
//   disc − lens = (the pin's segment ξ ≤ x₀) − (the bore's segment ξ ≤ x₀),
// two circular segments of one chord whose moments are closed forms
// (analytic/circular_segment.hpp), of depths d_pin = δ(r + e + R)/(2e) and d_bore = δ(r − e +
// R)/(2e) from their edges, with δ = r + e − R the overlap of the two circles along u. The slices
// are integrated along the profile by adaptive Gauss–Kronrod quadrature
// (volume/kernels/quadrature.hpp) with breakpoints at the pieces' ends, at the planes, and where
// the crescent appears (δ = 0) or the bore's circle leaves or enters the disc.

#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "volume/analytic/revolution_on_plane.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// A cylindrical bore of body B in the frame R of the pin: B's material lies outside the
/// cylinder of radius `radius` about the line through `point_R` along `axis_R` (unit, with a
/// positive z component, parallel to R's z axis: the caller checks how parallel), between
/// the planes ζ = zeta_lo and ζ = zeta_hi across the pin's axis (infinite where no plane of B
/// bounds it).
struct BoreSection {
  Eigen::Vector3d point_R = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_R = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  double zeta_lo = -std::numeric_limits<double>::infinity();
  double zeta_hi = std::numeric_limits<double>::infinity();
  /// Tilted bores: every slice by the polar quadrature, none by the closed forms (the
  /// reference the tests and benchmarks compare them with).
  bool polar_slices = false;
};

struct BoreContact {
  /// V, centroid, J_v, J_s of the interference; n ∝ ∫ n_B dS over B's boundary inside the pin
  /// (MODEL.md §1: the bore's arc in each slice, n_B towards the bore's axis, and the planes'
  /// parts inside the pin); area: the shadow along n, ∫ (the slice's width across u) dζ plus
  /// the planes' parts times |n_plane·n|, exact when u is the same in every slice; depth: the
  /// largest δ of a slice (the column along u through the axis' side of the slice).
  /// relative_error: the quadrature's estimate.
  ContactVolume cv;
  /// The connected regions of the interference, each by the same formulas from its own slices
  /// (in sortPatches order): the runs of the pin's axis over which the slices hold a region.
  /// One for a pin that touches in one band; a pin tilted in its bore gives two, at its ends
  /// on opposite walls. A slice holds one region (a crescent, or the disc less the bore), so
  /// the runs are the regions.
  std::vector<ContactVolume> patches;
  /// The area of the interference in the slices at the planes that bound it, m² (to bound the
  /// error of planes that are not exactly across the axis).
  double plane_area = 0.0;
};

/// A plane of the bored body in the pin's frame R: B's material on the side n·(p − point) ≤ 0
/// (n the plane's outward normal, unit).
struct BorePlane {
  Eigen::Vector3d normal_R = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d point_R = Eigen::Vector3d::Zero();
};

/// The interference of the solid of revolution (pose X_WR, axis the z axis of R) and the
/// body outside `bore`. The normal points out of the bored body into the pin.
/// @throws InputError on an empty profile, pieces that are not contiguous and ascending, a
///   radius that is not positive or an axis along which ζ does not advance
BoreContact revolutionInBore(const RevolutionProfile& profile, const Eigen::Isometry3d& X_WR,
                             const BoreSection& bore);

/// The same for a bore whose axis is tilted from the pin's (bore.axis_R with a positive z
/// component; zeta_lo and zeta_hi are not read): B's material is outside the bore and inside
/// every plane of `planes` (the faces the bore opens onto). In the slice at ζ the bore's
/// section is an ellipse and each plane's trace a line. Where the circle crosses the ellipse
/// twice (certified) the slice is a closed form: the disc's segment beyond the crossings'
/// chord less the ellipse's, each cut by the lines (volume/recovered/pin_in_bore_slices.hpp). Other
/// slices, or all with bore.polar_slices, are integrated in the polar angle ψ about the
/// disc's centre, along each ray in closed
/// form (the ray leaves the ellipse at the roots of a quadratic, crosses each plane's line
/// once), over ψ by adaptive Gauss–Kronrod between the angles where the ray's intervals
/// change (found by bisection between 64 rays from the crescent's deepest direction), then
/// over ζ as above, with breakpoints
/// where the slice's region appears or vanishes (bisection on its area between 16 samples a
/// piece) and where a plane's line touches the circle or the ellipse or passes their
/// crossings (volume/recovered/pin_in_bore_bands.hpp). `cv.relative_error` is
/// the outer quadrature's estimate (the inner one asked 1e-12). n ∝ −∫ n_A dS over the pin's
/// boundary inside B (its side, and its end faces), the same as ∫ n_B dS over B's inside the
/// pin for a closed region (MODEL.md §1); area |∫ n_A dS|, the shadow along n where n_A·n keeps
/// its sign; depth the largest radial depth of a ray. plane_area is 0.
/// @throws InputError as revolutionInBore
BoreContact revolutionInTiltedBore(const RevolutionProfile& profile, const Eigen::Isometry3d& X_WR,
                                   const BoreSection& bore, const std::vector<BorePlane>& planes);

}  // namespace vcontact::volume
