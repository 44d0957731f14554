#include "volume/fast/tree_pair_descent.hpp"

namespace vcontact::volume {

using Eigen::Isometry3d;
using geometry::BvhNode;
using geometry::MeshBvh;

bool MeshMeshCache::covers(const MeshBvh& treeA, const MeshBvh& treeB,
                           const Isometry3d& X_BA_now) const {
  if (a != &treeA || b != &treeB) return false;
  // Every point of A's root box is c + r with |r| ≤ ρ; it moved (in B's frame) by
  // |X_now c − X c + (R_now − R) r| ≤ |X_now c − X c| + ‖R_now − R‖_F ρ.
  const BvhNode& root = treeA.root();
  const double moved = (X_BA_now * root.center - X_BA * root.center).norm() +
                       (X_BA_now.linear() - X_BA.linear()).norm() * root.halfExtent.norm();
  return moved <= reach;
}

namespace internal {

TreePairDescent::TreePairDescent(const MeshBvh& a, const MeshBvh& b, const Isometry3d& X_BA,
                                 double margin, DescentScratch& scratch)
    : a_(a),
      b_(b),
      X_BA_(X_BA),
      absR_(X_BA.linear().cwiseAbs()),
      margin_(margin),
      scratch_(scratch) {
  scratch_.nodesA.reset(a.nodes().size());
}

void TreePairDescent::record(MeshMeshCache& cache) {
  const BvhNode& rootA = a_.root();
  const BvhNode& rootB = b_.root();
  const double reach = MeshMeshCache::kReach * (rootA.halfExtent.norm() + rootB.halfExtent.norm());
  const auto grownOverlap = [&](int ia, int ib) {
    const BvhNode& na = a_.nodes()[static_cast<std::size_t>(ia)];
    const BvhNode& nb = b_.nodes()[static_cast<std::size_t>(ib)];
    const PlacedNode& pa = placeNodeOfA(ia, na);
    return boxesOverlap(pa.center, pa.halfExtent, nb.center, nb.halfExtent, margin_ + reach);
  };
  cache.leafPairs.clear();
  descend(grownOverlap, [&](int ia, int ib) { cache.leafPairs.emplace_back(ia, ib); });
  cache.a = &a_;
  cache.b = &b_;
  cache.X_BA = X_BA_;
  cache.reach = reach;
  cache.recorded = true;
  ++cache.refreshes;
  cache.reusesAtRecord = cache.reuses;
}

}  // namespace internal
}  // namespace vcontact::volume
