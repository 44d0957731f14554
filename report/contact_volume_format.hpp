#pragma once
// ContactVolume as a human-readable table or as JSON (schema in README, "vcontact volume").

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "volume/contact_volume.hpp"

namespace vcontact::report {

nlohmann::json toJson(const volume::ContactVolume& cv);
std::string toTable(const volume::ContactVolume& cv);

}  // namespace vcontact::report
