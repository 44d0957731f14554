#pragma once
// Internal to volume/halfspace/clip.cpp and volume/halfspace/clip_patches.cpp, not part of the
// public API: the clip helpers both share (fan sums, triangle clipping, the placement X_HM,
// placed vertices, the apex, the move into H) and the cap loops on the plane, which the
// accelerated clip records (the single patch test) and the patch split traces.

#include <Eigen/Geometry>
#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/moments.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/kernels/stamp_set.hpp"

namespace vcontact::volume::internal {

using Eigen::Vector3d;
using geometry::MeshTopology;

/// The fan pieces (o, a, b, c) of a clip, corners relative to o in H axes, and their shadow.
struct FanSum {
  geometry::TetrahedronSum tetrahedra;
  double area = 0.0;  ///< projected area of the downward-facing clipped faces, m²

  void add(const Vector3d& a, const Vector3d& b, const Vector3d& c) { tetrahedra.add(a, b, c); }
  geometry::Moments moments() const { return tetrahedra.moments(); }
};

/// Adds the part below the plane z = 0 of the triangle v (corners relative to o, H axes) as
/// fan pieces with apex o (MODEL.md §1: the region is mesh ∩ {z_H ≤ 0}), and its shadow on
/// the plane if it faces down. With o and the crossing points exactly on the plane, the cap
/// polygon contributes nothing and is not built; the heights that decide a corner's side are
/// the very coordinates the pieces are made of, so shallow contacts keep their digits.
inline void clipTriangle(const Vector3d (&v)[3], FanSum& out) {
  const int inside = (v[0].z() < 0.0) + (v[1].z() < 0.0) + (v[2].z() < 0.0);
  if (inside == 0) return;
  // Twice the projected area of the whole face, negative when it faces down; the clipped part
  // keeps a fraction of it (a triangle and its sub-polygons share one normal).
  const double up2 =
      (v[1].x() - v[0].x()) * (v[2].y() - v[0].y()) - (v[1].y() - v[0].y()) * (v[2].x() - v[0].x());
  if (inside == 3) {
    out.add(v[0], v[1], v[2]);
    if (up2 < 0.0) out.area -= 0.5 * up2;
    return;
  }
  // Rotate so that the lone vertex (inside when inside == 1, outside when 2) comes first;
  // the cyclic order, and with it the orientation, is kept.
  const bool loneInside = inside == 1;
  int k0 = 0;
  while ((v[k0].z() < 0.0) != loneInside) ++k0;
  const Vector3d& a = v[k0];
  const Vector3d& b = v[(k0 + 1) % 3];
  const Vector3d& c = v[(k0 + 2) % 3];
  // The edges from the lone corner cross the plane at fractions tb, tc of their length.
  const double tb = a.z() / (a.z() - b.z()), tc = a.z() / (a.z() - c.z());
  Vector3d pb = a + tb * (b - a), pc = a + tc * (c - a);
  pb.z() = 0.0;
  pc.z() = 0.0;
  double kept;  // fraction of the face's area below the plane
  if (loneInside) {
    out.add(a, pb, pc);
    kept = tb * tc;
  } else {
    out.add(pb, b, c);
    out.add(pb, c, pc);
    kept = 1.0 - tb * tc;
  }
  if (up2 < 0.0) out.area -= 0.5 * kept * up2;
}

/// The pose X_HM applied one coordinate at a time: z_H alone decides which side a vertex is
/// on, and x_H, y_H are needed only for triangles that reach below the plane. Each coordinate
/// is summed in the order Eigen's `X_HM * p` uses, so the heights are the same numbers as
/// those of the transformed vertex (callers and tests may compute a depth either way).
struct Placement {
  explicit Placement(const Eigen::Isometry3d& X_HM) : R(X_HM.linear()), t(X_HM.translation()) {}
  double coordinate(int i, const Vector3d& p) const {
    return R(i, 0) * p.x() + R(i, 1) * p.y() + R(i, 2) * p.z() + t(i);
  }
  double z(const Vector3d& p) const { return coordinate(2, p); }
  Vector3d place(const Vector3d& p) const {
    return Vector3d(coordinate(0, p), coordinate(1, p), coordinate(2, p));
  }
  /// z_H in M axes: the plane's upward normal seen from the mesh.
  Vector3d up() const { return R.row(2).transpose(); }

