#pragma once
// The names of the files vcontact reads and writes: a name made safe for a file (a pair's
// output file), and extensions compared without regard to case (".OBJ" is ".obj"), everywhere
// a format is chosen by its extension.

#include <string>

namespace vcontact::io {

/// A file-name-safe form of a name: letters, digits, '-', '_' kept, every other byte '_'.
/// Names that differ only in the other bytes ("ball a", "ball_a") give the same text: a
/// reader that names files after names refuses such pairs (formats/scenario_file.cpp).
std::string fileSafe(const std::string& name);

/// The extension of `path` in lower case, with its dot (".stl"); "" when it has none.
std::string lowerExtension(const std::string& path);

/// Whether `path` ends in the extension `ext` (lower case, with its dot), in any case.
bool hasExtension(const std::string& path, const std::string& ext);

}  // namespace vcontact::io
