#pragma once
// ContactVolume and ContactPatches as a human-readable table or as JSON (schema in README,
// "vcontact volume").

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "volume/contact_volume.hpp"

namespace vcontact::report {

nlohmann::json toJson(const volume::ContactVolume& cv);
std::string toTable(const volume::ContactVolume& cv);

/// The aggregate's fields, in_contact (true with at least one patch) and "patches": every
/// patch with every field of a ContactVolume, in the order of the list (sortPatches).
nlohmann::json toJson(const volume::ContactPatches& contact);
/// The aggregate's table, the patch count, and each patch's table when there are several.
std::string toTable(const volume::ContactPatches& contact);

}  // namespace vcontact::report
