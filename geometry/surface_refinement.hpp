#pragma once
// Local refinement of a mesh towards its recognised surfaces (docs/SURFACES.md, "Refinement").
//
// A tessellation is inscribed in its part: the vertices lie on the true surface, the faces cut
// chords through it. Splitting a face k×k and moving the new vertices onto the face's
// recognised surface gives a finer polyhedron, still inscribed, whose chords miss the surface
// by about 1/k² of the original ones (the sagitta of a chord of length L on a radius R is
// L²/(8R)). Only the faces asked for are split; the exact polyhedral methods then run on the
// result, so a contact converges to the true surface's as k grows.
//
// Construction, for a set of faces to split and a level k:
//  1. every face to split is cut into k² triangles by the grid of barycentric points
//     (i/k, j/k); its inner points move to the closest point of its surface;
//  2. a point on an edge moves onto the surface when both faces of the edge lie on that one
//     surface, or when the closest point on one face's surface also lies on the other's (within
//     the recognition tolerance: a cylinder's rim circle lies on its cap plane too); otherwise
//     (a crease between two surfaces that do not agree, an edge of a free-form face) it stays
//     on the chord;
//  3. a face not split that shares an edge with a split face is fan-triangulated about its
//     centroid through the points of its split edges, so the result has no T-junction;
//  4. every other face is copied.
// The result is closed and outward-oriented when the input is (the grid keeps each face's
// orientation). Only faces on a recognised surface other than a plane are split: a plane's
// faces are exact already.

#include <vector>

#include "geometry/surface_recognition.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

struct SurfaceRefinement {
  TriangleMesh mesh;        ///< closed and outward-oriented when the input is
  std::vector<int> origin;  ///< per face of `mesh`: the face of the input it came from
  int level = 1;            ///< k: each split face became k² faces
  int split_faces = 0;      ///< faces split (on curved recognised surfaces)
  int fanned_faces = 0;     ///< faces not split but re-triangulated to meet a split edge
};

/// The point of surface `s` closest to `p` (for every kind: p minus its signed distance along
/// the surface's normal there).
Eigen::Vector3d closestPoint(const RecognisedSurface& s, const Eigen::Vector3d& p);

/// Refines `mesh` around `faces` (indices; faces that are free-form or planar are not split).
/// @param recognition  recogniseSurfaces(mesh)
/// @param level        k ≥ 1 (1: the mesh itself, with the same faces in the same order)
/// @throws std::invalid_argument for level < 1 or a face index out of range
SurfaceRefinement refineSurfaces(const TriangleMesh& mesh, const SurfaceRecognition& recognition,
                                 const std::vector<int>& faces, int level);

/// The largest distance between face f's chord and its recognised surface, sampled at the
/// centroid and the edge midpoints (0 for free-form faces).
double chordGap(const TriangleMesh& mesh, const SurfaceRecognition& recognition, int f);

}  // namespace vcontact::geometry
