#include "dynamics/pair_state.hpp"

#include <cassert>
#include <stdexcept>

namespace vcontact::dynamics {

void StateLayout::add(const std::string& id, const std::vector<StateSlot>& slots) {
  for (const StateSlot& slot : slots) {
    if (size_ + slot.size() > PairState::kCapacity) {
      throw std::length_error("the effects' states need more than PairState::kCapacity = " +
                              std::to_string(PairState::kCapacity) + " values; raise it");
    }
    entries_.push_back({id, slot, size_});
    size_ += slot.size();
  }
}

int StateLayout::offsetOf(const std::string& id) const {
  for (const Entry& e : entries_) {
    if (e.effect == id) return e.offset;
  }
  return -1;
}

std::vector<std::string> StateLayout::valueNames() const {
  std::vector<std::string> names;
  for (const Entry& e : entries_) {
    if (e.slot.kind == StateSlot::Kind::kScalar) {
      names.push_back(e.slot.name);
      continue;
    }
    for (const char* axis : {"x", "y", "z"}) names.push_back(e.slot.name + axis);
  }
  return names;
}

std::string StateLayout::describe(int i) const {
  assert(i >= 0 && i < size_);
  const std::vector<std::string> names = valueNames();
  for (const Entry& e : entries_) {
    if (i < e.offset + e.slot.size()) return e.effect + " state " + names[std::size_t(i)];
  }
  return {};
}

}  // namespace vcontact::dynamics
