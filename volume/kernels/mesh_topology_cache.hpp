#pragma once
// The adjacency of a mesh shape (geometry/mesh_topology.hpp), built on first use and shared
// afterwards, like its bounding-volume tree (kernels/bvh_cache.hpp).

#include <memory>

#include "geometry/mesh_topology.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::volume {

/// The topology of `mesh`; thread-safe. An entry lives as long as its mesh does.
/// @throws InputError when the mesh is not closed and consistently oriented
std::shared_ptr<const geometry::MeshTopology> topologyOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh);

}  // namespace vcontact::volume
