#pragma once
// The bounding-volume tree of a mesh shape, built on first use and shared afterwards, so that
// the per-pair entry point (computeContact) pays the O(n log n) build once per mesh.

#include <memory>

#include "geometry/bvh.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::volume {

/// The tree of `mesh`; thread-safe. An entry lives as long as its mesh does.
std::shared_ptr<const geometry::MeshBvh> bvhOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh);

}  // namespace vcontact::volume
