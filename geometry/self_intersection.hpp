#pragma once
// One closed shell that passes through itself (a corner pushed through the opposite face, a
// CAD export whose fillet folds over): every check of closedness and orientation passes, yet
// the divergence-theorem sums count the overlap twice or with the wrong sign, so that volume,
// centroid and inertia are wrong (issue 36: a centroid outside the part, a negative moment).
// Found as CGAL's does_self_intersect finds it (Polygon Mesh Processing: a box-intersection pass
// over the faces' bounding boxes, CGAL::box_self_intersection_d, then exact predicates on the
// candidate pairs: O(n log n) for a mesh without intersections), with double-arithmetic
// shortcuts, error-bounded, for the pairs that certainly do not intersect (on the flat regions
// of CAD parts the exact fallback of CGAL's filtered predicates cost more than reading the
// file), and removed on request with CGAL's autorefinement, which cuts
// the faces along their intersections and keeps the outer layer. CGAL stays in the .cpp.

#include <optional>
#include <string>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

/// Two faces that intersect other than along the edges and corners they share.
struct SelfIntersection {
  Eigen::Index face_a = -1, face_b = -1;         ///< the first pair found (face indices)
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  ///< a corner of face_a, to find the place
};

/// @param[in] mesh  closed, consistently oriented, finite, without degenerate faces
/// @return the first pair of faces that intersect, or nullopt
std::optional<SelfIntersection> findSelfIntersection(const TriangleMesh& mesh);

/// Cuts the faces of `mesh` along their intersections and keeps the outer layer (CGAL's
/// experimental::autorefine_and_remove_self_intersections).
/// @return what was changed, one sentence; empty when the mesh does not intersect itself
/// @throws InputError (empty source) when the intersections cannot all be removed
std::string removeSelfIntersections(TriangleMesh& mesh);

}  // namespace vcontact::geometry
