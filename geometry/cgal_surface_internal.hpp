#pragma once
// CGAL's Surface_mesh as the geometry layer's CGAL files use it (internal: included only by
// geometry/*.cpp, never by a header of the public API, so that CGAL stays out of it).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry::detail {

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalSurface = CGAL::Surface_mesh<CgalKernel::Point_3>;

/// The surface's faces as a TriangleMesh (its garbage collected first, so that indices are
/// dense); vertex and face i of the surface are vertex and face i of the result.
inline TriangleMesh toTriangleMesh(CgalSurface& sm) {
  sm.collect_garbage();
  TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(sm.number_of_vertices()), 3);
  for (const auto v : sm.vertices()) {
    const auto& p = sm.point(v);
    out.vertices.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  out.triangles.resize(static_cast<Eigen::Index>(sm.number_of_faces()), 3);
  for (const auto f : sm.faces()) {
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      out.triangles(static_cast<Eigen::Index>(f.idx()), k++) = static_cast<int>(v.idx());
    }
  }
  return out;
}

}  // namespace vcontact::geometry::detail
