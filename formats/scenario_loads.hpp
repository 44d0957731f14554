#pragma once
// The scenario keys of prescribed motion from a table, external loads and springs between
// bodies (docs/SCENARIO.md "Prescribed motion from a table", "Loads", "Springs"); internal
// to formats/scenario_file.cpp.

#include <memory>
#include <string>

#include "dynamics/scenario.hpp"
#include "formats/scenario_reader.hpp"

namespace vcontact::formats::detail {

/// A "motion" object {"csv": PATH, "interpolation": "linear" | "cubic"}: the trajectory of a
/// prescribed body, read from PATH (relative to base_dir).
std::shared_ptr<const dynamics::Trajectory> readTrajectoryMotion(const Reader& r,
                                                                 const std::string& base_dir);

/// "loads": external forces, torques and drives on the bodies of sc.
void readLoads(const Reader& r, const std::string& base_dir, dynamics::Scenario& sc);

/// "springs": spring–dampers between two bodies of sc.
void readSprings(const Reader& r, dynamics::Scenario& sc);

}  // namespace vcontact::formats::detail