  Eigen::Matrix3d R;
  Vector3d t;
};

/// Clips the triangle with corners p_H (placed in H) about o_H into `out`.
inline void clipPlacedTriangle(const Vector3d* const (&p_H)[3], const Vector3d& o_H, FanSum& out) {
  if (p_H[0]->z() >= 0.0 && p_H[1]->z() >= 0.0 && p_H[2]->z() >= 0.0) return;
  Vector3d v[3];
  for (int k = 0; k < 3; ++k) {
    v[k] = Vector3d(p_H[k]->x() - o_H.x(), p_H[k]->y() - o_H.y(), p_H[k]->z());
  }
  clipTriangle(v, out);
}

/// Clips triangle f of `mesh` (placed by X_HM) about o_H into `out`.
inline void clipFace(const geometry::TriangleMesh& mesh, Eigen::Index f, const Placement& X_HM,
                     const Vector3d& o_H, FanSum& out) {
  const Vector3d p[3] = {X_HM.place(mesh.corner(f, 0)), X_HM.place(mesh.corner(f, 1)),
                         X_HM.place(mesh.corner(f, 2))};
  clipPlacedTriangle({&p[0], &p[1], &p[2]}, o_H, out);
}

/// Vertices placed in H during one query, by vertex index (StampedValues). Reused across queries on
/// a thread, so a query allocates nothing once the largest mesh has been seen.
class PlacedVertices {
 public:
  /// The thread's cache, emptied for a new query on a mesh of `vertexCount` vertices.
  static PlacedVertices& forQuery(Eigen::Index vertexCount) {
    thread_local PlacedVertices cache;
    const auto n = static_cast<std::size_t>(vertexCount);
    cache.p_H_.reset(n);
    return cache;
  }

  /// Vertex i of `mesh` in H, placed now unless already placed in this query.
  const Vector3d& get(const geometry::TriangleMesh& mesh, int i, const Placement& X_HM) {
    bool fresh;
    Vector3d& p_H = p_H_.slot(i, fresh);
    if (fresh) p_H = X_HM.place(mesh.vertex(i));
    return p_H;
  }

 private:
  StampedValues<Vector3d> p_H_;
};

/// o: the deepest vertex (given in H) dropped onto the plane, in H and in M.
struct Apex {
  Vector3d o_H, o_M;
  Apex(const Eigen::Isometry3d& X_HM, const Vector3d& deepest_H)
      : o_H(deepest_H.x(), deepest_H.y(), 0.0), o_M(X_HM.inverse() * o_H) {}
};

/// The clip's sums as ClippedMoments in H: `inH` about o in H axes, `inM` about o in M axes.
inline ClippedMoments toHalfspaceFrame(const geometry::Moments& inH, const geometry::Moments& inM,
                                       double area, double depth, const Vector3d& o_H,
                                       const Eigen::Matrix3d& R_HM) {
  ClippedMoments out;
  out.moments.m0 = inH.m0 + inM.m0;
  out.moments.m1 = inH.m1 + R_HM * inM.m1;
  out.moments.m2 = inH.m2 + R_HM * inM.m2 * R_HM.transpose();
  out.area = area;
  out.depth = depth;
  out.origin = o_H;
  return out;
}

/// The cap segment a face that straddles the plane adds to the boundary of the clipped
/// solid, as the pair of its crossing edges (start → end), or none when the face does not
/// straddle. The cap's outward normal is +z_H, so its outer loops run counter-clockwise seen
/// from above: the cap runs each plane segment against its face's clipped polygon (lone corner
/// a below: polygon a → p_ab → p_ca, cap p_ca → p_ab; a above: cap p_ab → p_ca).
struct CapSegment {
  int from = -1, to = -1;  ///< topology edge indices
  int face = -1;           ///< the face it lies on
};
inline CapSegment capSegment(const MeshTopology& topo, int f, const Vector3d* const (&p_H)[3]) {
  const int inside = (p_H[0]->z() < 0.0) + (p_H[1]->z() < 0.0) + (p_H[2]->z() < 0.0);
  if (inside == 0 || inside == 3) return {};
  const bool loneInside = inside == 1;
  int k0 = 0;
  while ((p_H[k0]->z() < 0.0) != loneInside) ++k0;
  const int ab = topo.cornerEdge(f, k0), ca = topo.cornerEdge(f, (k0 + 2) % 3);
  return loneInside ? CapSegment{ca, ab, f} : CapSegment{ab, ca, f};
}

/// The cap loops of one query: the successor of each crossing edge along the cap boundary.
class CapLoops {
 public:
  /// The thread's loops, emptied for a mesh of `edgeCount` edges.
  static CapLoops& forQuery(std::size_t edgeCount) {
    thread_local CapLoops loops;
    loops.next_.reset(edgeCount);
    loops.segments_.clear();
    return loops;
  }

