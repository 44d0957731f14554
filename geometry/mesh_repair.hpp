#pragma once
// Repairs of a triangle soup read from a CAD file, each one a step of CGAL's Polygon Mesh
// Processing, and the test that a mesh's closed shells bound one solid (no two overlap, none
// sits inside another with the same orientation). The CGAL types stay in mesh_repair.cpp.
//
// Repair steps, in order (each reports what it changed, with a count and the first place):
//   1. weld vertices closer than RepairOptions::weldTolerance (relative to the bounding-box
//      diagonal) and merge the now equal points (merge_duplicate_points_in_polygon_soup);
//   2. drop duplicate faces and faces left with a repeated corner (repair_polygon_soup);
//   3. orient the faces consistently (orient_polygon_soup);
//   4. stitch border edges that coincide (stitch_borders);
//   5. drop zero-area faces, re-stitching their neighbours (remove_degenerate_faces);
//   6. when asked, fill holes whose boundary is shorter than kSmallHolePerimeter of the
//      diagonal (triangulate_hole);
//   7. turn outward the closed shells that lie inside no other and face inward
//      (volume_connected_components, reverse_face_orientations); a nested shell keeps its
//      orientation (inward: a cavity; outward: refused by checkShells);
//   8. when asked, remove the intersections of a closed surface with itself
//      (experimental::autorefine_and_remove_self_intersections, geometry/self_intersection.hpp).

#include <string>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

/// Default weld tolerance, a fraction of the bounding-box diagonal. CAD exporters write
/// single-precision coordinates (STL is float on disk): a seam's two copies of a vertex differ
/// by the float rounding of a coordinate, 2⁻²⁴ ≈ 6e-8 of its magnitude. 1e-6 is 16 of those
/// for a part whose coordinates are up to its own size, and 1000 times below a 1 mm feature
/// on a 1 m part, so no real edge is welded shut.
inline constexpr double kDefaultWeldTolerance = 1e-6;

/// Holes filled on request are at most this fraction of the diagonal around: a missing facet
/// of a coarse tessellation (a 24-segment sphere's is 0.22) or a pin-hole of an export, not a
/// missing side of the part (a box side is 1.5 to 2 diagonals around).
inline constexpr double kSmallHolePerimeter = 0.5;

struct RepairOptions {
  double weldTolerance = kDefaultWeldTolerance;  ///< fraction of the bounding-box diagonal
  bool fillHoles = false;
  /// step 8: cut a closed surface that passes through itself along its intersections and keep
  /// the outer layer (geometry/self_intersection.hpp)
  bool removeSelfIntersections = false;
};

/// What the refusal of a surface that passes through itself says to do.
inline constexpr const char* kSelfIntersectionHint =
    "'vcontact mesh-repair FILE --out FIXED.stl --remove-self-intersections' cuts the faces "
    "along the intersections and keeps the outer layer (CGAL's autorefinement), or repair it "
    "in a mesh editor (MeshLab: Filters > Cleaning and Repairing > Select Self Intersecting "
    "Faces)";

struct RepairResult {
  TriangleMesh mesh;
  std::vector<std::string> changes;  ///< one sentence per repair that changed something
};

/// @param[in] soup  triangles with finite coordinates and valid indices, in any state
/// @throws InputError (empty source) when no face is left
RepairResult repairMesh(const TriangleMesh& soup, const RepairOptions& options);

/// Triangles covering one planar polygon (CGAL's triangulate_hole_polyline).
/// @param[in] corners the polygon's corners in order, at least 3
/// @return index triples into `corners`, oriented as the polygon
std::vector<Eigen::Vector3i> triangulatePolygon(const std::vector<Eigen::Vector3d>& corners);

/// Shells of a closed, consistently oriented mesh (CGAL's volume_connected_components).
/// @return the number of closed shells
/// @throws InputError (empty source) when two shells intersect or touch (CGAL counts a shared
///   point as an intersection), a shell intersects itself (does_self_intersect), or a shell
///   lies inside another with an orientation that does not make it a cavity (their volumes
///   would add)
std::size_t checkShells(const TriangleMesh& mesh);

}  // namespace vcontact::geometry
