#pragma once
// Exact interference of a closed triangle mesh with a half-space: the polyhedron clipped by
// the plane, integrated by the divergence theorem over the clipped triangles.

#include <Eigen/Geometry>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/moments.hpp"
#include "geometry/primitives.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// Moments of (mesh ∩ {z_H ≤ 0}) about a point o on the plane, in the half-space frame H.
struct ClippedMoments {
  geometry::Moments moments;                         ///< about o, H axes
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< o, in H, with o.z = 0
  double area = 0.0;   ///< projected area of the downward-facing clipped faces onto z = 0, m²
  double depth = 0.0;  ///< −min z_H over the vertices, m (≤ 0: apart)
};

/// Clips every triangle (O(n)); the reference the accelerated clip is checked against.
/// With the apex of every tetrahedron on the plane, the cap polygon contributes nothing
/// and need not be built. o is the deepest vertex projected onto the plane, so that the
/// terms stay of the size of the region (a shallow 1 µm contact keeps its digits).
/// @param X_HM  pose of the mesh frame M in the half-space frame H
ClippedMoments clipMeshByHalfspace(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_HM);

/// The same clip accelerated by the mesh's bounding-volume tree: a subtree wholly below the
/// plane adds its fan moments about o in O(1) from the cached FanIntegrals (fan_integrals.hpp),
/// a subtree wholly above is skipped, and only the leaves that straddle the plane are clipped
/// triangle by triangle, as in the reference. Same o, so the same digits survive at shallow
/// depth. The projected area uses each node's normal cone and descends only where the faces
/// of a wholly-below subtree do not all face one way.
/// @param X_HM  pose of the mesh frame M in the half-space frame H
ClippedMoments clipMeshByHalfspace(const geometry::MeshBvh& bvh, const Eigen::Isometry3d& X_HM);

/// ContactVolume of a mesh body (pose X_WM) against a half-space (pose X_WH); the mesh is body A.
/// This overload runs the O(n) reference clip.
ContactVolume meshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH);

/// As above, by the accelerated clip.
ContactVolume meshHalfspaceContact(const geometry::MeshBvh& bvh, const Eigen::Isometry3d& X_WM,
                                   const Eigen::Isometry3d& X_WH);

/// The patches of a mesh body against a half-space: the connected components of the clipped
/// solid, each clipped about its own deepest vertex, beside the accelerated clip's aggregate
/// (bit-identical to meshHalfspaceContact). A query whose straddling faces close into one
/// cap loop on a one-shell mesh is one patch, the aggregate, at the cost of following that
/// loop; any other pays O(faces below the plane) to label the components (a cup cut through
/// its walls is one component joined through its annular cap).
/// @pre the mesh's shells are not nested (no cavities)
ContactPatches meshHalfspacePatches(const geometry::MeshBvh& bvh,
                                    const geometry::MeshTopology& topo,
                                    const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH);

/// The method table's backend of `halfspace` (methods.hpp): a mesh (A or B, its tree from
/// kernels/bvh_cache.hpp, its topology from kernels/mesh_topology_cache.hpp) against a half-space,
/// by meshHalfspacePatches, in either order; a convex mesh (kernels/mesh_convexity.hpp) is one
/// patch, the accelerated clip alone.
/// @pre one of a, b a mesh and the other a half-space
ContactPatches halfspaceClipContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                                    const geometry::Shape& b, const Eigen::Isometry3d& X_WB);

/// Turns moments about o in H into a ContactVolume in W with n = +z_H (the half-space is body B).
ContactVolume contactFromClippedMoments(const ClippedMoments& clipped,
                                        const Eigen::Isometry3d& X_WH, Method method);

}  // namespace vcontact::volume
