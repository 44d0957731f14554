#include "validation/candidates.hpp"

#include "dynamics/effects/registry.hpp"
#include "geometry/error.hpp"

namespace vcontact::validation {

CandidateSet CandidateSet::library() {
  CandidateSet set;
  for (const auto& id : dynamics::registeredEffectIds()) set.add(dynamics::createEffect(id));
  return set;
}

void CandidateSet::add(std::unique_ptr<dynamics::Effect> prototype) {
  for (const auto& p : prototypes_) {
    if (p->id() == prototype->id()) {
      throw InputError("candidates",
                       "candidate '" + std::string(prototype->id()) + "' appears twice");
    }
  }
  prototypes_.push_back(std::move(prototype));
}

std::vector<std::string> CandidateSet::ids() const {
  std::vector<std::string> ids;
  for (const auto& p : prototypes_) ids.emplace_back(p->id());
  return ids;
}

// A clone, never the prototype itself: diagnose fits candidates in parallel, each on its own
// model, and an expression effect's evaluation writes into its instance.
std::unique_ptr<dynamics::Effect> CandidateSet::create(std::string_view id) const {
  for (const auto& p : prototypes_) {
    if (p->id() == id) return p->clone();
  }
  return dynamics::createEffect(id);
}

}  // namespace vcontact::validation
