#pragma once
// Where a face of the bored body cuts the slices of a pin in a tilted bore
// (volume/recovered/pin_in_bore.hpp). In the slice at ζ a plane's trace is the line m·x = k(ζ), m
// the part of the plane's normal n across the pin's axis and k(ζ) = n·p − n_z ζ: as ζ advances it
// sweeps across the disc, a band of ζ 2r|m|/|n_z| wide. Inside the band the slice's region
// (the disc less the bore's ellipse, on B's side m·x ≤ k of the line) changes its form where
// the line
//   - touches the circle at a point outside the ellipse (the band's edge on the crescent's
//     side), or touches the ellipse at a point inside the disc: a segment of either curve
//     appears or goes, and the slice's moments go as |ζ − ζ*|^{3/2} there (singular);
//   - passes through a point where the circle crosses the ellipse: a corner of the crescent
//     changes sides, and the moments' second derivative jumps.
// Between these points the moments are smooth in ζ, and a Kronrod rule converges on each
// piece without bisecting towards them.

#include <functional>
#include <vector>

#include "volume/recovered/pin_in_bore.hpp"

namespace vcontact::volume::detail {

/// A point of a profile piece's parameter where the slices change form; `singular` where
/// they go as |t − t*|^{3/2} (integrated after the substitution of integrateSingularEnds).
struct Breakpoint {
  double t = 0.0;
  bool singular = false;
};

/// Intervals of a piece's parameter shorter than this share of the piece are left out, and
/// breakpoints closer are one: such an interval holds at most 1e-12 of the piece's length
/// times its largest slice.
inline constexpr double kNegligible = 1e-12;

/// Appends to `out` the parameters in (t0, t1) of piece p (ascending ζ) where the line of
/// `plane` changes the form of the slice of the pin in `bore` (the header's list). `rMax`
/// bounds the pin's radius: the band is sought where the line crosses a disc that wide.
void bandBreakpoints(const ProfilePiece& p, double t0, double t1, double rMax,
                     const BoreSection& bore, const BorePlane& plane, std::vector<Breakpoint>& out);

/// The breakpoints of piece p in (t0, t1), ascending: the events of bandBreakpoints for each
/// plane, and where the region appears or vanishes (singular), bisected on `present(t)`
/// (whether the slice at t has a region) between two tests that differ. Presence is tested at
/// 16 samples of the piece, at every event and halfway between any two consecutive of these
/// points, so that a region that lives only inside a band (between two samples without one)
/// is found; a change bisected to within 1e-9 of the piece of an event is the event's.
std::vector<Breakpoint> pieceBreakpoints(const ProfilePiece& p, double t0, double t1, double rMax,
                                         const BoreSection& bore,
                                         const std::vector<BorePlane>& planes,
                                         const std::function<bool(double)>& present);

}  // namespace vcontact::volume::detail
