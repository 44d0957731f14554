#include "volume/halfspace_clip.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "volume/bvh_cache.hpp"
#include "volume/mesh_convexity.hpp"
#include "volume/mesh_topology_cache.hpp"
#include "volume/stamp_set.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;
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
void clipTriangle(const Vector3d (&v)[3], FanSum& out) {
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
void clipPlacedTriangle(const Vector3d* const (&p_H)[3], const Vector3d& o_H, FanSum& out) {
  if (p_H[0]->z() >= 0.0 && p_H[1]->z() >= 0.0 && p_H[2]->z() >= 0.0) return;
  Vector3d v[3];
  for (int k = 0; k < 3; ++k) {
    v[k] = Vector3d(p_H[k]->x() - o_H.x(), p_H[k]->y() - o_H.y(), p_H[k]->z());
  }
  clipTriangle(v, out);
}

/// Clips triangle f of `mesh` (placed by X_HM) about o_H into `out`.
void clipFace(const geometry::TriangleMesh& mesh, Eigen::Index f, const Placement& X_HM,
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
ClippedMoments toHalfspaceFrame(const geometry::Moments& inH, const geometry::Moments& inM,
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
CapSegment capSegment(const MeshTopology& topo, int f, const Vector3d* const (&p_H)[3]) {
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

/// Smallest-index union-find over a query's face labels.
class LabelUnion {
 public:
  explicit LabelUnion(int n) : parent_(static_cast<std::size_t>(n)) {
    for (int i = 0; i < n; ++i) parent_[static_cast<std::size_t>(i)] = i;
  }
  int find(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      i = parent_[static_cast<std::size_t>(i)] =
          parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
    }
    return i;
  }
  void join(int i, int j) {
    i = find(i);
    j = find(j);
    if (i != j) parent_[static_cast<std::size_t>(std::max(i, j))] = std::min(i, j);
  }

 private:
  std::vector<int> parent_;
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

/// The clip split into the connected components of mesh ∩ {z_H ≤ 0}, for queries the single
/// patch test (CapLoops::oneLoop) could not settle. Steps:
///  1. label the faces that reach below the plane by flooding across edges with an end below,
///     from the faces of the straddling leaves, then from each shell wholly below;
///  2. join the labels whose cap loops bound one planar region: each hole loop belongs to the
///     smallest outer loop around it (an upright cup cut through its walls joins its outer
///     and inner walls only through the annular cap);
///  3. clip each face about its component's own apex (its deepest vertex dropped onto the
///     plane), so each patch keeps the digits of its own size.
/// Costs O(faces below the plane), paid only by queries with several cap regions; step 3 only
/// when there are several components.
/// @pre the mesh's shells are not nested (no cavities)
class PatchClip {
 public:
  PatchClip(const geometry::TriangleMesh& mesh, const MeshTopology& topo, const Placement& X_HM,
            PlacedVertices& placed)
      : mesh_(mesh), topo_(topo), placement_(X_HM), placed_(placed) {}

  std::vector<ClippedMoments> run(const std::vector<const BvhNode*>& straddling,
                                  const std::vector<int>& order) {
    thread_local StampedValues<int> label;
    thread_local std::vector<int> faces, labelStart;
    label.reset(static_cast<std::size_t>(mesh_.triangleCount()));
    faces.clear();
    labelStart.clear();
    label_ = &label;
    faces_ = &faces;
    labelStart_ = &labelStart;
    for (const BvhNode* node : straddling) {
      for (int i = node->first; i < node->first + node->count; ++i) flood(order[i]);
    }
    for (const geometry::MeshComponent& shell : topo_.components()) {
      const int v = shell.vertices.front();
      if (z(v) < 0.0) flood(*topo_.facesBegin(v));
    }
    labelStart.push_back(static_cast<int>(faces.size()));
    const int labels = static_cast<int>(labelStart.size()) - 1;
    LabelUnion components(labels);
    joinThroughCaps(components);
    int roots = 0;
    for (int l = 0; l < labels; ++l) roots += components.find(l) == l;
    if (roots == 1) return {};  // one component: the merged clip is it
    return clipComponents(components, labels);
  }

 private:
  const Vector3d& p(int v) { return placed_.get(mesh_, v, placement_); }
  double z(int v) { return p(v).z(); }
  bool reachesBelow(int f) {
    return z(mesh_.triangles(f, 0)) < 0.0 || z(mesh_.triangles(f, 1)) < 0.0 ||
           z(mesh_.triangles(f, 2)) < 0.0;
  }

  /// Labels the faces connected to `seed` below the plane with a new label, unless labelled.
  void flood(int seed) {
    if (label_->contains(seed) || !reachesBelow(seed)) return;
    const int id = static_cast<int>(labelStart_->size());
    labelStart_->push_back(static_cast<int>(faces_->size()));
    bool fresh;
    label_->slot(seed, fresh) = id;
    faces_->push_back(seed);
    for (std::size_t i = faces_->size() - 1; i < faces_->size(); ++i) {
      const int f = (*faces_)[i];
      for (int k = 0; k < 3; ++k) {
        const geometry::MeshEdge& e =
            topo_.edges()[static_cast<std::size_t>(topo_.cornerEdge(f, k))];
        if (!(z(e.v0) < 0.0 || z(e.v1) < 0.0)) continue;
        const int g = e.tri[0] == f ? e.tri[1] : e.tri[0];
        int& slot = label_->slot(g, fresh);
        if (!fresh) continue;
        slot = id;
        faces_->push_back(g);
      }
    }
  }

  /// Step 2: the cap loops of the labelled faces, and each hole joined to its outer loop.
  void joinThroughCaps(LabelUnion& components) {
    CapLoops& caps = CapLoops::forQuery(topo_.edges().size());
    for (int f : *faces_) {
      const Vector3d* corners[3] = {&p(mesh_.triangles(f, 0)), &p(mesh_.triangles(f, 1)),
                                    &p(mesh_.triangles(f, 2))};
      caps.add(capSegment(topo_, f, corners));
    }
    const std::vector<CapLoop> loops =
        traceCapLoops(caps, topo_, [this](int v) -> const Vector3d& { return p(v); });
    for (const CapLoop& hole : loops) {
      if (hole.signedArea >= 0.0) continue;
      const CapLoop* around = nullptr;
      for (const CapLoop& outer : loops) {
        if (outer.signedArea > 0.0 && (!around || outer.signedArea < around->signedArea) &&
            outer.contains(hole.points.front())) {
          around = &outer;
        }
      }
      if (around) components.join((*label_)[hole.face], (*label_)[around->face]);
    }
  }

  /// Step 3: each component's faces clipped about its own apex.
  std::vector<ClippedMoments> clipComponents(LabelUnion& components, int labels) {
    std::vector<int> root(static_cast<std::size_t>(labels));
    std::vector<double> lowest(static_cast<std::size_t>(labels),
                               std::numeric_limits<double>::infinity());
    std::vector<Vector3d> deepest(static_cast<std::size_t>(labels));
    for (int l = 0; l < labels; ++l) {
      const int r = root[static_cast<std::size_t>(l)] = components.find(l);
      for (int i = (*labelStart_)[l]; i < (*labelStart_)[l + 1]; ++i) {
        for (int k = 0; k < 3; ++k) {
          const Vector3d& v = p(mesh_.triangles((*faces_)[i], k));
          if (v.z() < lowest[static_cast<std::size_t>(r)]) {
            lowest[static_cast<std::size_t>(r)] = v.z();
            deepest[static_cast<std::size_t>(r)] = v;
          }
        }
      }
    }
    std::vector<FanSum> sums(static_cast<std::size_t>(labels));
    for (int l = 0; l < labels; ++l) {
      const std::size_t r = static_cast<std::size_t>(root[static_cast<std::size_t>(l)]);
      const Vector3d o_H(deepest[r].x(), deepest[r].y(), 0.0);
      for (int i = (*labelStart_)[l]; i < (*labelStart_)[l + 1]; ++i) {
        const int f = (*faces_)[i];
        clipPlacedTriangle(
            {&p(mesh_.triangles(f, 0)), &p(mesh_.triangles(f, 1)), &p(mesh_.triangles(f, 2))}, o_H,
            sums[r]);
      }
    }
    std::vector<ClippedMoments> out;
    for (int l = 0; l < labels; ++l) {
      const std::size_t r = static_cast<std::size_t>(l);
      if (root[r] != l) continue;
      const Vector3d o_H(deepest[r].x(), deepest[r].y(), 0.0);
      out.push_back(toHalfspaceFrame(sums[r].moments(), geometry::Moments{}, sums[r].area,
                                     -lowest[r], o_H, Eigen::Matrix3d::Identity()));
    }
    return out;
  }

  const geometry::TriangleMesh& mesh_;
  const MeshTopology& topo_;
  const Placement& placement_;
  PlacedVertices& placed_;
  StampedValues<int>* label_ = nullptr;
  std::vector<int>* faces_ = nullptr;       ///< labelled faces, grouped by label
  std::vector<int>* labelStart_ = nullptr;  ///< label l's faces: [labelStart[l], labelStart[l+1])
};

// A straddling subtree of at most this many triangles is clipped triangle by triangle rather
// than opened further: telling a triangle's side from its three heights costs less than
// bounding a node, and a triangle wholly above the plane costs nothing more.
constexpr int kClipLeafSize = 8;

// A box is treated as wholly on one side only when its z-range clears the plane by more than
// the rounding of the range itself (a few ulps of the coordinates); closer boxes are opened
// and their triangles clipped one by one exactly as the reference does.
constexpr double kBoxRoundingUlps = 16.0;

/// Traversal state of the accelerated clip. Nodes are bounded in the mesh frame M; wholly
/// below subtrees add their fan moments about o in M axes, rotated into H once at the end;
/// only triangles of straddling subtrees that reach below the plane are placed in H.
class BvhClip {
 public:
  BvhClip(const MeshBvh& bvh, const Eigen::Isometry3d& X_HM)
      : bvh_(bvh),
        mesh_(bvh.mesh()),
        X_HM_(X_HM),
        placement_(X_HM),
        up_(placement_.up()),
        absUp_(up_.cwiseAbs()),
        slackScale_(kBoxRoundingUlps * std::numeric_limits<double>::epsilon()),
        slackBase_(X_HM.translation().cwiseAbs().sum()) {}

  /// With `topo`, run() also tells whether the clip is one patch (onePatch) and patches() can
  /// split it.
  BvhClip(const MeshBvh& bvh, const MeshTopology& topo, const Eigen::Isometry3d& X_HM)
      : BvhClip(bvh, X_HM) {
    topo_ = &topo;
  }

  /// Is the clip of the last run() one connected region? Settled cheaply when the straddling
  /// faces' cap segments close into a single loop on a one-shell mesh (then one cap region,
  /// and every part below a crossing shell reaches the cap); false otherwise, even when
  /// patches() then finds one component. @pre constructed with a topology
  bool onePatch() const { return onePatch_; }

  /// The connected components of the last run()'s clip (PatchClip), or none when it is one
  /// (the merged clip is then the patch). @pre run() found contact
  std::vector<ClippedMoments> patches() const {
    return PatchClip(mesh_, *topo_, placement_, *placed_).run(*straddling_, bvh_.order());
  }

  ClippedMoments run() {
    // Scratch lists reused across queries on this thread: a query allocates nothing.
    thread_local std::vector<const BvhNode*> below, straddling;
    below.clear();
    straddling.clear();
    below_ = &below;
    straddling_ = &straddling;
    collect(bvh_.root());
    // The lowest vertex lies in a collected node (it is below the plane when there is
    // contact); search only those, the lowest-reaching first.
    double best = std::numeric_limits<double>::infinity();
    for (const BvhNode* node : below) best = deepestZ(*node, best);
    for (const BvhNode* node : straddling) best = deepestZ(*node, best);
    if (!(best < 0.0)) return ClippedMoments{};
    const Apex apex(X_HM_, deepest_);
    FanSum clipped;
    PlacedVertices& placed = PlacedVertices::forQuery(mesh_.vertexCount());
    placed_ = &placed;
    CapLoops* caps = topo_ ? &CapLoops::forQuery(topo_->edges().size()) : nullptr;
    for (const BvhNode* node : straddling) {
      for (int i = node->first; i < node->first + node->count; ++i) {
        clipPlacedFace(bvh_.order()[i], placed, apex.o_H, clipped, caps);
      }
    }
    onePatch_ = caps && !caps->segments().empty() && topo_->components().size() == 1 &&
                (caps->oneLoop() || oneCapRegion(*caps, placed));
    // Wholly-below subtrees are summed about o in M axes and rotated into H once.
    geometry::Moments belowInM;
    double area = clipped.area;
    for (const BvhNode* node : below) {
      belowInM += geometry::fanMoments(node->integrals, node->center - apex.o_M);
      area += downwardArea(*node);
    }
    return toHalfspaceFrame(clipped.moments(), belowInM, area, -best, apex.o_H, X_HM_.linear());
  }

 private:
  struct ZRange {
    double lo, hi;
  };

  /// Clips triangle f with each corner placed in H once per query: the ~6 triangles around a
  /// vertex of a straddling leaf share its coordinates. They are the numbers clipFace places
  /// (same sums, same order), so the clip stays bit-identical to the reference.
  /// Do the cap loops bound a single planar region (one outer loop, any holes)? Then the clip
  /// of a one-shell mesh is one component (each component has a region of its own).
  bool oneCapRegion(CapLoops& caps, PlacedVertices& placed) const {
    const std::vector<CapLoop> loops = traceCapLoops(
        caps, *topo_, [&](int v) -> const Vector3d& { return placed.get(mesh_, v, placement_); });
    return std::count_if(loops.begin(), loops.end(),
                         [](const CapLoop& l) { return l.signedArea > 0.0; }) == 1;
  }

  /// With `caps`, also records the face's cap segment.
  void clipPlacedFace(int f, PlacedVertices& placed, const Vector3d& o_H, FanSum& out,
                      CapLoops* caps) const {
    const Vector3d* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &placed.get(mesh_, mesh_.triangles(f, k), placement_);
    clipPlacedTriangle(p, o_H, out);
    if (caps) caps->add(capSegment(*topo_, f, p));
  }

  /// Bounds of z_H over the node's vertices: the tighter of its box and its normal slab.
  /// With n = the plane normal in M, split into a part along the slab axis a and the rest:
  /// (p − c)·n = (n·a) s + (p − c)·n_⊥ with s ∈ [axialLo, axialHi], |…| ≤ |n_⊥| ρ.
  /// The slab is worked out only when the box alone cannot place the node.
  ZRange zRange(const BvhNode& node) const {
    const double cz = placement_.z(node.center);
    const double boxExtent = absUp_.dot(node.halfExtent);
    const double slack = slackScale_ * (std::abs(cz) + boxExtent + slackBase_);
    ZRange box{cz - boxExtent - slack, cz + boxExtent + slack};
    if (box.lo >= 0.0 || box.hi < 0.0) return box;
    const double na = up_.dot(node.normalAxis);
    // |n_⊥| = sin∠(z_H, a) from the cross product: √(1 − (n·a)²) cancels when the axis is
    // nearly along z_H (a flat face nearly parallel to the plane) and can lose all its digits.
    const double perp = up_.cross(node.normalAxis).norm() * node.radialExtent;
    const double slabLo = std::min(na * node.axialLo, na * node.axialHi) - perp;
    const double slabHi = std::max(na * node.axialLo, na * node.axialHi) + perp;
    return {std::max(box.lo, cz + slabLo - slack), std::min(box.hi, cz + slabHi + slack)};
  }

  /// Branch and bound for the lowest vertex; returns the best z so far.
  double deepestZ(const BvhNode& node, double best) {
    return deepestZ(node, zRange(node).lo, best);
  }

  /// The same with the node's lower bound `lo` already known (each bound computed once).
  double deepestZ(const BvhNode& node, double lo, double best) {
    if (lo >= best) return best;
    if (node.isLeaf()) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        for (int k = 0; k < 3; ++k) {
          const Vector3d p = mesh_.corner(bvh_.order()[i], k);
          const double z = placement_.z(p);
          if (z < best) {
            best = z;
            deepest_ = X_HM_ * p;
          }
        }
      }
      return best;
    }
    const BvhNode& l = bvh_.nodes()[node.left];
    const BvhNode& r = bvh_.nodes()[node.right];
    const double loL = zRange(l).lo, loR = zRange(r).lo;
    if (loL <= loR) return deepestZ(r, loR, deepestZ(l, loL, best));
    return deepestZ(l, loL, deepestZ(r, loR, best));
  }

  /// Sorts the tree into subtrees wholly below the plane and leaves that straddle it;
  /// subtrees wholly above are dropped.
  void collect(const BvhNode& node) {
    const ZRange z = zRange(node);
    if (z.lo >= 0.0) return;
    if (z.hi < 0.0) {
      below_->push_back(&node);
    } else if (node.isLeaf() || node.count <= kClipLeafSize) {
      straddling_->push_back(&node);
    } else {
      collect(bvh_.nodes()[node.left]);
      collect(bvh_.nodes()[node.right]);
    }
  }

  /// Projected area onto z_H = 0 of the node's faces with n_z < 0: −(n·∫n dA) when the
  /// normal cone lies wholly below the horizontal, 0 when wholly above, else per child.
  double downwardArea(const BvhNode& node) const {
    const double axisZ = up_.dot(node.normalAxis);
    if (axisZ <= -node.normalSinHalfAngle) return -up_.dot(node.integrals.F);
    if (axisZ >= node.normalSinHalfAngle) return 0.0;
    if (!node.isLeaf()) {
      return downwardArea(bvh_.nodes()[node.left]) + downwardArea(bvh_.nodes()[node.right]);
    }
    double area = 0.0;
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int f = bvh_.order()[i];
      const Vector3d a = mesh_.corner(f, 0);
      const double up2 = (mesh_.corner(f, 1) - a).cross(mesh_.corner(f, 2) - a).dot(up_);
      if (up2 < 0.0) area -= 0.5 * up2;
    }
    return area;
  }

  const MeshBvh& bvh_;
  const geometry::TriangleMesh& mesh_;
  const Eigen::Isometry3d X_HM_;
  const Placement placement_;
  const Vector3d up_;        ///< z_H in M axes
  const Vector3d absUp_;     ///< |z_H| componentwise, for a box's extent along it
  const double slackScale_;  ///< kBoxRoundingUlps · eps
  const double slackBase_;   ///< |translation|₁, the size the heights are rounded against
  Vector3d deepest_ = Vector3d::Zero();  ///< deepest vertex, H
  std::vector<const BvhNode*>* below_ = nullptr;
  std::vector<const BvhNode*>* straddling_ = nullptr;
  const MeshTopology* topo_ = nullptr;
  PlacedVertices* placed_ = nullptr;
  bool onePatch_ = false;
};

}  // namespace

