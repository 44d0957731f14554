#pragma once
// The physical limits of every number that enters vcontact from a file or the command line,
// in one place (issue 20). A value outside them is refused where it enters, with the limit in
// the message, before it can turn into an infinite volume, a zero mass or a hang.
//
// The limits are wide on purpose: they bound what a rigid-body contact simulation of parts on
// a bench, a machine or a vehicle can mean, not what is typical. README "Input limits" lists
// them for users.

#include <cstddef>
#include <string>

namespace vcontact::io {

struct Range {
  double lower;  ///< inclusive
  double upper;  ///< inclusive
  const char* unit;
};

/// A shape's radius, length or edge, and a mesh's extent after scaling: a micrometre part is
/// below what a float32 STL can hold about its own size; a kilometre is a building, not a part.
inline constexpr Range kLengthRange{1e-6, 1e3, "m"};
/// Density: aerogel (~1) down to a foam at 0.1, up to 1e5 (osmium is 2.26e4).
inline constexpr Range kDensityRange{0.1, 1e5, "kg/m^3"};
/// Mass of a body given directly: a microgram to a thousand tonnes.
inline constexpr Range kMassRange{1e-9, 1e6, "kg"};
/// A position coordinate (pose, dataset x, y, z): the workspace is a kilometre cube.
inline constexpr double kMaxPosition = 1e3;  // m
/// Roll, pitch and yaw: one turn either way.
inline constexpr double kMaxAngleDegrees = 360.0;
/// A linear speed: faster than any rig or machine (a rifle bullet is ~1e3).
inline constexpr double kMaxSpeed = 1e3;  // m/s
/// An angular speed: 1e4 rad/s is about 95 000 rpm, a dental drill.
inline constexpr double kMaxAngularSpeed = 1e4;  // rad/s
/// Gravity or another acceleration magnitude per axis: a hundred g.
inline constexpr double kMaxAcceleration = 1e3;  // m/s^2
/// A simulated duration or a time stamp: about eleven days of simulated time.
inline constexpr Range kDurationRange{1e-9, 1e6, "s"};
inline constexpr double kMaxTime = 1e6;  // s, |t| of a dataset sample
/// The smallest interval between two dataset samples: a 1 GHz sampling rate.
inline constexpr double kMinSampleInterval = 1e-9;  // s
/// Output rate of a simulation and frequency of a prescribed motion: a megahertz.
inline constexpr Range kRateRange{1e-6, 1e6, "Hz"};
/// A measured or synthetic force component (N) and torque component (N m).
inline constexpr double kMaxForce = 1e9;
inline constexpr double kMaxTorque = 1e9;
/// Samples of a synthetic record: from the three a derivative needs to ten million.
inline constexpr std::size_t kMinSamples = 3;
inline constexpr std::size_t kMaxSamples = 10'000'000;

/// "expected NAME in [lower, upper] UNIT, got VALUE" when `value` is outside `range` or not
/// finite; empty when it is inside.
std::string outOfRange(double value, const Range& range, const std::string& name);

/// Parses one decimal number strictly: optional sign, digits with an optional point, an
/// optional exponent; nothing else (no hex, no nan or inf, no spaces, no trailing text).
/// @returns false and `why` ("not a number", "beyond the range of a double") on failure
bool parseDecimal(const std::string& text, double& value, std::string& why);

}  // namespace vcontact::io
