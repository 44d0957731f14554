#pragma once
// The slices of a pin in a bore by closed forms (volume/recovered/pin_in_bore.hpp). A parallel
// bore's section is a circle: the disc less the lens of the two circles. A tilted one's: in the
// slice across the pin's axis the pin is the disc |x| ≤ r and the bore's section an ellipse, the
// image x = c + S y of the disc |y| ≤ R (S symmetric, det S = 1/cos γ for a tilt γ). When the
// circle and the ellipse cross in two points, the disc less the ellipse is the disc's segment
// beyond the chord through the crossings less the ellipse's segment on the same side (the
// lens between them is convex, bounded by one arc of each on either side of the chord), and
// the ellipse's segment is the affine image of a circular segment: both from
// analytic/circular_segment.hpp. Other cases (no crossing, four, a grazing circle) are left to the
// caller's polar quadrature.

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace vcontact::volume::detail {

/// Moments of the disc less a parallel bore's circle in the slice's own axes (ξ along u from
/// the disc's edge point −r u, η along v; u towards the bore's centre), with the bore's chord
/// inside the disc, the width across u and δ = r + e − R.
struct InSlice {
  double A = 0.0, S1 = 0.0, S11 = 0.0, S22 = 0.0;
  double chord = 0.0, width = 0.0, depth = 0.0;
};

/// The disc of radius r less the disc of radius R whose centre is e away along u.
InSlice discLessBore(double r, double R, double e);

/// The bore's section in the slice: its centre c (where the bore's axis crosses the slice)
/// and the map y ↦ c + S y of the disc of radius R onto it.
struct SliceEllipse {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
  double R = 0.0;
};

/// The section of the cylinder of radius R about the line through `point` along the unit
/// `axis` (positive z component) by the plane z = ζ.
SliceEllipse boreEllipse(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double R,
                         double zeta);

/// The disc of radius r less the ellipse, about the disc's centre: area, ∫x, ∫y, ∫x², ∫xy,
/// ∫y²; the disc's arc outside the ellipse as ∫ r (cos ψ, sin ψ) dψ and its length; depth,
/// the largest r − ρ_E(ψ) over that arc (ρ_E the ray's exit from the ellipse).
struct EllipseSlice {
  double A = 0.0, Sx = 0.0, Sy = 0.0, Sxx = 0.0, Sxy = 0.0, Syy = 0.0;
  double arcX = 0.0, arcY = 0.0, arcLength = 0.0, depth = 0.0;
};

/// Fills `out` and returns true where the closed form holds: the ellipse holds the disc
/// (an empty region), or the two curves cross in exactly two points (certified by the
/// circle's side of the ellipse as a trigonometric polynomial of degree 2 whose first
/// harmonic dominates, positive on one side and negative on the other). Returns false, and
/// leaves `out` alone, otherwise. Without `withDepth` out.depth is 0 (its search is most of
/// the cost).
bool discLessEllipse(double r, const SliceEllipse& E, EllipseSlice& out, bool withDepth = true);

/// The two points where the circle of radius r about the origin crosses the ellipse, when
/// certified as in discLessEllipse: `lo` and `hi` counter-clockwise about the disc's arc
/// outside the ellipse. False, leaving them alone, otherwise (the ellipse holding the disc
/// included).
bool circleCrossings(double r, const SliceEllipse& E, Eigen::Vector2d& lo, Eigen::Vector2d& hi);

/// Half-planes a·x ≤ b.
using HalfPlanes = std::vector<std::pair<Eigen::Vector2d, double>>;

/// The same region cut by half-planes (B's side of its faces' lines in the slice): the disc's
/// and the ellipse's parts beyond the chord through the crossings, each cut by the lines, by
/// Green's theorem on their boundaries (the circle's arcs, the chords' pieces), the ellipse's
/// through its affine map; depth over the disc's arcs inside the lines. The same cases as
/// discLessEllipse are declined.
bool discLessEllipseCut(double r, const SliceEllipse& E, const HalfPlanes& lines, EllipseSlice& out,
                        bool withDepth = true);

}  // namespace vcontact::volume::detail
