#include "volume/kernels/mesh_topology_cache.hpp"

#include "volume/kernels/mesh_cache.hpp"

namespace vcontact::volume {

std::shared_ptr<const geometry::MeshTopology> topologyOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  return derivedOf<geometry::MeshTopology>(mesh);
}

}  // namespace vcontact::volume
