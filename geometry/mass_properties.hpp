#pragma once
// Exact volume moments of closed solids (divergence theorem) and of the primitives.

#include "geometry/moments.hpp"
#include "geometry/primitives.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

/// Moments of the solid bounded by a closed, outward-oriented mesh, in its body frame.
/// Exact for the polyhedron up to rounding: Σ over faces of the tetrahedron (o, a, b, c)
/// with o the bounding-box centre (keeps the terms small for parts far from the origin).
Moments meshMoments(const TriangleMesh& mesh);

/// Moments of a bounded shape in its own frame (closed forms; mesh by meshMoments).
/// @throws InputError for a HalfSpace (unbounded).
Moments solidMoments(const Shape& shape);

/// Mass properties for a density ρ (kg/m³): mass, centre of mass and inertia about it.
struct MassProperties {
  double mass = 0.0;                                  ///< kg
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< m, body frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< kg·m², about com, body axes
};
MassProperties massProperties(const Moments& moments, double density);

}  // namespace vcontact::geometry
