#include "dynamics/pair_contacts.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "geometry/error.hpp"

namespace vcontact::dynamics {

PairContacts::PairContacts(const Scenario& scenario, bool keep_latest)
    : scenario_(scenario), recovered_(scenario) {
  for (const RigidBody& b : scenario_.bodies) {
    const std::optional<geometry::Aabb> box = geometry::localBounds(b.shape);
    local_bounds_.push_back(
        box.value_or(geometry::Aabb{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}));
    broad_id_.push_back(box ? broad_phase_.add(geometry::placedBounds(*box, b.X_WB0)) : -1);
  }
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    const ContactPair& p = scenario_.pairs[k];
    const bool screened =
        broad_id_[p.a] >= 0 && broad_id_[p.b] >= 0 && !p.model.adjustsPayloadPose();
    const std::pair<int, int> ids = std::minmax(broad_id_[p.a], broad_id_[p.b]);
    screen_key_.push_back(screened ? ids : std::make_pair(-1, -1));
    any_screened_ = any_screened_ || screened;
    const geometry::Shape& a = scenario_.bodies[p.a].shape;
    const geometry::Shape& b = scenario_.bodies[p.b].shape;
    apart_.emplace_back();
    try {
      const std::optional<volume::Method> asked = recovered_.method(k, p.method);
      const volume::Method m = asked ? *asked
                               : p.friction == FrictionMode::kDistributed
                                   ? volume::defaultDepthFieldMethod(a, b)
                                   : volume::defaultMethod(a, b);
      volume::requireHandles(m, a, b);
      apart_.back().aggregate.method = m;
    } catch (const InputError& e) {
      throw InputError("pair '" + p.name + "'", e.message());
    }
  }
  queried_.assign(scenario_.pairs.size(), 1);
  caches_.resize(scenario_.pairs.size());
  fields_.resize(scenario_.pairs.size());
  if (keep_latest) latest_.resize(scenario_.pairs.size());
}

void PairContacts::screen(const std::vector<BodyKinematics>& kin) {
  if (!any_screened_) return;
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    if (broad_id_[i] < 0 || scenario_.bodies[i].motion == BodyMotion::kFixed) continue;
    broad_phase_.update(broad_id_[i], geometry::placedBounds(local_bounds_[i], kin[i].X_WB));
  }
  const std::vector<std::pair<int, int>> overlapping = broad_phase_.overlappingPairs();  // sorted
  for (std::size_t k = 0; k < scenario_.pairs.size(); ++k) {
    if (screen_key_[k].first < 0) continue;
    queried_[k] = std::binary_search(overlapping.begin(), overlapping.end(), screen_key_[k]);
  }
}

// The force evaluations skip the exact depth (kSkip: the model does not use it, and for `fast`
// it costs several times the rest of the query) unless query_depths_ asks for it.
volume::ContactPatches PairContacts::contact(std::size_t k, const std::vector<BodyKinematics>& kin,
                                             bool frozen, volume::DepthMode depth) {
  const ContactPair& pair = scenario_.pairs[k];
  if (reuse_) return latest_[k];
  if (!queried_[k]) {
    if (!latest_.empty()) latest_[k] = apart_[k];
    return apart_[k];
  }
  if (frozen && depth == volume::DepthMode::kSkip && !(query_depths_ && lacksDepth(k))) {
    assert(!latest_.empty());  // only the discrete stepper puts bodies to sleep
    ++skipped_;                // each body asleep or fixed: the same poses, the same answer
    return latest_[k];
  }
  // the constructor checked that the method takes the pair's shapes
  const bool distributed = pair.friction == FrictionMode::kDistributed;
  const Eigen::Isometry3d X_WA = pair.model.adjustPayloadPose(kin[pair.a].X_WB, kin[pair.b].X_WB);
  const geometry::Shape& shapeA = scenario_.bodies[pair.a].shape;
  const geometry::Shape& shapeB = scenario_.bodies[pair.b].shape;
  volume::QueryOptions query{recovered_.method(k, pair.method),
                             distributed ? pair.column_resolution : 0, depth};
  if (depth == volume::DepthMode::kDeepest) {
    return volume::computeContact(shapeA, X_WA, shapeB, kin[pair.b].X_WB, query);
  }
  if (query_depths_) query.depth = volume::DepthMode::kDeepest;
  ++queries_;
  volume::ContactPatches contact =
      volume::computeContact(shapeA, X_WA, shapeB, kin[pair.b].X_WB, query,
                             distributed ? &fields_[k] : nullptr, &caches_[k]);
  recovered_.count(k, contact);
  if (!latest_.empty()) latest_[k] = contact;
  return contact;
}

bool PairContacts::lacksDepth(std::size_t k) const {
  const volume::ContactPatches& c = latest_[k];
  return depthLeftOut(c.aggregate) || std::any_of(c.patches.begin(), c.patches.end(), depthLeftOut);
}

}  // namespace vcontact::dynamics
