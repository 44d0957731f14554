#include "volume/embree_lines.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <span>
#include <stdexcept>

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

// A line within this fraction of the mesh's scale (|c_M| + 3 r: the largest coordinate a
// ray or vertex takes in M) of an edge of a reported triangle, in the plate plane, may lie
// on the other side of it for Embree: ~100 float ulps, far above Embree's rounding of rays
// and vertices (a few ulps), far below any triangle.
constexpr double kNearEdge = 1e-5;

// Rays are cast this many at a time (Embree's stream API; coherent: neighbouring lines),
// through one buffer of ~80 kB that is reused.
constexpr int kRaysPerBatch = 1024;

// The rays start and end this fraction of the radius outside the mesh's bounding sphere.
constexpr double kRayMargin = 1e-2;

/// The one Embree device, released at exit.
RTCDevice device() {
  struct Holder {
    RTCDevice device = rtcNewDevice(nullptr);
    ~Holder() { rtcReleaseDevice(device); }
  };
  static const Holder holder;
  if (!holder.device) throw std::runtime_error("EmbreeLines: no Embree device");
  return holder.device;
}

/// A triangle that Embree's ray `ray` (of a batch) hit.
struct RayHit {
  int ray, face;
};

/// The intersection context of the rays, with the triangles their filter has seen.
struct HitCollector {
  RTCIntersectContext context;  // first member: the filter receives its address
  std::vector<RayHit>* hits;
};

/// Records every hit and rejects it, so that each ray's traversal goes on to the next one.
void collectHits(const RTCFilterFunctionNArguments* args) {
  auto* collector = reinterpret_cast<HitCollector*>(args->context);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] == 0) continue;
    collector->hits->push_back({static_cast<int>(RTCRayN_id(args->ray, args->N, k)),
                                static_cast<int>(RTCHitN_primID(args->hit, args->N, k))});
    args->valid[k] = 0;
  }
}

/// Plate coordinates (along e1, e2) of line (i, j), the expression of volume/columns.cpp.
Vector2d plate(const LineGrid& g, int i, int j) {
  return {-g.r1 + (i + 0.5) * 2.0 * g.r1 / g.n, -g.r2 + (j + 0.5) * 2.0 * g.r2 / g.n};
}

/// Twice the signed area of (0, a, b), as in volume/columns.cpp.
double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Side of the edge a→b with the top-left tie rule, as in volume/columns.cpp.
bool positiveSide(const Vector2d& a, const Vector2d& b) {
  const double e = cross2(a, b);
  if (e != 0.0) return e > 0.0;
  const Vector2d d = b - a;
  return d.x() > 0.0 || (d.x() == 0.0 && d.y() > 0.0);
}

/// What the double edge-function test says of one triangle and one line.
struct TriangleTest {
  bool crosses = false;
  bool misses = true;  ///< the line passes outside the triangle (or it is edge-on)
  bool nearEdge[3]{};  ///< the line is within the tolerance of the edge opposite corner k
  double t = 0.0;
  int delta = 0;
};

/// A triangle seen from the grid: its corners in the plate (along e1, e2) and along u, from o,
/// with the expressions of volume/columns.cpp, and the lengths of its projected edges.
struct Projected {
  Vector2d q[3];
  double z[3];
  double edge[3];  ///< edge[k]: the projected edge opposite corner k
};

/// The triangles of a mesh projected onto a grid, each on first use, stored in the order
/// they are first used (a query touches few of a large mesh's triangles).
class Projections {
 public:
  Projections(const geometry::TriangleMesh& mesh, const Isometry3d& X_WM, const LineGrid& g)
      : mesh_(mesh),
        X_WM_(X_WM),
        g_(g),
        slot_(static_cast<std::size_t>(mesh.triangleCount()), -1) {}

  /// Valid until the next call.
  const Projected& operator[](int f) {
    int& slot = slot_[static_cast<std::size_t>(f)];
    if (slot < 0) {
      slot = static_cast<int>(projected_.size());
      projected_.push_back(project(f));
    }
    return projected_[static_cast<std::size_t>(slot)];
  }

 private:
  Projected project(int f) const {
    Projected t;
    for (int k = 0; k < 3; ++k) {
      const Vector3d p = X_WM_ * mesh_.corner(f, k) - g_.o;
      t.q[k] = {p.dot(g_.e1), p.dot(g_.e2)};
      t.z[k] = p.dot(g_.u);
    }
    for (int k = 0; k < 3; ++k) t.edge[k] = (t.q[(k + 2) % 3] - t.q[(k + 1) % 3]).norm();
    return t;
  }

