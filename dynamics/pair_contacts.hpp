#pragma once
// The contact of every pair of a scenario at the bodies' poses, for the equations of motion
// (motion_equations.hpp): the one
// caller of the contact query in a run (volume/contact.hpp). It owns what the queries need
// between right-hand sides: the broad phase that screens the pairs (FCL's dynamic AABB tree
// over the bodies' placed bounds, geometry/broad_phase.hpp: a pair whose boxes do not overlap
// gets its contact when apart, V = 0, as the query would say), each pair's contact when apart,
// its query cache and δ map (distributed friction), the choice of the recovered surfaces
// (RecoveredPairs), and, for the discrete stepper, each pair's latest contact, reused instead
// of a query while asked to.
//
// Pairs with an unbounded body (half-space) or a model that moves the payload's pose
// (misalignment) are always queried. A pair whose bodies are both asleep or fixed gets its
// latest contact (the same poses, the same answer) and is counted as a skipped query.

#include <Eigen/Geometry>
#include <atomic>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "dynamics/recovered_pairs.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/scenario.hpp"
#include "geometry/broad_phase.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {

/// Whether a region is in contact with its exact depth left out (NaN: the query skipped the
/// depth pass, QueryOptions::depth).
inline bool depthLeftOut(const volume::ContactVolume& cv) {
  return cv.inContact() && std::isnan(cv.depth);
}

class PairContacts {
 public:
  /// Places every bounded body in the broad phase at its initial pose and checks every pair's
  /// method against its shapes, so that a pair no method handles fails before any output.
  /// @param keep_latest  keep each pair's latest contact (latest(), setReuse; discrete runs)
  /// @throws InputError naming the pair when no method handles it
  PairContacts(const Scenario& scenario, bool keep_latest);

  /// Screens the pairs for the bodies at `kin` (one per body): afterwards queried(k) says
  /// whether pair k's boxes overlap (always, for a pair that is not screened). Bodies that
  /// move are re-placed; fixed ones keep the bounds of their pose. Nothing when no pair is
  /// screened.
  void screen(const std::vector<BodyKinematics>& kin);
  /// Whether pair k's contact is queried at the latest screen (every pair before the first).
  bool queried(std::size_t k) const { return queried_[k] != 0; }
  /// Whether pair k is screened by the broad phase at all.
  bool screened(std::size_t k) const { return screen_key_[k].first >= 0; }

  /// Pair k's contact with the bodies at `kin`: its latest while setReuse is on; its contact
  /// when apart when the broad phase screened it out; its latest when `frozen` (both bodies
  /// asleep or fixed) and no depth is asked of it; otherwise queried. Body A's pose is the one
  /// the pair's model uses (Model::adjustPayloadPose). kSkip queries leave out the exact depth
  /// unless setQueryDepths asks for it, and are counted (queries()); a kDeepest query is an
  /// output sample's (the depths the force evaluations left out), made without the δ map and
  /// the pair's cache so that it leaves the run's state as it was, and not counted.
  /// Thread-safe across pairs (one thread per pair at a time).
  volume::ContactPatches contact(std::size_t k, const std::vector<BodyKinematics>& kin, bool frozen,
                                 volume::DepthMode depth = volume::DepthMode::kSkip);

  /// Pair k's δ map of its latest query (distributed friction), for its model.
  const volume::DepthField& field(std::size_t k) const { return fields_[k]; }
  /// Whether pair k's latest contact lacks a depth (NaN: the query left the pass out).
  bool lacksDepth(std::size_t k) const;

  /// The discrete stepper's modes: contact() returns each pair's latest contact instead of a
  /// query (the models re-evaluated after a settle); the queries compute the exact depth too
  /// (the step that lands on an output time, whose contacts the output reads).
  void setReuse(bool on) { reuse_ = on; }
  bool reusing() const { return reuse_; }
  void setQueryDepths(bool on) { query_depths_ = on; }

  long queries() const { return queries_; }  ///< contact queries made (kSkip ones)
  long skipped() const { return skipped_; }  ///< queries not made: both bodies asleep or fixed
  const RecoveredPairs& recovered() const { return recovered_; }
  /// Starts the recovered pairs' counts again (a new run); the query counts run on.
  void resetCounts() { recovered_.resetCounts(); }

 private:
  const Scenario& scenario_;
  RecoveredPairs recovered_;
  geometry::BroadPhase broad_phase_;
  std::vector<int> broad_id_;                 ///< per body, −1 when unbounded (half-space)
  std::vector<geometry::Aabb> local_bounds_;  ///< per body, its shape's own bounds
  /// Per pair, its bodies' broad-phase ids (smaller first) as overlappingPairs() lists them;
  /// (−1, −1) when it is always queried (a body unbounded, or body A's pose adjusted).
  std::vector<std::pair<int, int>> screen_key_;
  bool any_screened_ = false;
  std::vector<char> queried_;                   ///< per pair, at the latest screen
  std::vector<volume::ContactPatches> apart_;   ///< per pair, its contact when not queried
  std::vector<volume::ContactCache> caches_;    ///< per pair: fast's leaf pairs between queries
  std::vector<volume::DepthField> fields_;      ///< per pair: the δ map (distributed friction)
  std::vector<volume::ContactPatches> latest_;  ///< per pair, with keep_latest only
  bool reuse_ = false;
  bool query_depths_ = false;
  std::atomic<long> queries_ = 0;  // atomic: counted by pairs evaluated side by side
  std::atomic<long> skipped_ = 0;
};

}  // namespace vcontact::dynamics
