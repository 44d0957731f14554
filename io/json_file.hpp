#pragma once
// Reading and writing a JSON file, with the errors every reader of the project reports the
// same way.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

namespace vcontact::io {

/// Parses the file at `path`, strictly: a key repeated in one object and a number beyond the
/// range of a double are refused (RFC 8259 leaves both to the reader; nlohmann keeps the last
/// key and reads 1e400 as infinity).
/// @throws InputError naming `path`: "no such file", "cannot be read", or
///         "is a folder", "not valid JSON (byte N): …", or "KEY.PATH: …" for a repeated key
///         or an out-of-range number
nlohmann::json readJsonFile(const std::string& path);

/// Parses `text` as readJsonFile parses a file's content (a model handed over as text).
/// @throws InputError naming `source`: "not valid JSON (byte N): …", or "KEY.PATH: …"
nlohmann::json parseJsonText(const std::string& text, const std::string& source);

/// The text of `j` (indented by `indent` spaces; -1 for one line) as every writer of the
/// project puts it out. JSON text is UTF-8, and a string that is not (a file name holding a byte
/// of another encoding, from the command line or the file system) has each invalid byte
/// replaced by U+FFFD, the replacement character: the JSON stays valid and the rest of the
/// name readable (nlohmann's dump threw, an internal error after a whole run, issue 36).
std::string jsonText(const nlohmann::json& j, int indent = 2);

/// Puts `j` on `out` as writeJson writes it (for a file of an io::OutputSet).
void putJson(const nlohmann::json& j, std::ostream& out);

/// Writes `j` with two-space indentation and a final newline.
/// @throws InputError naming `path` when it cannot be opened for writing
void writeJson(const nlohmann::json& j, const std::string& path);

}  // namespace vcontact::io
