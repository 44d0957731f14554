#pragma once
// A set of small integers (vertex, face or node indices) that empties in O(1) between
// queries: each member carries the epoch it was inserted in. The exact clips keep one per
// mesh and thread, so a query costs what it touches, not the mesh's size.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vcontact::volume {

class StampSet {
 public:
  /// Empties the set and makes room for indices below n.
  void reset(std::size_t n) {
    if (stamp_.size() < n) stamp_.resize(n, 0);
    if (++epoch_ == 0) {  // wrapped: forget every old stamp
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      epoch_ = 1;
    }
  }
  bool contains(int i) const { return stamp_[static_cast<std::size_t>(i)] == epoch_; }
  /// True when i was not in the set.
  bool insert(int i) {
    auto& s = stamp_[static_cast<std::size_t>(i)];
    if (s == epoch_) return false;
    s = epoch_;
    return true;
  }

 private:
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
};

}  // namespace vcontact::volume
