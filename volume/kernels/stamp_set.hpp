#pragma once
// A set of small integers (vertex, face or node indices) that empties in O(1) between
// queries: each member carries the epoch it was inserted in; and values kept by such an
// index for one query (StampedValues). The exact clips keep one per
// mesh and thread, so a query costs what it touches, not the mesh's size.

#include <algorithm>
#include <cassert>
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

/// Values computed on first use in a query, by index: slot i holds this query's value when
/// the StampSet says so. The exact clips keep vertices, faces and tree nodes placed for a
/// query in these, so that each is placed once however often the query asks for it.
template <typename T>
class StampedValues {
 public:
  /// Forgets every value and makes room for indices below n.
  void reset(std::size_t n) {
    set_.reset(n);
    if (values_.size() < n) values_.resize(n);
  }
  bool contains(int i) const { return set_.contains(i); }
  /// Slot i. `fresh` is set when it held no value of this query, and the slot now counts as
  /// holding one: the caller fills it.
  T& slot(int i, bool& fresh) {
    fresh = set_.insert(i);
    return values_[static_cast<std::size_t>(i)];
  }
  /// Slot i's value. @pre contains(i)
  T& operator[](int i) {
    assert(contains(i));
    return values_[static_cast<std::size_t>(i)];
  }

 private:
  StampSet set_;
  std::vector<T> values_;
};

}  // namespace vcontact::volume