ClippedMoments clipMeshByHalfspace(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_HM) {
  if (mesh.vertexCount() == 0) return ClippedMoments{};
  const Placement placement(X_HM);
  Eigen::Index deepest = 0;
  double zmin = placement.z(mesh.vertex(0));
  for (Eigen::Index i = 1; i < mesh.vertexCount(); ++i) {
    const double z = placement.z(mesh.vertex(i));
    if (z < zmin) {
      zmin = z;
      deepest = i;
    }
  }
  if (!(zmin < 0.0)) return ClippedMoments{};
  const Apex apex(X_HM, X_HM * mesh.vertex(deepest));
  FanSum sum;
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    clipFace(mesh, f, placement, apex.o_H, sum);
  }
  return toHalfspaceFrame(sum.moments(), geometry::Moments{}, sum.area, -zmin, apex.o_H,
                          X_HM.linear());
}

ClippedMoments clipMeshByHalfspace(const MeshBvh& bvh, const Eigen::Isometry3d& X_HM) {
  return BvhClip(bvh, X_HM).run();
}

ContactVolume contactFromClippedMoments(const ClippedMoments& clipped,
                                        const Eigen::Isometry3d& X_WH, Method method) {
  const geometry::Moments& M = clipped.moments;
  if (!(M.m0 > 0.0)) return ContactVolume{.method = method};
  return contactFromMoments(M, clipped.origin, X_WH, X_WH.linear().col(2), clipped.area,
                            clipped.depth, method);
}