  const geometry::TriangleMesh& mesh_;
  const Isometry3d& X_WM_;
  const LineGrid& g_;
  std::vector<int> slot_;  ///< index into projected_, −1 before the first use
  std::vector<Projected> projected_;
};

/// The rasteriser's test of volume/columns.cpp for one (line, triangle) pair, with the same
/// expressions (so the same bits), plus whether the line passes within `near` of an edge.
TriangleTest test(const Projected& p, const Vector2d& s, double near) {
  const Vector2d a = p.q[0] - s, b = p.q[1] - s, c = p.q[2] - s;
  TriangleTest r;
  const double w0 = cross2(b, c), w1 = cross2(c, a), w2 = cross2(a, b);
  r.nearEdge[0] = std::abs(w0) <= near * p.edge[0];
  r.nearEdge[1] = std::abs(w1) <= near * p.edge[1];
  r.nearEdge[2] = std::abs(w2) <= near * p.edge[2];
  const bool side0 = positiveSide(b, c);
  if (positiveSide(c, a) != side0 || positiveSide(a, b) != side0) return r;
  const double sum = w0 + w1 + w2;  // 2 × projected area; sign: n·u
  if (sum == 0.0) return r;         // edge-on: its neighbours carry the crossing
  r.crosses = true;
  r.misses = false;
  r.t = (w0 * p.z[0] + w1 * p.z[1] + w2 * p.z[2]) / sum;
  r.delta = sum > 0.0 ? -1 : +1;
  return r;
}

}  // namespace

struct EmbreeLines::Impl {
  geometry::TriangleMesh mesh;
  RTCScene scene = nullptr;
  std::vector<int> cornerStart, cornerFaces;  ///< triangles at each vertex (CSR)
  Vector3d c_M;                               ///< centre of the bounding sphere
  double radius = 0.0;

  void buildScene();
  void buildCornerFaces();
  void fillRays(const Isometry3d& X_MW, const LineGrid& g, int first,
                std::span<RTCRayHit> rays) const;
  bool resolveLine(Projections& projections, const LineGrid& g, int line,
                   std::span<const RayHit> hits, std::vector<int>& tested,
                   std::vector<LineCrossing>& out) const;
  int triangles(int f, int k) const { return mesh.triangles(f, k); }
  std::span<const int> facesAt(int v) const {
    return {cornerFaces.data() + cornerStart[static_cast<std::size_t>(v)],
            cornerFaces.data() + cornerStart[static_cast<std::size_t>(v) + 1]};
  }
  bool hasCorner(int f, int v) const {
    return triangles(f, 0) == v || triangles(f, 1) == v || triangles(f, 2) == v;
  }
};

void EmbreeLines::Impl::buildScene() {
  const RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto nv = static_cast<std::size_t>(mesh.vertexCount());
  const auto nf = static_cast<std::size_t>(mesh.triangleCount());
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
  auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nf));
  for (std::size_t i = 0; i < nv; ++i) {
    for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.vertices(i, k));
  }
  for (std::size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) t[3 * f + k] = static_cast<unsigned>(mesh.triangles(f, k));
  }
  rtcSetGeometryIntersectFilterFunction(geom, collectHits);
  rtcCommitGeometry(geom);
  scene = rtcNewScene(device());
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
}

void EmbreeLines::Impl::buildCornerFaces() {
  cornerStart.assign(static_cast<std::size_t>(mesh.vertexCount()) + 1, 0);
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) ++cornerStart[static_cast<std::size_t>(mesh.triangles(f, k)) + 1];
  }
  for (std::size_t v = 1; v < cornerStart.size(); ++v) cornerStart[v] += cornerStart[v - 1];
  cornerFaces.resize(static_cast<std::size_t>(cornerStart.back()));
  std::vector<int> next(cornerStart.begin(), cornerStart.end() - 1);
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      cornerFaces[static_cast<std::size_t>(
          next[static_cast<std::size_t>(mesh.triangles(f, k))]++)] = static_cast<int>(f);
    }
  }
}

/// One ray per line first, first + 1, ... of g (as many as `rays` holds), in M, from outside
/// the mesh's bounding sphere through it.
void EmbreeLines::Impl::fillRays(const Isometry3d& X_MW, const LineGrid& g, int first,
                                 std::span<RTCRayHit> rays) const {
  const Vector3d u_M = X_MW.linear() * g.u;
  const double reach = (1.0 + kRayMargin) * radius;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const int line = first + static_cast<int>(k);
    const Vector2d s = plate(g, line / g.n, line % g.n);
    const Vector3d p_M = X_MW * Vector3d(g.o + s.x() * g.e1 + s.y() * g.e2);
    const Vector3d start_M = p_M + ((c_M - p_M).dot(u_M) - reach) * u_M;
    RTCRayHit& rh = rays[k];
    rh.ray.org_x = float(start_M.x()), rh.ray.org_y = float(start_M.y());
    rh.ray.org_z = float(start_M.z());
    rh.ray.dir_x = float(u_M.x()), rh.ray.dir_y = float(u_M.y()), rh.ray.dir_z = float(u_M.z());
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = float(2.0 * reach);
    rh.ray.mask = ~0u;
    rh.ray.id = static_cast<unsigned>(k);
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  }
}

