#pragma once
// Non-convex test meshes for the contact-patch tests: several closed shells in one mesh (a
// plate with a gap, a part on two feet) and a polygonal ring (a plate with a round or square
// hole).

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "geometry/primitives.hpp"
#include "geometry/tessellate.hpp"

namespace vcontact::test {

/// The shells of `parts` (each placed by its pose) as one mesh.
inline geometry::TriangleMesh merged(
    const std::vector<std::pair<geometry::TriangleMesh, Eigen::Isometry3d>>& parts) {
  geometry::TriangleMesh m;
  Eigen::Index nv = 0, nt = 0;
  for (const auto& [mesh, X] : parts) {
    nv += mesh.vertexCount();
    nt += mesh.triangleCount();
  }
  m.vertices.resize(nv, 3);
  m.triangles.resize(nt, 3);
  Eigen::Index v = 0, t = 0;
  for (const auto& [mesh, X] : parts) {
    for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
      m.vertices.row(v + i) = (X * mesh.vertex(i)).transpose();
    }
    for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
      m.triangles.row(t + f) = mesh.triangles.row(f).array() + static_cast<int>(v);
    }
    v += mesh.vertexCount();
    t += mesh.triangleCount();
  }
  return m;
}

/// A ring of axis z between radii r_in and r_out (circumradii of its polygons, `segments`
/// corners at angles 2πk/segments) and heights z ∈ [−h/2, h/2]: a plate with a polygonal hole.
inline geometry::TriangleMesh ring(double r_in, double r_out, double h, int segments) {
  geometry::TriangleMesh m;
  const int n = segments;
  m.vertices.resize(4 * n, 3);
  m.triangles.resize(8 * n, 3);
  // vertex 4k + {0: outer bottom, 1: outer top, 2: inner bottom, 3: inner top}
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n, c = std::cos(a), s = std::sin(a);
    m.vertices.row(4 * k + 0) << r_out * c, r_out * s, -h / 2;
    m.vertices.row(4 * k + 1) << r_out * c, r_out * s, h / 2;
    m.vertices.row(4 * k + 2) << r_in * c, r_in * s, -h / 2;
    m.vertices.row(4 * k + 3) << r_in * c, r_in * s, h / 2;
  }
  int t = 0;
  auto quad = [&](int a, int b, int c, int d) {  // counter-clockwise seen from outside
    m.triangles.row(t++) << a, b, c;
    m.triangles.row(t++) << a, c, d;
  };
  for (int k = 0; k < n; ++k) {
    const int i = 4 * k, j = 4 * ((k + 1) % n);
    quad(i + 0, j + 0, j + 1, i + 1);  // outer wall, normal outwards
    quad(i + 2, i + 3, j + 3, j + 2);  // inner wall, normal towards the axis
    quad(i + 1, j + 1, j + 3, i + 3);  // top, +z
    quad(i + 0, i + 2, j + 2, j + 0);  // bottom, −z
  }
  return m;
}

inline geometry::Mesh meshShape(geometry::TriangleMesh m, const std::string& name) {
  return {std::make_shared<const geometry::TriangleMesh>(std::move(m)), name};
}

inline Eigen::Isometry3d placed(const Eigen::Vector3d& p,
                                const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

}  // namespace vcontact::test
