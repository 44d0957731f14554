#pragma once
// A closed triangle mesh in its body frame M: vertex positions p_MV (metres) and
// counter-clockwise (outward-normal) triangles.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vcontact::geometry {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct TriangleMesh {
  Vertices vertices;    ///< one row per vertex, body frame, metres
  Triangles triangles;  ///< one row per face, vertex indices, counter-clockwise seen from outside

  Eigen::Index vertexCount() const { return vertices.rows(); }
  Eigen::Index triangleCount() const { return triangles.rows(); }
  Eigen::Vector3d vertex(Eigen::Index i) const { return vertices.row(i).transpose(); }
  /// Corner k (0, 1, 2) of triangle f.
  Eigen::Vector3d corner(Eigen::Index f, int k) const { return vertex(triangles(f, k)); }
};

/// Axis-aligned bounds of the vertices, as {min, max}.
struct Aabb {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
  Eigen::Vector3d size() const { return max - min; }
};
Aabb bounds(const TriangleMesh& mesh);

}  // namespace vcontact::geometry
