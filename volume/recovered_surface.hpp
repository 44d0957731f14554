#pragma once
// Contact of a mesh body on its recovered surfaces (geometry/surface_recognition.hpp) against
// a half-space (docs/SURFACES.md).
//
// A tessellation is inscribed in its part: the vertices lie on the true surface and the faces
// cut chords inside it, so at the micrometre depths of metal contact the polyhedron misses
// most of the interference (a 10,000-triangle sphere at d/R = 1e-4 by 96 %). Where the part of
// the body that can reach the plane lies on one recognised sphere, or on one recognised
// cylinder closed by flat ends, the contact is that of the true solid: the closed forms of
// the analytic backend. Anywhere else (free-form faces, several surfaces, kinds without a
// closed form against a plane yet) the result is the polyhedral one, and says so.

#include <Eigen/Geometry>
#include <string>

#include "geometry/surface_recognition.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

struct RecoveredContact {
  ContactVolume cv;
  /// What the contact was computed on: "sphere" or "cylinder" (the recognised surface, by
  /// closed form), or "mesh" (the polyhedron).
  std::string representation;
  /// Why the polyhedron was used, for "mesh"; empty otherwise.
  std::string reason;
  /// A bound on |V − V_true|, m³: for a recovered surface the contact area times the largest
  /// distance of the surface's vertices to it (the fit residual) plus the closed form's own
  /// error; for the polyhedron, the area times the largest chord gap of the faces that can
  /// reach the plane (how far the true surface may lie outside the faces).
  double volume_error_bound = 0.0;
};

/// @param mesh         the body's mesh, frame M
/// @param recognition  recogniseSurfaces(mesh)
/// @param X_WM, X_WH   poses of the mesh and of the half-space (solid z ≤ 0 of H)
RecoveredContact recoveredHalfspaceContact(const geometry::TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const Eigen::Isometry3d& X_WM,
                                           const Eigen::Isometry3d& X_WH);

}  // namespace vcontact::volume
