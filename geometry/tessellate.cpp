#include "geometry/tessellate.hpp"

#include <cmath>
#include <stdexcept>

namespace vcontact::geometry {
namespace {

struct Builder {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  int add(const Eigen::Vector3d& p) {
    v.push_back(p);
    return static_cast<int>(v.size()) - 1;
  }
  void tri(int a, int b, int c) { f.emplace_back(a, b, c); }
  void quad(int a, int b, int c, int d) {  // counter-clockwise a→b→c→d
    tri(a, b, c);
    tri(a, c, d);
  }
  TriangleMesh build() const {
    TriangleMesh m;
    m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
    m.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (std::size_t i = 0; i < v.size(); ++i) m.vertices.row(static_cast<Eigen::Index>(i)) = v[i];
    for (std::size_t i = 0; i < f.size(); ++i) m.triangles.row(static_cast<Eigen::Index>(i)) = f[i];
    return m;
  }
};

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

TriangleMesh tessellateSphere(double radius, int segments, int rings) {
  require(segments >= 3 && rings >= 2, "tessellateSphere: segments >= 3 and rings >= 2");
  Builder b;
  const int south = b.add({0, 0, -radius});
  std::vector<int> ring(static_cast<std::size_t>(segments));
  std::vector<int> prev;
  for (int i = 1; i < rings; ++i) {
    const double polar = M_PI * (1.0 - static_cast<double>(i) / rings);  // from the south pole
    for (int j = 0; j < segments; ++j) {
      const double az = 2.0 * M_PI * j / segments;
      ring[j] = b.add(radius * Eigen::Vector3d(std::sin(polar) * std::cos(az),
                                               std::sin(polar) * std::sin(az), std::cos(polar)));
    }
    for (int j = 0; j < segments; ++j) {
      const int k = (j + 1) % segments;
      if (prev.empty()) {
        b.tri(south, ring[k], ring[j]);
      } else {
        b.quad(prev[j], prev[k], ring[k], ring[j]);
      }
    }
    prev = ring;
  }
  const int north = b.add({0, 0, radius});
  for (int j = 0; j < segments; ++j) b.tri(prev[j], prev[(j + 1) % segments], north);
  return b.build();
}

TriangleMesh tessellateCylinder(double radius, double length, int segments) {
  require(segments >= 3, "tessellateCylinder: segments >= 3");
  Builder b;
  const double h = 0.5 * length;
  const int bottom = b.add({0, 0, -h});
  const int top = b.add({0, 0, h});
  std::vector<int> lo(segments), hi(segments);
  for (int j = 0; j < segments; ++j) {
    const double az = 2.0 * M_PI * j / segments;
    const double x = radius * std::cos(az), y = radius * std::sin(az);
    lo[j] = b.add({x, y, -h});
    hi[j] = b.add({x, y, h});
  }
  for (int j = 0; j < segments; ++j) {
    const int k = (j + 1) % segments;
    b.quad(lo[j], lo[k], hi[k], hi[j]);
    b.tri(bottom, lo[k], lo[j]);
    b.tri(top, hi[j], hi[k]);
  }
  return b.build();
}

TriangleMesh tessellateBox(const Eigen::Vector3d& size) {
  Builder b;
  const Eigen::Vector3d h = 0.5 * size;
  int c[8];
  for (int i = 0; i < 8; ++i) {
    c[i] = b.add({(i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()});
  }
  b.quad(c[0], c[2], c[3], c[1]);  // z−
  b.quad(c[4], c[5], c[7], c[6]);  // z+
  b.quad(c[0], c[1], c[5], c[4]);  // y−
  b.quad(c[2], c[6], c[7], c[3]);  // y+
  b.quad(c[0], c[4], c[6], c[2]);  // x−
  b.quad(c[1], c[3], c[7], c[5]);  // x+
  return b.build();
}

TriangleMesh tessellateTorus(double majorRadius, double tubeRadius, int segments,
                             int tubeSegments) {
  require(segments >= 3 && tubeSegments >= 3, "tessellateTorus: segments, tubeSegments >= 3");
  Builder b;
  std::vector<int> idx(static_cast<std::size_t>(segments * tubeSegments));
  for (int i = 0; i < segments; ++i) {
    const double u = 2.0 * M_PI * i / segments;
    for (int j = 0; j < tubeSegments; ++j) {
      const double w = 2.0 * M_PI * j / tubeSegments;
      const double rho = majorRadius + tubeRadius * std::cos(w);
      idx[i * tubeSegments + j] =
          b.add({rho * std::cos(u), rho * std::sin(u), tubeRadius * std::sin(w)});
    }
  }
  for (int i = 0; i < segments; ++i) {
    const int i1 = (i + 1) % segments;
    for (int j = 0; j < tubeSegments; ++j) {
      const int j1 = (j + 1) % tubeSegments;
      b.quad(idx[i * tubeSegments + j], idx[i1 * tubeSegments + j], idx[i1 * tubeSegments + j1],
             idx[i * tubeSegments + j1]);
    }
  }
  return b.build();
}

TriangleMesh tessellateRevolution(const std::vector<Eigen::Vector2d>& profile, int segments) {
  require(segments >= 3 && profile.size() >= 2, "tessellateRevolution: segments >= 3, 2 points");
  for (std::size_t i = 0; i < profile.size(); ++i)
    require(profile[i].x() > 0.0 && (i == 0 || profile[i].y() > profile[i - 1].y()),
            "tessellateRevolution: radii > 0 and z increasing");
  Builder b;
  const int bottom = b.add({0, 0, profile.front().y()});
  const int top = b.add({0, 0, profile.back().y()});
  const int n = segments;
  const int first = static_cast<int>(b.v.size());  // vertex (ring i, angle j): first + i·n + j
  for (const Eigen::Vector2d& rz : profile)
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * M_PI * j / n;
      b.add({rz.x() * std::cos(a), rz.x() * std::sin(a), rz.y()});
    }
  const auto at = [&](std::size_t i, int j) { return first + static_cast<int>(i) * n + j % n; };
  for (int j = 0; j < n; ++j) {
    for (std::size_t i = 0; i + 1 < profile.size(); ++i)
      b.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
    b.tri(bottom, at(0, j + 1), at(0, j));
    b.tri(top, at(profile.size() - 1, j), at(profile.size() - 1, j + 1));
  }
  return b.build();
}

}  // namespace vcontact::geometry
