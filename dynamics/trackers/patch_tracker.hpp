#pragma once
// Which state slot each contact patch of a pair uses (MODEL.md §1: every connected region of
// A ∩ B has its own friction and dwell states). A pair owns a fixed number of slots, so that
// the integrator's state vector keeps its size; the tracker follows a patch from one accepted
// step to the next so that its slot, and with it its bristle deflection and dwell, stays with
// it (docs/SCENARIO.md, "Contact patches").
//
// The rule, applied to the patches of one evaluation against the records of the latest
// accepted step:
//  1. A patch i and the record of slot j are candidates when their normals are within 60°
//     (n_i · n_j ≥ cos 60°, n_j turned with body B) and their centroids are within
//     2 max(r_gyr,i, r_gyr,j) + m_j, where m_j is how far the bodies moved relative to each
//     other at that centroid since the record (the record's point carried by A against the
//     same point carried by B).
//  2. Candidates are taken greedily by increasing centroid distance (ties: patch, then slot
//     index), each patch and slot at most once: a deterministic matching.
//  3. A patch left over takes the lowest free slot (no record, none taken now) and starts
//     from rest (its slot's states were reset when the slot was freed).
//  4. With no free slot the patch has no slot of its own: it reads the states of the slot
//     whose patch (or record) is nearest and integrates none (PatchMatch::without_slot).
// After an accepted step (update) the matched slots record their patches and the others are
// freed, so a vanished patch is dropped; its slot's states are reset by Model::settle.

#include <Eigen/Geometry>
#include <vector>

#include "volume/contact_volume.hpp"

namespace vcontact::dynamics {

/// Where a slot's patch was at the latest accepted step.
struct PatchRecord {
  bool active = false;                             ///< the slot holds a patch
  Eigen::Vector3d p_AC = Eigen::Vector3d::Zero();  ///< centroid in body A's frame, m
  Eigen::Vector3d p_BC = Eigen::Vector3d::Zero();  ///< centroid in body B's frame, m
  Eigen::Vector3d n_B = Eigen::Vector3d::UnitZ();  ///< normal in body B's axes, unit
  double r_gyr = 0.0;                              ///< m
};

/// The slots of one evaluation's patches.
struct PatchMatch {
  std::vector<int> slot;  ///< per patch: its slot, or −1 when it has none
  std::vector<int> host;  ///< per patch: the slot whose states it reads (its own, or nearest)
  int without_slot = 0;   ///< patches with no slot of their own
};

class PatchTracker {
 public:
  /// Normals further apart than this are never the same patch (rule 1).
  static constexpr double kMaxNormalAngleCos = 0.5;  // cos 60°

  /// @pre slots ≥ 1
  explicit PatchTracker(int slots = 1) : records_(static_cast<std::size_t>(slots)) {}

  int slots() const { return static_cast<int>(records_.size()); }
  const std::vector<PatchRecord>& records() const { return records_; }

  /// The slots of `patches` at body poses X_WA, X_WB (rules 1–4); leaves the records as they
  /// are, so every evaluation within a step is matched against the same records.
  void match(const std::vector<volume::ContactVolume>& patches, const Eigen::Isometry3d& X_WA,
             const Eigen::Isometry3d& X_WB, PatchMatch& out) const;

  /// After an accepted step: the slots matched in `m` record their patches, the others are
  /// freed.
  void update(const std::vector<volume::ContactVolume>& patches, const PatchMatch& m,
              const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB);

 private:
  std::vector<PatchRecord> records_;
};

}  // namespace vcontact::dynamics
