#pragma once
// Internal states of one contact pair (MODEL.md §3 "State handling"). Each effect declares its
// states as named slots (Effect::stateSlots); a StateLayout puts the slots one after another,
// and a PairState holds their values in that order.
//
// A slot is a scalar or a world vector in the contact plane. Such a vector (the bristle
// deflection z, a 2-vector of MODEL.md) is stored as a 3-vector with z·n = 0, so that it needs
// no tangent basis that would have to turn with the normal: when the normal turns, the model
// projects it onto the new plane (Model::settle), and every effect reads the projected value.

#include <Eigen/Core>
#include <array>
#include <cassert>
#include <string>
#include <vector>

namespace vcontact::dynamics {

/// One named state of an effect.
struct StateSlot {
  enum class Kind {
    kScalar,       ///< one number
    kPlaneVector,  ///< a world 3-vector kept in the contact plane (projected when n turns)
  };
  std::string name;  ///< e.g. "theta_n"; a plane vector's components are name + x, y, z
  Kind kind = Kind::kScalar;
  std::string unit;         ///< SI unit, "-" for none
  std::string description;  ///< one line

  int size() const { return kind == Kind::kPlaneVector ? 3 : 1; }
};

/// The values of a pair's states in the order of a StateLayout; every state is zero by
/// default. Fixed capacity, so that copies in the integrator's loop do not allocate.
class PairState {
 public:
  static constexpr int kCapacity = 8;  ///< states per pair; StateLayout checks its total

  double& operator[](int i) { return at(i); }
  double operator[](int i) const { return values_[index(i)]; }
  /// The plane vector whose x component is at `offset`.
  Eigen::Map<Eigen::Vector3d> vector(int offset) {
    return Eigen::Map<Eigen::Vector3d>(&at(offset));
  }
  Eigen::Map<const Eigen::Vector3d> vector(int offset) const {
    return Eigen::Map<const Eigen::Vector3d>(&values_[index(offset)]);
  }

  /// Writes the first `size` states to out[0..size).
  void pack(double* out, int size) const {
    for (int i = 0; i < size; ++i) out[i] = values_[index(i)];
  }
  /// A state with the first `size` values from in[0..size), the others zero.
  static PairState unpack(const double* in, int size) {
    PairState s;
    for (int i = 0; i < size; ++i) s[i] = in[i];
    return s;
  }

 private:
  static std::size_t index(int i) {
    assert(i >= 0 && i < kCapacity);
    return static_cast<std::size_t>(i);
  }
  double& at(int i) { return values_[index(i)]; }

  std::array<double, kCapacity> values_{};
};

/// Time derivatives of a PairState, in the same layout (the slots' units per second).
using PairStateRates = PairState;

/// Where each effect's slots sit in a PairState: the slots one after another, in the order in
/// which the effects were added.
class StateLayout {
 public:
  struct Entry {
    std::string effect;  ///< effect id
    StateSlot slot;
    int offset;  ///< index of the slot's first value in a PairState
  };

  /// Appends the slots of effect `id`. @throws std::length_error beyond PairState::kCapacity
  void add(const std::string& id, const std::vector<StateSlot>& slots);

  const std::vector<Entry>& entries() const { return entries_; }
  /// Number of values.
  int size() const { return size_; }
  /// Offset of the first slot of effect `id`, or −1 when it has none.
  int offsetOf(const std::string& id) const;
  /// One name per value: a scalar's name, a plane vector's name + "x", "y", "z".
  std::vector<std::string> valueNames() const;
  /// "<effect> state <value name>" for value i, e.g. "bristle state theta_n".
  /// @pre 0 ≤ i < size()
  std::string describe(int i) const;

 private:
  std::vector<Entry> entries_;
  int size_ = 0;
};

}  // namespace vcontact::dynamics
