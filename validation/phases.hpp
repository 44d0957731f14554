#pragma once
// The phases of a record's motion (issue 37 item 4; docs/DIAGNOSIS.md "Phases"), computed
// from the replayed geometry and the record's kinematics, per sample:
//
//   not in contact:  approach     the payload moves towards the plate (−v_z ≥ 0)
//                    separation   it moves away
//   in contact, with tangential motion (the largest of the slip speed |v_t|, the spin speed
//   r_gyr |ω_n| and the rolling speed |ω_t| |p_c − p_o| at least the rest speed: kRestSpeed,
//   or kRestSpeedFraction of the record's fastest tangential motion in contact when that is
//   higher, since velocities differentiated from motion capture are noise of 1e-4 m/s and
//   more at rest):
//                    sliding      |v_t| is the largest
//                    spinning     r_gyr |ω_n| is the largest
//                    rolling      the rolling speed is the largest
//   in contact, without tangential motion, by the penetration rate δ̇:
//                    loading      δ̇ > ε_n
//                    unloading    δ̇ < −ε_n
//                    rest         |δ̇| ≤ ε_n in a record that has tangential motion somewhere
//                                 (a stop between motions)
//                    holding      |δ̇| ≤ ε_n in a record whose contact moves only normally
//                                 (an indentation held at depth)
//   ε_n = kNormalRateFraction of the record's largest |δ̇| in contact (a motion-capture
//   record with constant height has ε_n = 0 and δ̇ = 0: rest, not loading), at least
//   kNormalRateFloor.
// One sample's label is then replaced by the most common label over the ±half-window around
// it (ties keep the sample's own), so that the noise of differentiated velocities near the
// kRestSpeed threshold does not cut a phase into single samples. Every sample has exactly one
// phase: the labels cannot contradict each other.

#include <cstddef>
#include <string_view>
#include <vector>

#include "validation/replay.hpp"

namespace vcontact::validation {

enum class Phase {
  kApproach,
  kSeparation,
  kLoading,
  kHolding,
  kUnloading,
  kSliding,
  kRolling,
  kSpinning,
  kRest
};

/// "approach", "separation", "loading", …
std::string_view phaseName(Phase phase);

/// Share of the record's fastest tangential speed below which the contact counts as at rest:
/// 2 % keeps a drive's slowest level (0.5 of 15 mm/s) sliding and a 150 mm/s push's
/// motion-capture noise (≈ 1e-4 … 1e-3 m/s) at rest.
inline constexpr double kRestSpeedFraction = 0.02;
/// Share of the record's largest in-contact |δ̇| below which the normal motion counts as held.
inline constexpr double kNormalRateFraction = 1e-3;
/// Smallest ε_n, m/s: far below any indentation rate a rig drives (µm/s).
inline constexpr double kNormalRateFloor = 1e-9;

/// Each sample's phase (see the header), smoothed over ±halfWindow samples.
std::vector<Phase> phasesOf(const std::vector<RegimeSample>& regime, std::size_t halfWindow);

/// A run of samples of one phase: [first, last], inclusive.
struct PhaseSpan {
  Phase phase;
  std::size_t first = 0, last = 0;
};

/// The contiguous runs of `phases`, in record order.
std::vector<PhaseSpan> phaseSpans(const std::vector<Phase>& phases);

}  // namespace vcontact::validation
