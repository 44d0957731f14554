#pragma once
// The friction map (validation/friction_map.hpp) as CSV: one row per ε, forces in N and
// torques in N·m about the centroid; the exact columns are empty where there is no closed form.

#include <string>

#include "validation/friction_map.hpp"

namespace vcontact::report {

/// @throws InputError naming `path` when it cannot be opened for writing
void writeFrictionMapCsv(const validation::FrictionMap& map, const std::string& path);

}  // namespace vcontact::report