ContactVolume meshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH) {
  return contactFromClippedMoments(clipMeshByHalfspace(mesh, X_WH.inverse() * X_WM), X_WH,
                                   Method::kHalfspace);
}

ContactVolume meshHalfspaceContact(const MeshBvh& bvh, const Eigen::Isometry3d& X_WM,
                                   const Eigen::Isometry3d& X_WH) {
  return contactFromClippedMoments(clipMeshByHalfspace(bvh, X_WH.inverse() * X_WM), X_WH,
                                   Method::kHalfspace);
}

ContactPatches meshHalfspacePatches(const MeshBvh& bvh, const MeshTopology& topo,
                                    const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH) {
  BvhClip clip(bvh, topo, X_WH.inverse() * X_WM);
  ContactPatches contact =
      singlePatch(contactFromClippedMoments(clip.run(), X_WH, Method::kHalfspace));
  if (!contact.inContact() || clip.onePatch()) return contact;
  const std::vector<ClippedMoments> patches = clip.patches();
  if (patches.empty()) return contact;
  contact.patches.clear();
  for (const ClippedMoments& patch : patches) {
    contact.patches.push_back(contactFromClippedMoments(patch, X_WH, Method::kHalfspace));
  }
  sortPatches(contact.patches);
  return contact;
}

