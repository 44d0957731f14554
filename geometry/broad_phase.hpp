#pragma once
// Broad phase: which bodies' world-frame bounding boxes overlap, kept in FCL's dynamic AABB
// tree so that moving a body costs O(log n). FCL types stay in broad_phase.cpp.

#include <memory>
#include <utility>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

class BroadPhase {
 public:
  BroadPhase();
  ~BroadPhase();
  BroadPhase(const BroadPhase&) = delete;
  BroadPhase& operator=(const BroadPhase&) = delete;

  /// Adds a body with its world bounds; returns its id (0, 1, 2, … in order of addition).
  /// @pre box.min ≤ box.max componentwise, all finite
  int add(const Aabb& box_W);
  /// Moves body `id` to new world bounds.
  void update(int id, const Aabb& box_W);
  /// Pairs (i, j), i < j, whose boxes overlap (touching counts), sorted.
  std::vector<std::pair<int, int>> overlappingPairs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// World bounds of a mesh placed by X_WM (the vertices, transformed).
Aabb worldBounds(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM);

}  // namespace vcontact::geometry
