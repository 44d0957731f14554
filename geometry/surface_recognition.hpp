#pragma once
// The analytic surfaces a tessellated CAD part was made from: planes, spheres, cylinders,
// cones and tori, recognised on a closed triangle mesh (docs/SURFACES.md).
//
// A CAD exporter places the vertices of a tessellation on the true surface and lets the faces
// cut chords through it, so the vertices carry the surface to the precision of the file while
// the faces do not. Recognition therefore works on the vertices: CGAL's efficient RANSAC
// (Shape_detection) proposes the surfaces from the vertices and their normals, Ceres polishes
// each surface's parameters to the least-squares fit of its vertices' distances, and a face
// belongs to a surface when its three corners lie on it within the tolerance and its normal
// agrees with the surface's. Faces on no surface are free-form and stay polyhedral.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

enum class SurfaceKind { kPlane, kSphere, kCylinder, kCone, kTorus };

/// "plane", "sphere", "cylinder", "cone", "torus".
const char* surfaceKindName(SurfaceKind kind);

/// One recognised surface, in the mesh frame M (metres, radians). Which fields are used:
/// - plane: `point` on it, `axis` its outward normal (the normal of its faces);
/// - sphere: `point` its centre, `radius`;
/// - cylinder: `point` on its axis (the foot of the covered vertices' centroid), `axis`, `radius`;
/// - cone: `point` its apex, `axis` from the apex into the cone, `angle` the half-angle;
/// - torus: `point` its centre, `axis`, `radius` the major radius, `minor_radius`.
struct RecognisedSurface {
  SurfaceKind kind = SurfaceKind::kPlane;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  double minor_radius = 0.0;
  double angle = 0.0;
  /// true when the solid lies on the side the surface's normal points away from (a ball, a
  /// shaft); false for a concave surface (a bore, a spherical socket). Planes: true.
  bool convex = true;
  std::vector<int> faces;     ///< the faces it covers, ascending
  double area = 0.0;          ///< of those faces, m²
  double rms_residual = 0.0;  ///< distance of their vertices to the surface, m
  double max_residual = 0.0;  ///< m
};

/// Signed distance of `p` to the surface (positive on the side its normal points to for a
/// convex surface, i.e. outside the solid), metres.
double signedDistance(const RecognisedSurface& s, const Eigen::Vector3d& p);
/// The surface's unit normal at the point of it nearest to `p`, pointing out of the solid.
Eigen::Vector3d outwardNormal(const RecognisedSurface& s, const Eigen::Vector3d& p);

struct RecognitionOptions {
  /// A vertex lies on a surface when within this fraction of the mesh's bounding-box
  /// diagonal. The default accepts single-precision files (STL stores floats: ~6e-8 of a
  /// coordinate) with margin, and refuses the chordal error of any tessellation a person would
  /// call smooth (a 1,000-triangle sphere's chords miss the sphere by 2e-3 of its diameter).
  double tolerance = 1e-5;
  /// Edges whose faces' normals differ by more than this are creases (the rim of a cylinder,
  /// a box's edges): a vertex has one normal per side of a crease. Radians. A tessellation
  /// with fewer than about 360°/crease_angle segments around a curved surface is taken for
  /// a prism.
  double crease_angle = 0.5;
  /// The random sampling of RANSAC is seeded, so a mesh gives the same surfaces every run.
  unsigned seed = 1;
};

struct SurfaceRecognition {
  std::vector<RecognisedSurface> surfaces;  ///< largest covered area first
  std::vector<int> face_surface;            ///< per face: index into surfaces, or −1 (free-form)
  double tolerance = 0.0;                   ///< the absolute vertex tolerance used, m
  double free_form_area = 0.0;              ///< m², the faces on no surface
  int free_form_faces = 0;
};

/// @throws InputError unless the mesh is closed and consistently oriented (MeshTopology)
SurfaceRecognition recogniseSurfaces(const TriangleMesh& mesh,
                                     const RecognitionOptions& options = {});

/// One line per surface (kind, parameters, faces, area, residuals), for people.
std::string describe(const RecognisedSurface& s);

}  // namespace vcontact::geometry
