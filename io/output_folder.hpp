#pragma once
// The folder a command writes into and the files already in it: checked before any work (a
// folder that cannot be made is bad input, found before a long fit), an input of the command
// never overwritten by one of its outputs, and the temporaries (io/output_file.hpp) that a
// killed run left behind cleaned away.

#include <string>
#include <vector>

namespace vcontact::io {

/// Checks, before any work, that `dir` is a folder or can be made: the nearest part of the path
/// that exists is a folder the process may enter and write in.
/// @throws InputError naming `dir`: "is a file", or the part of the path that stops it and the
///   system's reason (Permission denied, Not a directory, Too many levels of symbolic links)
void checkOutputFolder(const std::string& dir);

/// An input file of a command: its path and what it is to the command ("the dataset's CSV").
struct InputFile {
  std::string path;
  std::string role;
};

/// Refuses to let an output overwrite an input of the same command (`compare --out` into the
/// dataset's folder with a dataset CSV named residuals.csv, issue 36). Paths are compared as the
/// files they name (the same file through another path or a link counts).
/// @throws InputError naming `option` and both files when an output is one of the inputs
void refuseOverwritingInputs(const std::vector<std::string>& outputs,
                             const std::vector<InputFile>& inputs, const std::string& option);

/// Whether `name` (a file name without folder) has the form of a temporary of OutputFile,
/// ".NAME.tmp-PID-N"; its PID in `pid` when so.
bool isTemporaryName(const std::string& name, long& pid);

/// Deletes the temporaries in `dir` whose process no longer runs (a run killed by SIGKILL or
/// a second Ctrl-C leaves its temporaries; a live process's are left alone, and so is every
/// other file). Returns the names deleted.
std::vector<std::string> removeDeadTemporaries(const std::string& dir);

}  // namespace vcontact::io
