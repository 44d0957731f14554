#pragma once
// Step 1 of the exact mesh–mesh intersection (fast/surface_integration.hpp): the two
// bounding-volume trees descended together, A's nodes placed in B's frame (each once per query) and
// a node pair kept while its boxes and its slabs (bvh.hpp) overlap; or, with a MeshMeshCache, the
// leaf pairs recorded at a nearby pose retested instead of the descent.

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "geometry/bvh.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/fast/triangle_pair.hpp"
#include "volume/kernels/stamp_set.hpp"

namespace vcontact::volume::internal {

/// A node of A's tree in B's frame: box centre, the half-sizes of the axis-aligned box
/// around A's placed box (|R_BA|·h), normal-cone axis.
struct PlacedNode {
  Eigen::Vector3d center, halfExtent, normalAxis;
};

/// What a descent reuses from one query to the next of a thread.
struct DescentScratch {
  StampedValues<PlacedNode> nodesA;  ///< nodes of A's tree placed in B's frame
  std::vector<std::pair<int, int>> nodeStack;
};

/// The leaf pairs of two trees whose boxes and slabs overlap, at the relative pose X_BA.
class TreePairDescent {
 public:
  /// @param margin  growth of every box and slab, m (covers the rounding of the placements)
  TreePairDescent(const geometry::MeshBvh& a, const geometry::MeshBvh& b,
                  const Eigen::Isometry3d& X_BA, double margin, DescentScratch& scratch);

  /// Calls atLeaves(ia, ib) (node indices of A's and B's trees) for every overlapping pair of
  /// leaves: by descending both trees, or with a cache from its recorded pairs (recorded
  /// again first when it does not cover X_BA, unless its last recording went unused: then
  /// by the plain descent, keeping only the pose). Either way in the same order: the
  /// descent's order, of which a recording keeps a superset (every ancestor of an
  /// overlapping leaf pair overlaps when grown).
  template <typename AtLeaves>
  void forEachLeafPair(MeshMeshCache* cache, const AtLeaves& atLeaves) {
    const auto overlap = [this](int ia, int ib) { return overlaps(ia, ib); };
    if (cache == nullptr) {
      descend(overlap, atLeaves);
      return;
    }
    const bool near = cache->covers(a_, b_, X_BA_);
    if (near && cache->recorded) {
      ++cache->reuses;
    } else if (near || cache->a != &a_ || cache->b != &b_ ||
               cache->reuses > cache->reusesAtRecord) {
      record(*cache);
    } else {
      // The last recording went unused: descend without one, keep the pose (MeshMeshCache).
      ++cache->plain;
      cache->recorded = false;
      cache->X_BA = X_BA_;
      descend(overlap, atLeaves);
      return;
    }
    for (const auto& [ia, ib] : cache->leafPairs) {
      if (overlaps(ia, ib)) atLeaves(ia, ib);
    }
  }

 private:
  /// Do nodes ia of A and ib of B overlap (boxes, then slabs)? Inlined: the descent's inner
  /// loop.
  [[gnu::always_inline]] bool overlaps(int ia, int ib) {
    const geometry::BvhNode& na = a_.nodes()[static_cast<std::size_t>(ia)];
    const geometry::BvhNode& nb = b_.nodes()[static_cast<std::size_t>(ib)];
    const PlacedNode& pa = placeNodeOfA(ia, na);
    return boxesOverlap(pa.center, pa.halfExtent, nb.center, nb.halfExtent, margin_) &&
           slabsOverlap(na, pa.center, pa.normalAxis, nb);
  }