/// Tests every triangle Embree reported for `line` once, and, where the line passes near one
/// of its edges, the triangle across that edge (near two edges: every triangle at their common
/// corner; outside it and near none: every triangle at its corners). Appends the crossings.
/// @return whether the line's crossings balance (it enters the closed mesh as often as it
///   leaves)
bool EmbreeLines::Impl::resolveLine(Projections& projections, const LineGrid& g, int line,
                                    std::span<const RayHit> hits, std::vector<int>& tested,
                                    std::vector<LineCrossing>& out) const {
  const Vector2d s = plate(g, line / g.n, line % g.n);
  const double near = kNearEdge * (c_M.norm() + 3.0 * radius);
  tested.clear();
  int balance = 0;
  auto visit = [&](int f) {
    if (std::find(tested.begin(), tested.end(), f) != tested.end()) return TriangleTest{};
    tested.push_back(f);
    const TriangleTest r = test(projections[f], s, near);
    if (r.crosses) {
      out.push_back({line, r.t, r.delta});
      balance += r.delta;
    }
    return r;
  };
  for (const RayHit& h : hits) {
    if (std::find(tested.begin(), tested.end(), h.face) != tested.end()) continue;
    const TriangleTest r = visit(h.face);
    const bool lost = r.misses && !r.nearEdge[0] && !r.nearEdge[1] && !r.nearEdge[2];
    for (int k = 0; k < 3; ++k) {
      if (lost || (r.nearEdge[(k + 1) % 3] && r.nearEdge[(k + 2) % 3])) {
        for (int f : facesAt(triangles(h.face, k))) visit(f);
      } else if (r.nearEdge[k]) {
        const int v2 = triangles(h.face, (k + 2) % 3);
        for (int f : facesAt(triangles(h.face, (k + 1) % 3))) {
          if (hasCorner(f, v2)) visit(f);
        }
      }
    }
  }
  return balance == 0;
}

EmbreeLines::EmbreeLines(const geometry::TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = mesh;
  const geometry::Aabb box = geometry::bounds(mesh);
  impl_->c_M = 0.5 * (box.min + box.max);
  impl_->radius = 0.5 * box.size().norm();
  impl_->buildScene();
  impl_->buildCornerFaces();
}

EmbreeLines::~EmbreeLines() { rtcReleaseScene(impl_->scene); }

bool EmbreeLines::cross(const Isometry3d& X_WM, const LineGrid& grid,
                        std::vector<LineCrossing>& out) const {
  const Isometry3d X_MW = X_WM.inverse();
  const int lines = grid.n * grid.n;
  std::vector<RTCRayHit> rays(static_cast<std::size_t>(std::min(lines, kRaysPerBatch)));
  std::vector<RayHit> hits, byRay;
  std::vector<int> start, tested;
  Projections projections(impl_->mesh, X_WM, grid);
  out.clear();
  for (int first = 0; first < lines; first += kRaysPerBatch) {
    const std::span<RTCRayHit> batch(rays.data(),
                                     std::min(rays.size(), std::size_t(lines - first)));
    impl_->fillRays(X_MW, grid, first, batch);
    hits.clear();
    HitCollector collector{{}, &hits};
    rtcInitIntersectContext(&collector.context);
    collector.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(impl_->scene, &collector.context, batch.data(),
                   static_cast<unsigned>(batch.size()), sizeof(RTCRayHit));
    // Counting sort of the batch's hits by ray.
    start.assign(batch.size() + 1, 0);
    for (const RayHit& h : hits) ++start[static_cast<std::size_t>(h.ray) + 1];
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    byRay.resize(hits.size());
    for (const RayHit& h : hits) byRay[static_cast<std::size_t>(start[h.ray]++)] = h;
    for (std::size_t k = 0, begin = 0; k < batch.size(); begin = start[k++]) {
      const std::span<const RayHit> rayHits(byRay.data() + begin, byRay.data() + start[k]);
      if (rayHits.empty()) continue;
      if (!impl_->resolveLine(projections, grid, first + static_cast<int>(k), rayHits, tested,
                              out)) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace vcontact::volume
