#include "dynamics/patch_tracker.hpp"

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

}  // namespace

void PatchTracker::match(const std::vector<volume::ContactVolume>& patches,
                         const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB,
                         PatchMatch& out) const {
  const int np = static_cast<int>(patches.size()), ns = slots();
  out.slot.assign(patches.size(), -1);
  out.host.assign(patches.size(), -1);
  out.without_slot = 0;
  std::vector<Candidate> candidates;
  for (int i = 0; i < np; ++i) {
    for (int j = 0; j < ns; ++j) {
      if (!records_[std::size_t(j)].active) continue;
      const double d = gatedDistance(patches[std::size_t(i)], records_[std::size_t(j)], X_WA, X_WB);
      if (d >= 0.0) candidates.push_back({d, i, j});
    }
  }
  std::sort(candidates.begin(), candidates.end());  // rule 2
  std::vector<char> taken(records_.size(), 0);
  for (const Candidate& c : candidates) {
    if (out.slot[std::size_t(c.patch)] >= 0 || taken[std::size_t(c.slot)]) continue;
    out.slot[std::size_t(c.patch)] = c.slot;
    taken[std::size_t(c.slot)] = 1;
  }
  for (int i = 0; i < np; ++i) {  // rule 3
    if (out.slot[std::size_t(i)] >= 0) continue;
    for (int j = 0; j < ns; ++j) {
      if (records_[std::size_t(j)].active || taken[std::size_t(j)]) continue;
      out.slot[std::size_t(i)] = j;
      taken[std::size_t(j)] = 1;
      break;
    }
  }
  // Rule 4: where each slot's patch is now (its matched patch, else its record).
  std::vector<Eigen::Vector3d> where(records_.size());
  for (int j = 0; j < ns; ++j) where[std::size_t(j)] = X_WB * records_[std::size_t(j)].p_BC;
  for (int i = 0; i < np; ++i) {
    if (out.slot[std::size_t(i)] >= 0)
      where[std::size_t(out.slot[std::size_t(i)])] = patches[std::size_t(i)].p_WC;
  }
  for (int i = 0; i < np; ++i) {
    out.host[std::size_t(i)] = out.slot[std::size_t(i)];
    if (out.slot[std::size_t(i)] >= 0) continue;
    ++out.without_slot;
    double best = std::numeric_limits<double>::infinity();
    for (int j = 0; j < ns; ++j) {
      const double d = (where[std::size_t(j)] - patches[std::size_t(i)].p_WC).norm();
      if (d < best) {
        best = d;
        out.host[std::size_t(i)] = j;
      }
    }
  }
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
