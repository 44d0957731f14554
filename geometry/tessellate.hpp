#pragma once
// Closed, outward-oriented triangle meshes of the primitives, for tests, benchmarks and the
// bundled assets. Vertices lie on the exact surface, so the polyhedron is inscribed.

#include <vector>

#include "geometry/primitives.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

/// UV sphere: `segments` around the z axis, `rings` from pole to pole (≥ 3 and ≥ 2).
/// Triangles: 2·segments·(rings − 1).
TriangleMesh tessellateSphere(double radius, int segments, int rings);

/// Cylinder of axis z centred at the origin, `segments` around; caps are fans about a centre
/// vertex. Triangles: 4·segments.
TriangleMesh tessellateCylinder(double radius, double length, int segments);

/// Box centred at the origin, 12 triangles.
TriangleMesh tessellateBox(const Eigen::Vector3d& size);

/// Torus about the z axis: major radius R, tube radius r. Triangles: 2·segments·tubeSegments.
TriangleMesh tessellateTorus(double majorRadius, double tubeRadius, int segments, int tubeSegments);

/// Solid of revolution about the z axis: `profile` lists (radius, z) from the bottom rim to the
/// top rim (radii > 0, z increasing), `segments` around; the two ends are flat fans about a
/// centre vertex. A cylinder with chamfered ends: (r − c, 0), (r, c), (r, L − c), (r − c, L).
/// Triangles: 2·segments·profile.size().
TriangleMesh tessellateRevolution(const std::vector<Eigen::Vector2d>& profile, int segments);

}  // namespace vcontact::geometry
