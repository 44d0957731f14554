#pragma once
// One entry point over every backend: the interference of two placed shapes by a chosen
// method, or by the best method the pair allows.

#include <Eigen/Geometry>
#include <optional>

#include "geometry/primitives.hpp"
#include "volume/columns.hpp"
#include "volume/contact_volume.hpp"
#include "volume/mesh_mesh.hpp"

namespace vcontact::volume {

/// The method used when none is asked for: analytic for a primitive against a half-space,
/// the exact half-space clip for a mesh against a half-space, the exact local surface
/// integration (fast, mesh_mesh.hpp) for two meshes.
/// @throws InputError when no backend in this build handles the pair
Method defaultMethod(const geometry::Shape& a, const geometry::Shape& b);

/// Does `method` compute the contact of these shapes (whatever their poses)? analytic: a
/// sphere, cylinder or box against a half-space; halfspace: a mesh against a half-space; cgal:
/// two meshes, or a mesh and a half-space; fast: two meshes; columns: two meshes, or a mesh
/// and a half-space. Either order.
bool handles(Method method, const geometry::Shape& a, const geometry::Shape& b);
/// Throws the InputError a query by `method` would throw for these shapes (naming both and
/// what the method computes) unless it handles them: for readers that check before a run.
void requireHandles(Method method, const geometry::Shape& a, const geometry::Shape& b);

/// What a pair of shapes keeps between queries at nearby poses (one per pair and thread;
/// used by the methods that gain from it: `fast`, MeshMeshCache).
struct ContactCache {
  MeshMeshCache meshMesh;
};

/// ContactVolume of A (B1) and B (B2) by `method` (default: defaultMethod). `fast` takes
/// two meshes only: a mesh against a half-space is refused (the halfspace clip is the exact
/// method for it).
/// @param cache  if not null, the pair's memory between queries (ContactCache)
/// @throws InputError when the method does not handle the pair, naming both shapes
ContactVolume computeContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                             const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                             std::optional<Method> method = std::nullopt,
                             ContactCache* cache = nullptr);

/// The column method with its δ map (MODEL.md §1): A and B each a mesh or a half-space, at
/// least one a mesh.
/// @param[out] field  the δ map of the finest grid
/// @param options      grid and tolerance (default: refined to 1e-3)
/// @throws InputError when the pair is not handled, naming both shapes
ContactVolume columnsContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                             const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                             ColumnField* field, const ColumnOptions& options = {});

}  // namespace vcontact::volume
