#include "volume/contact.hpp"

#include "geometry/error.hpp"
#include "volume/analytic.hpp"
#include "volume/bvh_cache.hpp"
#include "volume/cgal_reference.hpp"
#include "volume/columns.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/mesh_mesh.hpp"
#include "volume/mesh_topology_cache.hpp"

namespace vcontact::volume {
namespace {

bool isHalfspace(const geometry::Shape& s) {
  return std::holds_alternative<geometry::HalfSpace>(s);
}

const geometry::Mesh* meshOf(const geometry::Shape& s) { return std::get_if<geometry::Mesh>(&s); }

/// What `method` computes, for the message of a pair it does not handle.
const char* scope(Method method) {
  switch (method) {
    case Method::kAnalytic:
      return "it takes a sphere, cylinder or box against a half-space";
    case Method::kHalfspace:
      return "it clips a mesh by a half-space";
    case Method::kCgal:
      return "it intersects two meshes, or a mesh and a half-space";
    case Method::kFast:
      return "it intersects two meshes (for a mesh against a half-space use halfspace)";
    case Method::kColumns:
      return "it integrates columns through two meshes, or a mesh and a half-space";
  }
  return "unknown method";
}

[[noreturn]] void unsupported(Method method, const geometry::Shape& a, const geometry::Shape& b) {
  throw InputError("--method " + methodName(method), "cannot compute " + geometry::describe(a) +
                                                         " against " + geometry::describe(b) +
                                                         " with this method; " + scope(method));
}

ContactVolume halfspaceClip(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                            const geometry::Shape& b, const Eigen::Isometry3d& X_WB) {
  if (const auto* m = meshOf(a); m && isHalfspace(b)) {
    return meshHalfspaceContact(*bvhOf(m->mesh), X_WA, X_WB);
  }
  if (const auto* m = meshOf(b); m && isHalfspace(a)) {
    return swapped(meshHalfspaceContact(*bvhOf(m->mesh), X_WB, X_WA));
  }
  unsupported(Method::kHalfspace, a, b);
}

ContactVolume cgalReference(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                            const geometry::Shape& b, const Eigen::Isometry3d& X_WB) {
  const auto* ma = meshOf(a);
  const auto* mb = meshOf(b);
  if (ma && mb) return cgalMeshMeshContact(*ma->mesh, X_WA, *mb->mesh, X_WB);
  if (ma && isHalfspace(b)) return cgalMeshHalfspaceContact(*ma->mesh, X_WA, X_WB);
  if (mb && isHalfspace(a)) return swapped(cgalMeshHalfspaceContact(*mb->mesh, X_WB, X_WA));
  unsupported(Method::kCgal, a, b);
}

ContactVolume fastMeshMesh(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                           const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                           MeshMeshCache* cache) {
  const auto* ma = meshOf(a);
  const auto* mb = meshOf(b);
  if (!ma || !mb) {
    unsupported(Method::kFast, a, b);
  }
  return meshMeshContact(*bvhOf(ma->mesh), *topologyOf(ma->mesh), X_WA, *bvhOf(mb->mesh),
                         *topologyOf(mb->mesh), X_WB, cache);
}

/// A mesh (with its cached tree) or a half-space as a column-method body; null otherwise.
std::optional<ColumnBody> columnBody(const geometry::Shape& s, const Eigen::Isometry3d& X_WS,
                                     std::shared_ptr<const geometry::MeshBvh>& keepAlive) {
  if (isHalfspace(s)) return ColumnBody{nullptr, X_WS};
  const auto* m = meshOf(s);
  if (!m) return std::nullopt;
  keepAlive = bvhOf(m->mesh);
  return ColumnBody{keepAlive.get(), X_WS};
}

}  // namespace

ContactVolume columnsContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                             const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                             ColumnField* field, const ColumnOptions& options) {
  std::shared_ptr<const geometry::MeshBvh> bvhA, bvhB;
  const auto ca = columnBody(a, X_WA, bvhA);
  const auto cb = columnBody(b, X_WB, bvhB);
  if (!ca || !cb || (!bvhA && !bvhB)) {
    unsupported(Method::kColumns, a, b);
  }
  return columnsContact(*ca, *cb, options, field);
}

Method defaultMethod(const geometry::Shape& a, const geometry::Shape& b) {
  if (analyticSupports(a, b)) return Method::kAnalytic;
  if ((meshOf(a) && isHalfspace(b)) || (meshOf(b) && isHalfspace(a))) return Method::kHalfspace;
  if (meshOf(a) && meshOf(b)) return Method::kFast;
  throw InputError("", "no volume method in this build handles " + geometry::describe(a) +
                           " against " + geometry::describe(b));
}

bool handles(Method method, const geometry::Shape& a, const geometry::Shape& b) {
  const bool meshA = meshOf(a) != nullptr, meshB = meshOf(b) != nullptr;
  const bool halfA = isHalfspace(a), halfB = isHalfspace(b);
  switch (method) {
    case Method::kAnalytic:
      return analyticSupports(a, b);
    case Method::kHalfspace:
      return (meshA && halfB) || (meshB && halfA);
    case Method::kCgal:
      return (meshA && (meshB || halfB)) || (meshB && halfA);
    case Method::kFast:
      return meshA && meshB;
    case Method::kColumns:
      return (meshA || halfA) && (meshB || halfB) && (meshA || meshB);
  }
  return false;
}

void requireHandles(Method method, const geometry::Shape& a, const geometry::Shape& b) {
  if (!handles(method, a, b)) unsupported(method, a, b);
}

ContactVolume computeContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                             const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                             std::optional<Method> method, ContactCache* cache) {
  const Method m = method ? *method : defaultMethod(a, b);  // value_or would evaluate eagerly
  switch (m) {
    case Method::kAnalytic:
      return analyticContact(a, X_WA, b, X_WB);
    case Method::kHalfspace:
      return halfspaceClip(a, X_WA, b, X_WB);
    case Method::kCgal:
      return cgalReference(a, X_WA, b, X_WB);
    case Method::kFast:
      return fastMeshMesh(a, X_WA, b, X_WB, cache ? &cache->meshMesh : nullptr);
    case Method::kColumns:
      return columnsContact(a, X_WA, b, X_WB, nullptr);
  }
  unsupported(m, a, b);
}

}  // namespace vcontact::volume
