#pragma once
// Generators of the defects third-party CAD meshes come with (issue 16), each applied to a
// closed, outward tessellation whose solid is known, so that a repair can be checked against
// the solid that was meant.

#include <string>
#include <vector>

#include "geometry/mesh_check.hpp"
#include "geometry/tessellate.hpp"
#include "geometry/triangle_mesh.hpp"
#include "support/test_support.hpp"

namespace vcontact::test {

using geometry::TriangleMesh;

/// The message checkAndRepair refuses `mesh` with, or "" when it accepts it.
inline std::string rejection(TriangleMesh mesh) {
  return inputErrorMessage([&] { geometry::checkAndRepair(mesh); });
}

/// A part of CAD size (30 x 50 x 70 mm) in metres; its sides are not binary fractions.
inline TriangleMesh cadBox() { return geometry::tessellateBox({0.03, 0.05, 0.07}); }

/// Issue 36: the CAD box (half sides h = 15, 25, 35 mm) with its corner (+x, +y, +z) pushed
/// down through the opposite face to (5, 10, -105) mm: closed and consistently oriented, but
/// the faces at that corner cross the bottom face. Its divergence-theorem moments (worked out
/// by hand from the 12 faces): volume 1.2833e-5 m^3, centroid (-19.2, -33.3, 45.3) mm, outside
/// the bounds, and Σ's eigenvalues -8.2e-8, 1.16e-9, 5.28e-9 m^5.
inline TriangleMesh boxWithCornerPushedThrough() {
  TriangleMesh m = cadBox();
  m.vertices.row(7) = Eigen::RowVector3d(0.005, 0.01, -0.105);  // vertex 7 is (+, +, +)
  return m;
}

/// The same corner pushed straight down to (15, 25, -105) mm: the side faces at it stay in
/// their planes and fold back onto themselves (coplanar overlaps). Centroid inside the bounds,
/// but Σ has a negative eigenvalue (for the unit cube, corner to z = -1.5: -0.0564, 0.0148,
/// 0.05 m^5 at volume 1/3 m^3; scaling the axes keeps their signs). CGAL 5.5's autorefinement
/// does not handle it.
inline TriangleMesh boxWithCornerFolded() {
  TriangleMesh m = cadBox();
  m.vertices.row(7) = Eigen::RowVector3d(0.015, 0.025, -0.105);
  return m;
}

inline int addVertex(TriangleMesh& m, const Eigen::Vector3d& p) {
  m.vertices.conservativeResize(m.vertexCount() + 1, 3);
  m.vertices.row(m.vertexCount() - 1) = p;
  return static_cast<int>(m.vertexCount() - 1);
}

inline void addFace(TriangleMesh& m, int a, int b, int c) {
  m.triangles.conservativeResize(m.triangleCount() + 1, 3);
  m.triangles.row(m.triangleCount() - 1) << a, b, c;
}

/// An exporter's seam: every face after the first one around `vertex` uses a copy of it
/// moved by `gap` along x, so the edges there are open.
inline TriangleMesh withSeam(TriangleMesh m, int vertex, double gap) {
  const int copy = addVertex(m, m.vertex(vertex) + Eigen::Vector3d(gap, 0, 0));
  bool first = true;
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (m.triangles(f, k) != vertex) continue;
      if (!first) m.triangles(f, k) = copy;
      first = false;
    }
  }
  return m;
}

/// A revolved part's seam: the vertices of the sphere's first meridian are duplicated (moved
/// by `gap` along x) for the faces on one side of it, as a CAD surface's parameter seam is.
inline TriangleMesh sphereWithMeridianSeam(double gap) {
  TriangleMesh m = geometry::tessellateSphere(0.02, 24, 12);
  const TriangleMesh before = m;
  std::vector<int> copyOf(static_cast<std::size_t>(m.vertexCount()), -1);
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    const Eigen::Vector3d c = (before.corner(f, 0) + before.corner(f, 1) + before.corner(f, 2));
    if (!(c.y() < 0.0 && c.x() > 0.0)) continue;  // faces just below the meridian y = 0, x > 0
    for (int k = 0; k < 3; ++k) {
      const int v = m.triangles(f, k);
      const Eigen::Vector3d p = before.vertex(v);
      if (v >= before.vertexCount() || std::abs(p.y()) > 0.0 || p.x() <= 0.0) continue;
      if (copyOf[v] < 0) copyOf[v] = addVertex(m, p + Eigen::Vector3d(gap, 0, 0));
      m.triangles(f, k) = copyOf[v];
    }
  }
  return m;
}

/// `count` zero-area faces with every edge still shared by two faces: the diagonal of each of
/// the first `count` box sides gets its midpoint on one side only (a T-junction), closed by a
/// face along the diagonal. @pre m is tessellateBox output (faces 2k, 2k+1 share a diagonal)
inline TriangleMesh withZeroAreaFaces(TriangleMesh m, int count) {
  for (int k = 0; k < count; ++k) {
    const Eigen::Index f = 2 * k;
    const int a = m.triangles(f, 0), b = m.triangles(f, 1), c = m.triangles(f, 2);
    const int mid = addVertex(m, 0.5 * (m.vertex(a) + m.vertex(c)));
    m.triangles.row(f) << a, b, mid;
    addFace(m, b, c, mid);
    addFace(m, a, mid, c);  // a, mid, c are collinear: zero area
  }
  return m;
}

inline TriangleMesh withFacesReversed(TriangleMesh m, const std::vector<int>& faces) {
  for (const int f : faces) std::swap(m.triangles(f, 1), m.triangles(f, 2));
  return m;
}

inline TriangleMesh inverted(TriangleMesh m) {
  m.triangles.col(1).swap(m.triangles.col(2));
  return m;
}

inline TriangleMesh withDuplicateFace(TriangleMesh m, int face) {
  addFace(m, m.triangles(face, 0), m.triangles(face, 1), m.triangles(face, 2));
  return m;
}

inline TriangleMesh withoutFaces(const TriangleMesh& m, const std::vector<int>& drop) {
  TriangleMesh out = m;
  out.triangles.resize(0, 3);
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    if (std::find(drop.begin(), drop.end(), f) != drop.end()) continue;
    addFace(out, m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2));
  }
  return out;
}

inline TriangleMesh translated(TriangleMesh m, const Eigen::Vector3d& t) {
  m.vertices.rowwise() += t.transpose();
  return m;
}

/// Both meshes as the shells of one.
inline TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m;
  m.vertices.resize(a.vertexCount() + b.vertexCount(), 3);
  m.vertices << a.vertices, b.vertices;
  m.triangles.resize(a.triangleCount() + b.triangleCount(), 3);
  m.triangles << a.triangles, (b.triangles.array() + static_cast<int>(a.vertexCount())).matrix();
  return m;
}

}  // namespace vcontact::test
