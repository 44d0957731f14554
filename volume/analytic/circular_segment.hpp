#pragma once
// The moments of a circular segment, the slice of a disc that a line cuts off, by closed
// forms that keep their digits down to the thinnest segment (a series where the closed forms
// would cancel), two small pieces of trigonometry the slices need, and the walk along a
// profile piece. Shared by the analytic
// backend's solids of revolution (volume/analytic/revolution_on_plane.hpp).

#include <vector>

#include "volume/analytic/revolution_on_plane.hpp"

namespace vcontact::volume::detail {

/// A segment of a disc of radius R cut at ξ = −R cos θ (depth d = R(1 − cos θ) from the
/// disc's edge at ξ = −R), moments about that edge point: area, ∫ξ', ∫ξ'², ∫η², with
/// ξ' = ξ + R and η along the chord.
struct Segment {
  double A, S1, S11, S22;
};

/// @param theta half the angle the chord subtends at the centre, in [0, π]
Segment segmentMoments(double R, double theta);

/// The same by a shorter evaluation of the series for thin segments (Horner's rule, as many
/// terms as θ needs): equal to segmentMoments to rounding, not bit for bit.
Segment shallowSegmentMoments(double R, double theta);

/// θ with d = R(1 − cos θ), accurate for small d; d is clamped to [0, 2R].
double segmentAngle(double R, double d);

/// ∫_0^θ |A cos φ + B| dφ, sin θ and cos θ given (the shadow of a slice's wetted arc along a
/// plane's normal).
double absCosIntegral(double A, double B, double theta, double sinTheta, double cosTheta);

/// Appends to `out` the solutions α ∈ (lo, hi) of P cos α + Q sin α = K (lo, hi in [−π, π]).
void trigRoots(double P, double Q, double K, double lo, double hi, std::vector<double>& out);

/// A profile piece walked by its parameter t: ζ itself on constant and linear pieces, the
/// angle α on an arc (ζ = z_c + a sin α, r = ρ_c + σ a cos α).
struct PieceAt {
  double zeta, r;
  double J;     ///< dζ/dt
  double drdt;  ///< dr/dt
};
PieceAt pieceAt(const ProfilePiece& p, double t);
/// dr/dζ of a linear piece.
double linearSlope(const ProfilePiece& p);
/// The parameter of ζ on the piece.
double parameterOf(const ProfilePiece& p, double zeta);

/// @throws InputError from `where` on an empty profile or pieces that are not contiguous and
///   ascending
void checkProfile(const RevolutionProfile& profile, const char* where);

}  // namespace vcontact::volume::detail
