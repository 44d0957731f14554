#pragma once
// The effects `diagnose` tries to add (issue 15, item 4): by default every registered effect
// of the library; or the user's own list (`diagnose --candidates FILE`,
// formats/candidates_file.hpp), built-in ids and expression effects alike.
//
// A candidate is a prototype effect: diagnose adds a copy of it, at the prototype's parameter
// values, to the fitted baseline. The effects a candidate requires (MODEL.md §3) come from the
// set when it holds them, else from the library.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dynamics/effect.hpp"

namespace vcontact::validation {

class CandidateSet {
 public:
  /// Every registered effect, in registration order, at its default parameters.
  static CandidateSet library();

  /// Appends a prototype. @throws InputError (source "candidates") on a repeated id
  void add(std::unique_ptr<dynamics::Effect> prototype);

  /// The candidates' ids, in the order they were added.
  std::vector<std::string> ids() const;
  /// A new copy of candidate `id`, or of the registered effect `id`; null when neither exists.
  std::unique_ptr<dynamics::Effect> create(std::string_view id) const;

 private:
  std::vector<std::shared_ptr<const dynamics::Effect>> prototypes_;
};

}  // namespace vcontact::validation
