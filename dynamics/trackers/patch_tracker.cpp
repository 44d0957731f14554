#include "dynamics/trackers/patch_tracker.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

namespace vcontact::dynamics {
namespace {

struct Candidate {
  double distance;
  int patch;
  int slot;
  bool operator<(const Candidate& o) const {
    return std::tie(distance, patch, slot) < std::tie(o.distance, o.patch, o.slot);
  }
};

// Rule 1 for patch p against record r: the centroid distance when they may be the same patch,
// or a negative number when they may not.
double gatedDistance(const volume::ContactVolume& p, const PatchRecord& r,
                     const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) {
  if (p.n_W.dot(X_WB.linear() * r.n_B) < PatchTracker::kMaxNormalAngleCos) return -1.0;
  const Eigen::Vector3d by_B = X_WB * r.p_BC;
  const double moved = (X_WA * r.p_AC - by_B).norm();
  const double reach = 2.0 * std::max(p.r_gyr, r.r_gyr) + moved;
  const double d = (p.p_WC - by_B).norm();
  return d <= reach ? d : -1.0;
}

// Rules 1 and 2: each patch to the nearest record that may be the same patch, greedily.
void matchRecords(const std::vector<volume::ContactVolume>& patches,
                  const std::vector<PatchRecord>& records, const Eigen::Isometry3d& X_WA,
                  const Eigen::Isometry3d& X_WB, std::vector<int>& slot, std::vector<char>& taken) {
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    for (std::size_t j = 0; j < records.size(); ++j) {
      if (!records[j].active) continue;
      const double d = gatedDistance(patches[i], records[j], X_WA, X_WB);
      if (d >= 0.0) candidates.push_back({d, int(i), int(j)});
    }
  }
  std::sort(candidates.begin(), candidates.end());
  for (const Candidate& c : candidates) {
    if (slot[std::size_t(c.patch)] >= 0 || taken[std::size_t(c.slot)]) continue;
    slot[std::size_t(c.patch)] = c.slot;
    taken[std::size_t(c.slot)] = 1;
  }
}

// Rule 3: the patches left over take the lowest free slots.
void takeFreeSlots(const std::vector<PatchRecord>& records, std::vector<int>& slot,
                   std::vector<char>& taken) {
  for (int& s : slot) {
    if (s >= 0) continue;
    for (std::size_t j = 0; j < records.size(); ++j) {
      if (records[j].active || taken[j]) continue;
      s = int(j);
      taken[j] = 1;
      break;
    }
  }
}

// Rule 4: a patch without a slot reads the slot whose patch (matched now, else its record)
// is nearest.
void chooseHosts(const std::vector<volume::ContactVolume>& patches,
                 const std::vector<PatchRecord>& records, const Eigen::Isometry3d& X_WB,
                 PatchMatch& out) {
  std::vector<Eigen::Vector3d> where(records.size());
  for (std::size_t j = 0; j < records.size(); ++j) where[j] = X_WB * records[j].p_BC;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (out.slot[i] >= 0) where[std::size_t(out.slot[i])] = patches[i].p_WC;
  }
  out.host = out.slot;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (out.slot[i] >= 0) continue;
    ++out.without_slot;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < records.size(); ++j) {
      const double d = (where[j] - patches[i].p_WC).norm();
      if (d < best) {
        best = d;
        out.host[i] = int(j);
      }
    }
  }
}

}  // namespace

void PatchTracker::match(const std::vector<volume::ContactVolume>& patches,
                         const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB,
                         PatchMatch& out) const {
  out.slot.assign(patches.size(), -1);
  out.without_slot = 0;
  std::vector<char> taken(records_.size(), 0);
  matchRecords(patches, records_, X_WA, X_WB, out.slot, taken);
  takeFreeSlots(records_, out.slot, taken);
  chooseHosts(patches, records_, X_WB, out);
}

void PatchTracker::update(const std::vector<volume::ContactVolume>& patches, const PatchMatch& m,
                          const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) {
  for (PatchRecord& r : records_) r.active = false;
  for (std::size_t i = 0; i < patches.size() && i < m.slot.size(); ++i) {
    if (m.slot[i] < 0) continue;
    const volume::ContactVolume& p = patches[i];
    PatchRecord& r = records_[std::size_t(m.slot[i])];
    r.active = true;
    r.p_AC = X_WA.inverse() * p.p_WC;
    r.p_BC = X_WB.inverse() * p.p_WC;
    r.n_B = X_WB.linear().transpose() * p.n_W;
    r.r_gyr = p.r_gyr;
  }
}

}  // namespace vcontact::dynamics
