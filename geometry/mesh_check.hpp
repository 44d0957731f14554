#pragma once
// Checks a triangle mesh before use and repairs what can be repaired without guessing.
//
// Rejected (InputError, one message naming the defect, its count and the first place):
//   - a non-finite vertex coordinate;
//   - a face index out of range;
//   - a degenerate face (repeated vertex or zero area);
//   - an edge used by one face only (the mesh is not closed) or by more than two;
//   - two faces listing a shared edge in the same direction (inconsistent orientation);
//   - zero enclosed volume;
//   - closed shells that intersect, one that passes through itself (self_intersection.hpp), or
//     one inside another with the same orientation (mesh_repair.hpp, checkShells);
//   - impossible mass properties: a centroid outside the bounds, a negative principal moment of
//     inertia, principal moments breaking the triangle inequality.
// Each message about the surface names the repair (mesh_repair.hpp) that would fix it.
// Repaired with a warning: a consistently inverted mesh (negative enclosed volume) is flipped.

#include <string>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

struct MeshCheckResult {
  std::vector<std::string> warnings;  ///< repairs made, one sentence each
  bool flipped = false;               ///< the faces were inverted and have been flipped
  std::size_t shells = 1;             ///< closed shells (connected parts of the surface)
};

/// @throws InputError (empty source) naming the count and the first vertex with a NaN or
///   infinite coordinate
void checkFinite(const TriangleMesh& mesh);

/// Refuses what no solid has: a centroid outside the mesh's bounding box, a negative principal
/// moment of inertia, principal moments that break the triangle inequality.
/// @pre mesh encloses a positive volume
/// @throws InputError (empty source) naming the figures
void checkMassProperties(const TriangleMesh& mesh);

/// @param[in,out] mesh  the mesh; flipped in place when inverted
/// @throws InputError (empty source: the caller names the file) on any defect listed above
MeshCheckResult checkAndRepair(TriangleMesh& mesh);

}  // namespace vcontact::geometry
