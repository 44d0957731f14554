#pragma once
// The columns method's δ map as CSV: one row per column line with δ > 0, the point where it
// meets the contact plate (world frame, m) and its depth (m), 17 significant digits.

#include <ostream>
#include <string>

#include "volume/contact_volume.hpp"

namespace vcontact::report {

/// Puts the map on `out` (for a file of an io::OutputSet).
void putDepthMapCsv(const volume::DepthField& field, std::ostream& out);

/// @throws InputError naming `path` when it cannot be opened for writing
void writeDepthMapCsv(const volume::DepthField& field, const std::string& path);

}  // namespace vcontact::report