  /// Descends both trees together from the roots: the up to four child pairs of a pair that
  /// `overlap`s are tested before they are pushed (both nodes are split at once, skipping the
  /// intermediate (child, parent) tests); `atLeaves` gets every overlapping pair of leaves.
  template <typename Overlap, typename AtLeaves>
  void descend(const Overlap& overlap, const AtLeaves& atLeaves) {
    const auto& nodesA = a_.nodes();
    const auto& nodesB = b_.nodes();
    auto& stack = scratch_.nodeStack;
    stack.clear();
    if (overlap(0, 0)) stack.emplace_back(0, 0);
    while (!stack.empty()) {
      const auto [ia, ib] = stack.back();
      stack.pop_back();
      const geometry::BvhNode& na = nodesA[static_cast<std::size_t>(ia)];
      const geometry::BvhNode& nb = nodesB[static_cast<std::size_t>(ib)];
      if (na.isLeaf() && nb.isLeaf()) {
        atLeaves(ia, ib);
        continue;
      }
      const int childrenA[2] = {na.isLeaf() ? ia : na.left, na.right};
      const int childrenB[2] = {nb.isLeaf() ? ib : nb.left, nb.right};
      for (int i = 0; i < (na.isLeaf() ? 1 : 2); ++i) {
        for (int j = 0; j < (nb.isLeaf() ? 1 : 2); ++j) {
          if (overlap(childrenA[i], childrenB[j])) stack.emplace_back(childrenA[i], childrenB[j]);
        }
      }
    }
  }

  /// Records in `cache` the leaf pairs whose boxes, A's placed in B's frame at X_BA, overlap
  /// when grown by the cache's reach m (MeshMeshCache): boxes only, since the slab bound of a
  /// turned node is not a grown copy of the old one. A node's placed box at a pose reached by
  /// moving A's points at most m lies within its box here grown by m, so any leaf pair that
  /// overlaps there is among those recorded.
  void record(MeshMeshCache& cache);

  /// Node ia of A's tree in B's frame, placed on first use in this query.
  const PlacedNode& placeNodeOfA(int ia, const geometry::BvhNode& na) {
    bool fresh;
    PlacedNode& P = scratch_.nodesA.slot(ia, fresh);
    if (!fresh) return P;
    P.center = X_BA_ * na.center;
    P.halfExtent = absR_ * na.halfExtent;
    P.normalAxis = X_BA_.linear() * na.normalAxis;
    return P;
  }

  /// The slab bounds of two nodes (bvh.hpp: axial range along the normal axis, radius about
  /// it), both in B's frame: each node's vertices projected onto the other's axis must meet
  /// the other's axial range. Tight where boxes are not: two nearly flat, tilted patches.
  bool slabsOverlap(const geometry::BvhNode& na, const Eigen::Vector3d& centerA,
                    const Eigen::Vector3d& axisA, const geometry::BvhNode& nb) const {
    // cos and sin² of the angle between the axes, the same seen from either node. sin∠ from
    // the cross product: √(1 − k²) cancels for nearly parallel axes (two flat patches nearly
    // face to face) and can lose all its digits.
    const double k = axisA.dot(nb.normalAxis);
    const double sine2 = axisA.cross(nb.normalAxis).squaredNorm();
    // The gap between other's axial range (projected on slab's axis) and slab's own, before
    // other's radial part (≤ radialExtent·sin∠) is added: it must not exceed that part,
    // compared squared so that the descent needs no square root.
    const auto meets = [this, k, sine2](
                           const geometry::BvhNode& slab, const Eigen::Vector3d& slabCenter,
                           const Eigen::Vector3d& slabAxis, const geometry::BvhNode& other,
                           const Eigen::Vector3d& otherCenter) {
      // other's vertices: otherCenter + s·otherAxis + radial part (⟂ axis)
      const double c = (otherCenter - slabCenter).dot(slabAxis);
      const double below =
          c + std::min(k * other.axialLo, k * other.axialHi) - (slab.axialHi + margin_);
      const double above =
          (slab.axialLo - margin_) - (c + std::max(k * other.axialLo, k * other.axialHi));
      const double gap = std::max(below, above);
      return (gap <= 0.0) | (gap * gap <= other.radialExtent * other.radialExtent * sine2);
    };
    return meets(na, centerA, axisA, nb, nb.center) &
           meets(nb, nb.center, nb.normalAxis, na, centerA);
  }

  const geometry::MeshBvh& a_;
  const geometry::MeshBvh& b_;
  Eigen::Isometry3d X_BA_;
  Eigen::Matrix3d absR_;  ///< |R_BA|, elementwise
  double margin_;
  DescentScratch& scratch_;
};

}  // namespace vcontact::volume::internal