  void add(const CapSegment& s) {
    if (s.from < 0) return;
    bool fresh;
    next_.slot(s.from, fresh) = s.to;
    segments_.push_back(s);
  }

  /// Do the segments close into exactly one loop? (True with no segment at all.)
  bool oneLoop() {
    if (segments_.empty()) return true;
    const int first = segments_.front().from;
    std::size_t steps = 1;
    for (int e = next_[first]; e != first && steps <= segments_.size(); e = next_[e]) ++steps;
    return steps == segments_.size();
  }

  const std::vector<CapSegment>& segments() const { return segments_; }
  int next(int e) { return next_[e]; }

 private:
  StampedValues<int> next_;
  std::vector<CapSegment> segments_;
};

/// One closed cap loop on the plane: its crossing points (x_H, y_H) and signed area (> 0: an
/// outer boundary of the cap, < 0: a hole).
struct CapLoop {
  std::vector<Eigen::Vector2d> points;
  double signedArea = 0.0;
  int face = -1;  ///< a face of the surface it bounds

  /// Crossing-number test (Haines, "Point in Polygon Strategies", Graphics Gems IV).
  bool contains(const Eigen::Vector2d& q) const {
    bool in = false;
    for (std::size_t i = 0, j = points.size() - 1; i < points.size(); j = i++) {
      const Eigen::Vector2d& a = points[i];
      const Eigen::Vector2d& b = points[j];
      if ((a.y() > q.y()) != (b.y() > q.y()) &&
          q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x()) {
        in = !in;
      }
    }
    return in;
  }
};

/// Where edge e crosses the plane, (x_H, y_H), from its lower-index end (one value per edge);
/// `placed(v)` is vertex v in H.
template <class Placed>
Eigen::Vector2d capCrossing(const MeshTopology& topo, int e, Placed& placed) {
  const geometry::MeshEdge& edge = topo.edges()[static_cast<std::size_t>(e)];
  const Vector3d& a = placed(edge.v0);
  const Vector3d& b = placed(edge.v1);
  const double t = a.z() / (a.z() - b.z());
  return {a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y())};
}

/// The closed loops of the recorded cap segments, with their crossing points and signed areas
/// (shoelace formula).
template <class Placed>
std::vector<CapLoop> traceCapLoops(CapLoops& caps, const MeshTopology& topo, Placed placed) {
  thread_local StampSet seen;
  seen.reset(topo.edges().size());
  std::vector<CapLoop> loops;
  for (const CapSegment& s : caps.segments()) {
    if (!seen.insert(s.from)) continue;
    CapLoop loop;
    loop.face = s.face;
    for (int e = s.from;;) {
      loop.points.push_back(capCrossing(topo, e, placed));
      e = caps.next(e);
      if (!seen.insert(e)) break;
    }
    for (std::size_t i = 0, j = loop.points.size() - 1; i < loop.points.size(); j = i++) {
      loop.signedArea +=
          0.5 * (loop.points[j].x() * loop.points[i].y() - loop.points[i].x() * loop.points[j].y());
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The connected components of the clip whose straddling leaves are `straddling` (PatchClip,
/// halfspace/clip_patches.cpp), or none when it is one. Vertices are placed in H by `X_HM` through
/// `placed`, the query's cache.
std::vector<ClippedMoments> clipPatches(const geometry::TriangleMesh& mesh,
                                        const MeshTopology& topo, const Placement& X_HM,
                                        PlacedVertices& placed,
                                        const std::vector<const geometry::BvhNode*>& straddling,
                                        const std::vector<int>& order);

}  // namespace vcontact::volume::internal
