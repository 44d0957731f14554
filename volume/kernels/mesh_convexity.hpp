#pragma once
// Whether a mesh shape bounds a convex solid, decided once per mesh and shared, like its tree
// (kernels/bvh_cache.hpp): a convex body meets a half-space in one region, so its clip needs no
// patch labels at all.

#include <memory>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::volume {

/// The convexity of one mesh: one closed shell whose every edge is convex (the far corner of
/// each face lies on or below the plane of its neighbour across the edge; a fold below 1e-9
/// rad counts as flat). An embedded closed surface that is locally convex at every edge
/// bounds a convex solid. An open or inconsistently oriented mesh counts as not convex.
struct MeshConvexity {
  explicit MeshConvexity(const geometry::TriangleMesh& mesh);
  bool convex = false;
};

/// Is `mesh` convex (MeshConvexity)? Built on first use and shared afterwards; thread-safe.
bool isConvex(const std::shared_ptr<const geometry::TriangleMesh>& mesh);

}  // namespace vcontact::volume
