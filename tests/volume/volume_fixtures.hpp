#pragma once
// Meshes and poses shared by the volume tests: the named bodies of the cross-method tables.

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "geometry/tessellate.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::test {

/// Prism of height h (z ∈ [0, h]) over a counter-clockwise polygon that is star-shaped about
/// its vertex `apex` (caps are fans from it).
inline geometry::TriangleMesh extrudePolygon(const std::vector<Eigen::Vector2d>& poly, double h,
                                             int apex) {
  const int n = static_cast<int>(poly.size());
  geometry::TriangleMesh m;
  m.vertices.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    m.vertices.row(i) << poly[i].x(), poly[i].y(), 0.0;
    m.vertices.row(n + i) << poly[i].x(), poly[i].y(), h;
  }
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    f.emplace_back(i, j, n + j);
    f.emplace_back(i, n + j, n + i);
  }
  for (int k = 1; k + 1 < n; ++k) {
    const int a = (apex + k) % n, b = (apex + k + 1) % n;
    f.emplace_back(apex, b, a);              // bottom, facing −z
    f.emplace_back(n + apex, n + a, n + b);  // top, facing +z
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// Box centred at the origin with every face split into n × n cells (2 triangles each), so a
/// flat contact covers many small triangles.
inline geometry::TriangleMesh subdividedBox(const Eigen::Vector3d& size, int n) {
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> v;
  auto vertex = [&](std::array<int, 3> g) {
    const auto [it, added] = index.try_emplace(g, static_cast<int>(v.size()));
    if (added) {
      v.push_back(size.cwiseProduct(Eigen::Vector3d(g[0], g[1], g[2]) / n -
                                    Eigen::Vector3d::Constant(0.5)));
    }
    return it->second;
  };
  std::vector<Eigen::Vector3i> f;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) right-handed
    for (int side : {0, n}) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<int, 3> g00{}, g10{}, g11{}, g01{};
          for (auto* g : {&g00, &g10, &g11, &g01}) (*g)[axis] = side;
          g00[u] = i, g00[w] = j, g10[u] = i + 1, g10[w] = j;
          g11[u] = i + 1, g11[w] = j + 1, g01[u] = i, g01[w] = j + 1;
          const int a = vertex(g00), b = vertex(g10), c = vertex(g11), d = vertex(g01);
          if (side == n) {  // normal +axis: counter-clockwise in (u, w)
            f.emplace_back(a, b, c), f.emplace_back(a, c, d);
          } else {
            f.emplace_back(a, c, b), f.emplace_back(a, d, c);
          }
        }
      }
    }
  }
  geometry::TriangleMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.vertices.row(static_cast<Eigen::Index>(i)) = v[i];
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// L-shaped bracket, legs `leg` long and `thickness` thick, extruded by `width`.
inline geometry::TriangleMesh lBracket(double leg, double thickness, double width) {
  const double a = leg, t = thickness;
  return extrudePolygon({{0, 0}, {a, 0}, {a, t}, {t, t}, {t, a}, {0, a}}, width, 3);
}

inline Eigen::Isometry3d translation(const Eigen::Vector3d& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = t;
  return X;
}

}  // namespace vcontact::test
