#pragma once
// The columns method's δ map as CSV: one row per column line with δ > 0, the point where it
// meets the contact plate (world frame, m) and its depth (m), 17 significant digits.

#include <string>

#include "volume/contact_volume.hpp"

namespace vcontact::report {

/// @throws InputError naming `path` when it cannot be opened for writing
void writeDepthMapCsv(const volume::DepthField& field, const std::string& path);

}  // namespace vcontact::report
