#pragma once
// The steps of surface recognition (geometry/surface_recognition.hpp), each in its own file:
// the sample points (surface_samples.cpp), CGAL's RANSAC (surface_detection.cpp) and the
// Ceres polish (surface_fit.cpp).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/mesh_topology.hpp"
#include "geometry/surface_recognition.hpp"

namespace vcontact::geometry::detail {

/// The points RANSAC sees. First each vertex seen from each side of the creases through it:
/// its position and the angle-weighted normal of the faces on that side. Then, in a smooth
/// region with few vertices, four points inside each face (its centroid, and a point nearer
/// each corner) with the normal interpolated from its corners' normals: CGAL accepts no shape
/// of fewer than 10 points, and a box face has only 4 corners.
struct SamplePoints {
  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Vector3d> normal;
  std::vector<int> vertex;  ///< the mesh vertex of each sample; −1 inside a face
  std::vector<int> face;    ///< the face of a sample inside one; a face of a vertex's side
};

/// Unit face normals (zero for a face of no area).
std::vector<Eigen::Vector3d> faceNormals(const TriangleMesh& mesh);

/// The smooth regions of the mesh (faces joined across every edge whose faces' normals agree
/// within cos_crease), each face labelled by one face of its region; with `taken`, a face f
/// with taken[f] >= 0 joins no region but its own.
std::vector<int> smoothRegions(const TriangleMesh& mesh, const MeshTopology& topology,
                               const std::vector<Eigen::Vector3d>& face_normals, double cos_crease,
                               const std::vector<int>* taken = nullptr);

SamplePoints samplePoints(const TriangleMesh& mesh, const MeshTopology& topology,
                          const std::vector<Eigen::Vector3d>& face_normals, double crease_angle);

/// A surface RANSAC proposed: its rough parameters and the samples it took.
struct Candidate {
  RecognisedSurface surface;
  std::vector<int> samples;
};

struct DetectionSettings {
  double epsilon;           ///< a sample lies on a candidate within this distance, m
  double cluster_epsilon;   ///< samples farther apart than this are not one connected surface, m
  double normal_threshold;  ///< cosine: a sample's normal must agree this well
  unsigned seed;
  unsigned kinds = 0;  ///< bits 1 << SurfaceKind of the kinds to look for
};

/// CGAL's efficient RANSAC over the samples with `use[i]` set, in the order it extracted the
/// shapes; the candidates' samples index `samples`.
std::vector<Candidate> detectCandidates(const SamplePoints& samples, const std::vector<char>& use,
                                        const DetectionSettings& s);

/// The surface whose parameters minimise the squared distances of `points` (Ceres,
/// Levenberg–Marquardt from `start`); kind and convexity are kept. None when the solve fails
/// or the points do not fix the surface (points on two circles and a torus).
std::optional<RecognisedSurface> polishSurface(const RecognisedSurface& start,
                                               const std::vector<Eigen::Vector3d>& points);

}  // namespace vcontact::geometry::detail
