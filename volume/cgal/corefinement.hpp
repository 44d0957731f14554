#pragma once
// The exact reference for two meshes: CGAL corefinement (exact constructions) of the two
// closed meshes, then the moments of the intersection polyhedron by the divergence theorem.
// Slow (milliseconds); it is the oracle the fast methods are tested and timed against.

#include <Eigen/Geometry>

#include "geometry/primitives.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// The patches of mesh A (the payload, pose X_WA) and mesh B (the plate or other body, pose X_WB):
/// the connected components of the corefined intersection polyhedron (PMP::connected_components),
/// each by the formulas below from its own faces, sorted by sortPatches, beside the whole region as
/// the aggregate:
///   V, p_c, Σ from the fan of the intersection's faces about a point of the region;
///   n ∝ ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA = −2 ∫_{∂A∩B} n_A dA (MODEL.md §1; the
///   region's boundary is closed, so the two parts' area vectors cancel);
///   area = ½ Σ_faces |n_f·n| A_f, the projection of the region onto the plate, exact when
///   every column along n crosses the region once; depth = max over the plate of δ(s), the
///   deepest column along n, from the intersection's faces (depth/deepest_column.hpp, exact under
///   the same condition).
/// @pre both meshes closed, outward-oriented and free of self-intersections, without cavities
ContactPatches cgalMeshMeshContact(const geometry::TriangleMesh& a, const Eigen::Isometry3d& X_WA,
                                   const geometry::TriangleMesh& b, const Eigen::Isometry3d& X_WB);

/// The same for a mesh (body A) against a half-space (body B, pose X_WH), the half-space modelled
/// as a box whose top face is the plane and which encloses the mesh's part below it; n = +z_H.
ContactPatches cgalMeshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                        const Eigen::Isometry3d& X_WM,
                                        const Eigen::Isometry3d& X_WH);

/// The method table's backend of `cgal` (methods.hpp): two meshes, or a mesh and a half-space
/// in either order.
/// @pre a and b both meshes, or one a mesh and the other a half-space
ContactPatches cgalContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                           const geometry::Shape& b, const Eigen::Isometry3d& X_WB);

}  // namespace vcontact::volume
