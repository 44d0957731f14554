#pragma once
// The one error type for bad input (files, command line, public API).
// It carries where the input came from, the place in it, and what was expected,
// so that a message reads "part.stl: 3 boundary edges, mesh is not closed; ...".

#include <stdexcept>
#include <string>

namespace vcontact {

class InputError : public std::runtime_error {
 public:
  /// @param source  file name or other origin ("part.stl", "--pose-a"); may be empty
  /// @param message what is wrong and what was expected
  InputError(std::string source, std::string message)
      : std::runtime_error(source.empty() ? message : source + ": " + message),
        source_(std::move(source)),
        message_(std::move(message)) {}

  const std::string& source() const { return source_; }
  const std::string& message() const { return message_; }

  /// The same error attributed to another source (used when a reader knows the file name
  /// but a deeper check raised the error).
  InputError withSource(const std::string& source) const { return InputError(source, message_); }

 private:
  std::string source_;
  std::string message_;
};

}  // namespace vcontact
