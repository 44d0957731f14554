#pragma once
// Broad phase: which bodies' world-frame bounding boxes overlap, kept in FCL's dynamic AABB
// tree so that moving a body costs O(log n). FCL types stay in broad_phase.cpp.

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/primitives.hpp"
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

/// The shape's bounds in its own frame (a mesh's vertices, a primitive's extent); none for a
/// half-space, which no box holds.
std::optional<Aabb> localBounds(const Shape& shape);

/// World bounds of a shape-frame box placed by X_WS: the axis-aligned box around the turned
/// box (O(1), looser than worldBounds for a turned mesh), grown on every side by 1e-9 of its
/// size and distance from the origin, which covers the rounding of the placement many times
/// over: a shape lies inside its placed bounds even as rounded.
Aabb placedBounds(const Aabb& local, const Eigen::Isometry3d& X_WS);

}  // namespace vcontact::geometry
