#include "volume/mesh_topology_cache.hpp"

#include <map>
#include <mutex>

namespace vcontact::volume {
namespace {

struct Entry {
  std::weak_ptr<const geometry::TriangleMesh> mesh;  // detects a freed and reused address
  std::shared_ptr<const geometry::MeshTopology> topology;
};

}  // namespace

std::shared_ptr<const geometry::MeshTopology> topologyOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  static std::mutex mutex;
  static std::map<const geometry::TriangleMesh*, Entry> cache;
  const std::lock_guard lock(mutex);
  std::erase_if(cache, [](const auto& kv) { return kv.second.mesh.expired(); });
  Entry& e = cache[mesh.get()];
  if (!e.topology) e = {mesh, std::make_shared<const geometry::MeshTopology>(*mesh)};
  return e.topology;
}

}  // namespace vcontact::volume
