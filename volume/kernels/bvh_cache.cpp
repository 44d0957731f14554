#include "volume/kernels/bvh_cache.hpp"

#include "volume/kernels/mesh_cache.hpp"

namespace vcontact::volume {

std::shared_ptr<const geometry::MeshBvh> bvhOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  return derivedOf<geometry::MeshBvh>(mesh);
}

}  // namespace vcontact::volume