namespace {

/// A mesh shape (B1) against a half-space: a convex mesh is one patch, the clip itself.
ContactPatches meshShapeHalfspacePatches(const std::shared_ptr<const geometry::TriangleMesh>& mesh,
                                         const Eigen::Isometry3d& X_WM,
                                         const Eigen::Isometry3d& X_WH) {
  if (isConvex(mesh)) return singlePatch(meshHalfspaceContact(*bvhOf(mesh), X_WM, X_WH));
  return meshHalfspacePatches(*bvhOf(mesh), *topologyOf(mesh), X_WM, X_WH);
}

}  // namespace

ContactPatches halfspaceClipContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                                    const geometry::Shape& b, const Eigen::Isometry3d& X_WB) {
  if (const auto* mesh = std::get_if<geometry::Mesh>(&a)) {
    assert(std::holds_alternative<geometry::HalfSpace>(b));
    return meshShapeHalfspacePatches(mesh->mesh, X_WA, X_WB);
  }
  assert(std::holds_alternative<geometry::HalfSpace>(a) &&
         std::holds_alternative<geometry::Mesh>(b));
  return swapped(meshShapeHalfspacePatches(std::get<geometry::Mesh>(b).mesh, X_WB, X_WA));
}

}  // namespace vcontact::volume
