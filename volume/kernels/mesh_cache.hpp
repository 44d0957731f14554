#pragma once
// What is built once from a mesh and shared by every query on it (its bounding-volume tree,
// its edge topology): one cache per kind, keyed by the mesh, living as long as the mesh does.

#include <map>
#include <memory>
#include <mutex>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::volume {

/// The `Derived` of `mesh`, built with `Derived(const TriangleMesh&)` on first use; thread-safe.
template <class Derived>
std::shared_ptr<const Derived> derivedOf(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  struct Entry {
    std::weak_ptr<const geometry::TriangleMesh> mesh;  // detects a freed and reused address
    std::shared_ptr<const Derived> derived;
  };
  static std::mutex mutex;
  static std::map<const geometry::TriangleMesh*, Entry> cache;
  const std::lock_guard lock(mutex);
  // A live entry at this address is this mesh's (two live meshes cannot share an address);
  // the map is swept of dead meshes only when an entry is added, so a query's look-up costs
  // one find (the per-pair entry point asks for a tree and a topology at every query).
  const auto it = cache.find(mesh.get());
  if (it != cache.end() && !it->second.mesh.expired()) return it->second.derived;
  std::erase_if(cache, [](const auto& kv) { return kv.second.mesh.expired(); });
  Entry& e = cache[mesh.get()];
  e = {mesh, std::make_shared<const Derived>(*mesh)};
  return e.derived;
}

}  // namespace vcontact::volume
