#pragma once
// Reading and writing a JSON file, with the errors every reader of the project reports the
// same way.

#include <nlohmann/json.hpp>
#include <string>

namespace vcontact::io {

/// Parses the file at `path`.
/// @throws InputError naming `path`: "no such file", "cannot be read", or
///         "not valid JSON (byte N): …"
nlohmann::json readJsonFile(const std::string& path);

/// Writes `j` with two-space indentation and a final newline.
/// @throws InputError naming `path` when it cannot be opened for writing
void writeJson(const nlohmann::json& j, const std::string& path);

}  // namespace vcontact::io
