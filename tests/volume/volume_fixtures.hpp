#pragma once
// Meshes and poses shared by the volume tests: the named bodies of the cross-method tables.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "geometry/tessellate.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::test {

/// Prism of height h (z ∈ [0, h]) over a counter-clockwise polygon whose area is covered by
/// the counter-clockwise triangles `cap` (vertex indices into poly).
inline geometry::TriangleMesh extrudeTriangulated(const std::vector<Eigen::Vector2d>& poly,
                                                  double h,
                                                  const std::vector<Eigen::Vector3i>& cap) {
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
  for (const Eigen::Vector3i& t : cap) {
    f.emplace_back(t[0], t[2], t[1]);              // bottom, facing −z
    f.emplace_back(n + t[0], n + t[1], n + t[2]);  // top, facing +z
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// Prism of height h (z ∈ [0, h]) over a counter-clockwise polygon that is star-shaped about
/// its vertex `apex` (caps are fans from it).
inline geometry::TriangleMesh extrudePolygon(const std::vector<Eigen::Vector2d>& poly, double h,
                                             int apex) {
  const int n = static_cast<int>(poly.size());
  std::vector<Eigen::Vector3i> fan;
  for (int k = 1; k + 1 < n; ++k) fan.emplace_back(apex, (apex + k) % n, (apex + k + 1) % n);
  return extrudeTriangulated(poly, h, fan);
}

/// The legs and bridge of a "U" standing on its legs (profile in x, y; legs along −y).
struct UProfile {
  double leftLeg, gap, rightLeg;  ///< widths along x, m
  double legHeight, height;       ///< y of the bridge's underside, overall height, m
};

/// The U prism of width w along z: legs x ∈ [0, leftLeg] and [leftLeg + gap, total], feet at
/// y = 0, bridge y ∈ [legHeight, height]. One shell, eight profile corners.
inline geometry::TriangleMesh uPrism(const UProfile& u, double w) {
  const double a = u.leftLeg, b = a + u.gap, c = b + u.rightLeg;
  const std::vector<Eigen::Vector2d> poly = {{0, 0}, {a, 0}, {a, u.legHeight}, {b, u.legHeight},
                                             {b, 0}, {c, 0}, {c, u.height},    {0, u.height}};
  return extrudeTriangulated(poly, w,
                             {{0, 1, 2}, {0, 2, 7}, {2, 3, 7}, {3, 6, 7}, {3, 4, 5}, {3, 5, 6}});
}

/// A square cup standing on z = 0: outer half-width a, height h, a pocket of half-width b < a
/// open at the top down to its floor at z = floor. Its outer surface and its pocket meet only
/// at the rim. 16 vertices, 28 faces.
inline geometry::TriangleMesh squareCup(double a, double b, double h, double floor) {
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};  // corners, CCW seen from +z
  geometry::TriangleMesh m;
  m.vertices.resize(16, 3);
  for (int j = 0; j < 4; ++j) {
    m.vertices.row(j) << a * sx[j], a * sy[j], 0.0;         // outer bottom ob
    m.vertices.row(4 + j) << a * sx[j], a * sy[j], h;       // outer top ot
    m.vertices.row(8 + j) << b * sx[j], b * sy[j], h;       // pocket top it
    m.vertices.row(12 + j) << b * sx[j], b * sy[j], floor;  // pocket floor ib
  }
  std::vector<Eigen::Vector3i> f = {{0, 2, 1}, {0, 3, 2}, {12, 13, 14}, {12, 14, 15}};
  for (int j = 0; j < 4; ++j) {
    const int k = (j + 1) % 4;
    f.emplace_back(j, k, 4 + k);  // outer wall, facing out
    f.emplace_back(j, 4 + k, 4 + j);
    f.emplace_back(4 + j, 4 + k, 8 + k);  // rim, facing up
    f.emplace_back(4 + j, 8 + k, 8 + j);
    f.emplace_back(12 + j, 8 + k, 12 + k);  // pocket wall, facing the axis
    f.emplace_back(12 + j, 8 + j, 8 + k);
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// A tube of axis z centred at the origin: outer radius ro, a round hole of radius ri, length
/// h, `segments` around (both circles inscribed). 4·segments vertices, 8·segments faces.
inline geometry::TriangleMesh tube(double ro, double ri, double h, int segments) {
  geometry::TriangleMesh m;
  m.vertices.resize(4 * segments, 3);
  const auto olo = [](int j) { return 4 * j; };
  const auto ohi = [](int j) { return 4 * j + 1; };
  const auto ilo = [](int j) { return 4 * j + 2; };
  const auto ihi = [](int j) { return 4 * j + 3; };
  for (int j = 0; j < segments; ++j) {
    const double az = 2.0 * M_PI * j / segments, c = std::cos(az), s = std::sin(az);
    m.vertices.row(olo(j)) << ro * c, ro * s, -0.5 * h;
    m.vertices.row(ohi(j)) << ro * c, ro * s, 0.5 * h;
    m.vertices.row(ilo(j)) << ri * c, ri * s, -0.5 * h;
    m.vertices.row(ihi(j)) << ri * c, ri * s, 0.5 * h;
  }
  std::vector<Eigen::Vector3i> f;
  for (int j = 0; j < segments; ++j) {
    const int k = (j + 1) % segments;
    f.emplace_back(olo(j), olo(k), ohi(k));  // outer wall, facing out
    f.emplace_back(olo(j), ohi(k), ohi(j));
    f.emplace_back(ilo(j), ihi(j), ihi(k));  // hole wall, facing the axis
    f.emplace_back(ilo(j), ihi(k), ilo(k));
    f.emplace_back(ohi(j), ohi(k), ihi(k));  // top, facing +z
    f.emplace_back(ohi(j), ihi(k), ihi(j));
    f.emplace_back(olo(j), ilo(k), olo(k));  // bottom, facing −z
    f.emplace_back(olo(j), ilo(j), ilo(k));
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// A shaft with four keys, a "+" of arms of half-width a reaching to radius L, length h along
/// z, centred at the origin. One shell, 12 profile corners.
inline geometry::TriangleMesh keyedShaft(double a, double L, double h) {
  const std::vector<Eigen::Vector2d> poly = {{a, -a},  {L, -a},  {L, a},   {a, a},
                                             {a, L},   {-a, L},  {-a, a},  {-L, a},
                                             {-L, -a}, {-a, -a}, {-a, -L}, {a, -L}};
  geometry::TriangleMesh m = extrudeTriangulated(poly, h,
                                                 {{9, 0, 3},
                                                  {9, 3, 6},
                                                  {0, 1, 2},
                                                  {0, 2, 3},
                                                  {3, 4, 5},
                                                  {3, 5, 6},
                                                  {6, 7, 8},
                                                  {6, 8, 9},
                                                  {9, 10, 11},
                                                  {9, 11, 0}});
  m.vertices.col(2).array() -= 0.5 * h;
  return m;
}

/// Meshes a and b as one mesh of two shells.
inline geometry::TriangleMesh twoShells(const geometry::TriangleMesh& a,
                                        const geometry::TriangleMesh& b) {
  geometry::TriangleMesh m;
  m.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
  m.vertices << a.vertices, b.vertices;
  m.triangles.resize(a.triangles.rows() + b.triangles.rows(), 3);
  m.triangles << a.triangles, (b.triangles.array() + static_cast<int>(a.vertices.rows())).matrix();
  return m;
}

/// The hub of keyedShaft(a, ·, ·): four blocks of width w (across the flank), 7.1 mm radially
/// from x = 10.1 mm and 12.1 mm along z, one beside the leading (+y) flank of the +x key with
/// `gap` clearance, the others by quarter turns about z. One mesh of four shells.
inline geometry::TriangleMesh keyedHub(double a, double gap, double w) {
  geometry::TriangleMesh block = geometry::tessellateBox(Eigen::Vector3d(0.0071, w, 0.0121));
  block.vertices.rowwise() += Eigen::RowVector3d(0.0101, a + gap + 0.5 * w, 0.0);
  std::vector<geometry::TriangleMesh> blocks(4, block);
  for (int k = 1; k < 4; ++k) {
    const Eigen::Matrix3d R(Eigen::AngleAxisd(k * std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
    blocks[static_cast<std::size_t>(k)].vertices = block.vertices * R.transpose();
  }
  return twoShells(twoShells(blocks[0], blocks[1]), twoShells(blocks[2], blocks[3]));
}

/// A plate 0.2 × 0.2 × 0.05 m of two triangles a face, its top face the plane z = 0.
inline geometry::TriangleMesh plateTopAtZero() {
  geometry::TriangleMesh m = geometry::tessellateBox(Eigen::Vector3d(0.2, 0.2, 0.05));
  m.vertices.rowwise() += Eigen::RowVector3d(0.0, 0.0, -0.025);
  return m;
}

/// A dumbbell's two ends: spheres of radius R (48 × 24 facets) centred at x = ∓half.
inline std::array<geometry::TriangleMesh, 2> dumbbellEnds(double R, double half) {
  std::array<geometry::TriangleMesh, 2> ends{geometry::tessellateSphere(R, 48, 24),
                                             geometry::tessellateSphere(R, 48, 24)};
  ends[0].vertices.col(0).array() -= half;
  ends[1].vertices.col(0).array() += half;
  return ends;
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

/// Square plate (x, y ∈ [−half, half], z ∈ [0, thickness]) with a round hole of radius
/// `holeRadius` about the z axis, `n` segments around (a multiple of 8, so the square's
/// corners are vertices). Outer and hole boundary vertices share their angles.
inline geometry::TriangleMesh plateWithHole(double half, double thickness, double holeRadius,
                                            int n) {
  geometry::TriangleMesh m;
  m.vertices.resize(4 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n, c = std::cos(t), s = std::sin(t);
    const double k = half / std::max(std::abs(c), std::abs(s));  // circle pushed onto the square
    m.vertices.row(i) << holeRadius * c, holeRadius * s, 0.0;    // hole, bottom
    m.vertices.row(n + i) << k * c, k * s, 0.0;                  // outer, bottom
    m.vertices.row(2 * n + i) << holeRadius * c, holeRadius * s, thickness;  // hole, top
    m.vertices.row(3 * n + i) << k * c, k * s, thickness;                    // outer, top
  }
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const int ib = i, jb = j, ob = n + i, pb = n + j, it = 2 * n + i, jt = 2 * n + j,
              ot = 3 * n + i, pt = 3 * n + j;
    f.emplace_back(it, ot, pt), f.emplace_back(it, pt, jt);  // top, +z
    f.emplace_back(ib, pb, ob), f.emplace_back(ib, jb, pb);  // bottom, −z
    f.emplace_back(ob, pb, pt), f.emplace_back(ob, pt, ot);  // outer wall, outward
    f.emplace_back(ib, jt, jb), f.emplace_back(ib, it, jt);  // hole wall, towards the axis
  }
  m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
  return m;
}

/// Regular octahedron with vertices centre ± a along each axis (8 faces).
inline geometry::TriangleMesh octahedron(const Eigen::Vector3d& centre, double a) {
  geometry::TriangleMesh m;
  m.vertices.resize(6, 3);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d[k] = a;
    m.vertices.row(2 * k) = (centre + d).transpose();
    m.vertices.row(2 * k + 1) = (centre - d).transpose();
  }
  // Vertex 2k is +axis k, 2k + 1 is −axis k; a face (x, y, z) of signs is counter-clockwise
  // seen from outside when the sign product is positive, reversed otherwise.
  m.triangles.resize(8, 3);
  int f = 0;
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) {
        const int x = sx, y = 2 + sy, z = 4 + sz;
        if ((sx + sy + sz) % 2 == 0) {
          m.triangles.row(f++) << x, y, z;
        } else {
          m.triangles.row(f++) << x, z, y;
        }
      }
    }
  }
  return m;
}

inline Eigen::Isometry3d translation(const Eigen::Vector3d& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = t;
  return X;
}

}  // namespace vcontact::test
