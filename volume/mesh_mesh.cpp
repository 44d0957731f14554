#include "volume/mesh_mesh.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include "geometry/moments.hpp"
#include "volume/bvh_cache.hpp"
#include "volume/exact_predicates.hpp"
#include "volume/mesh_topology_cache.hpp"
#include "volume/stamp_set.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;
using geometry::MeshEdge;
using geometry::MeshTopology;

constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Boxes are grown by this fraction of the largest coordinate in play. Placing a vertex in W
/// or in the other body's frame rounds it by a few ε of that size; 1e-12 (≈ 4500 ε) covers
/// it many times over, so the broad phase never drops a pair the exact predicates would see.
constexpr double kBoxMargin = 1e-12;
/// A double orient3d det[u, v, w] of rounded differences is within this factor times
/// ‖u‖₁‖v‖₁‖w‖₁ (≥ the permanent) of the exact value: ≈ 8ε from the differences, products
/// and sums (Shewchuk 1997 bounds orient3d by 7ε of the permanent); 32ε for margin.
constexpr double kOrientBound = 32.0 * kEps;
/// A region whose volume is below kVolumeNoise·ε·(the V error from moving every boundary
/// point by ε·scale, plus the terms' own rounding) is rounding noise: the bodies touch (a
/// perturbed flat contact) without overlapping. Each point is placed or constructed to a
/// few ε of the largest coordinate; 64 leaves a factor of ten.
constexpr double kVolumeNoise = 64.0;
/// The two boundary parts' area vectors are each of the order of Σ|patch area| and cancel
/// to rounding (a few ε times the ratio of the coordinates' size to the region's, far below
/// 1e-9 for any region above a millionth of its distance from the origin) when the region is
/// bounded by one body alone; below this fraction n is undefined (contactNormal).
constexpr double kNormalNoise = 1e-9;
/// Crossings closer than this along their edge (as a fraction of its length) may be out of
/// order after sorting by the rounded λ; their order is then re-derived exactly
/// (orderAlongEdge). λ = d_p/(d_p − d_q) is good to a few ε unless the edge is within about
/// 1e-7 rad of the face's plane; a false alarm costs one exact parity test.
constexpr double kLambdaTie = 1e-9;

/// A face placed in W for one query, with what the face-pair tests use of it.
struct PlacedFace {
  Vector3d corner[3];  ///< W
  Vector3d n;          ///< (c1 − c0) × (c2 − c0), unnormalised
  double nBound;       ///< kOrientBound·‖c1 − c0‖₁‖c2 − c0‖₁ (planeSides)
  Vector3d lo, hi;     ///< axis-aligned box in W
};

/// A face's plane as the integration uses it.
struct FaceFoot {
  Vector3d normal;  ///< unit, outward, W
  Vector3d foot;    ///< the fan apex o projected onto the plane, W
};

/// Per-mesh memory reused by the queries of one thread, so a query costs what it touches.
struct SideScratch {
  StampedValues<Vector3d> p_W;      ///< vertices placed in W
  StampedValues<PlacedFace> faces;  ///< faces placed in W
  StampedValues<FaceFoot> feet;     ///< faces' planes for the integration
  StampSet inside;                  ///< vertices inside the other body
  std::vector<int> insideList;
  StampSet cut;  ///< faces with at least one intersection segment
  std::vector<int> cutList;
  StampSet crossingEdge;      ///< edges that cross the other surface
  StampSet coplanarSame;      ///< faces in the plane of a face of the other mesh, same way
  StampSet coplanarOpposite;  ///< ... facing it
  std::vector<char> seeded;   ///< per component: has a crossing edge
};

/// One edge of one mesh through one face of the other.
struct Crossing {
  int side;       ///< mesh of the edge: 0 = A, 1 = B
  int edge;       ///< edge index in that mesh
  int face;       ///< face of the other mesh
  int sigma;      ///< +1: the edge, run v0 → v1, enters the other body here; −1: leaves
  double lambda;  ///< position along v0 → v1, in [0, 1]
  Vector3d x;     ///< W
};

/// An end of the segment t_A ∩ t_B, oriented as the boundary of t_A ∩ B.
struct Endpoint {
  std::uint64_t key;  ///< (t_A << 32) | t_B
  int crossing;
  bool start;
};

/// A directed boundary edge (p → q) of the region t ∩ (other body), t a face of mesh `side`.
struct Piece {
  int side;
  int face;
  Vector3d p, q;
};

/// A boundary patch as the area and depth passes see it.
struct Patch {
  Vector3d normal;  ///< unit normal of its face
  double area;      ///< signed area (a piece's share of its face's region)
  Vector3d p, q;    ///< points of the patch, for the extent along n
};

struct WholeFace {
  int side;
  int face;
};

/// A node of A's tree in B's frame: box centre, the half-sizes of the axis-aligned box
/// around A's placed box (|R_BA|·h), normal-cone axis.
struct PlacedNode {
  Vector3d center, halfExtent, normalAxis;
};

struct Scratch {
  SideScratch sides[2];
  StampedValues<PlacedNode> nodesA;  ///< nodes of A's tree placed in B's frame
  std::vector<Crossing> crossings;
  std::vector<int> order;
  std::vector<Endpoint> endpoints;
  std::vector<Piece> pieces;
  std::vector<WholeFace> wholes;
  std::vector<std::pair<int, int>> nodeStack;
  std::vector<int> stack;
  /// Faces of B's leaf that meet A's leaf slab (testLeaves), with their placement.
  std::vector<std::pair<int, const PlacedFace*>> columns;
  std::vector<Patch> patches;
};

/// A mesh placed in W for one query.
struct Body {
  const MeshBvh& bvh;
  const MeshTopology& topo;
  Isometry3d X_WM;
  SideScratch& s;

  const geometry::TriangleMesh& mesh() const { return bvh.mesh(); }
  /// p_W of vertex v, placed on first use.
  const Vector3d& p(int v) {
    bool fresh;
    Vector3d& p_W = s.p_W.slot(v, fresh);
    if (fresh) p_W = X_WM * mesh().vertex(v);
    return p_W;
  }
  /// Face f placed in W, on first use (the look-up inline, the placement not: the descent
  /// asks for each face many times).
  const PlacedFace& face(int f) {
    if (s.faces.contains(f)) return s.faces[f];
    return placeFace(f);
  }
  const Vector3d& corner(int f, int k) { return p(mesh().triangles(f, k)); }
  /// Face f's unit outward normal and the foot of the fan apex o on its plane (W), on first
  /// use; o is the same for the whole query.
  const FaceFoot& foot(int f, const Vector3d& o) {
    bool fresh;
    FaceFoot& F = s.feet.slot(f, fresh);
    if (!fresh) return F;
    const Vector3d& a = corner(f, 0);
    const Vector3d N = (corner(f, 1) - a).cross(corner(f, 2) - a);
    F.normal = N * (1.0 / N.norm());              // one division, not three
    F.foot = o - F.normal * F.normal.dot(o - a);  // o projected onto the face's plane
    return F;
  }
  /// Places face f in W (face()'s first use).
  [[gnu::noinline]] const PlacedFace& placeFace(int f) {
    bool fresh;  // always: face() has looked
    PlacedFace& F = s.faces.slot(f, fresh);
    for (int k = 0; k < 3; ++k) F.corner[k] = corner(f, k);
    const Vector3d u = F.corner[1] - F.corner[0], v = F.corner[2] - F.corner[0];
    F.n = u.cross(v);
    F.nBound = kOrientBound * u.lpNorm<1>() * v.lpNorm<1>();
    F.lo = F.corner[0].cwiseMin(F.corner[1]).cwiseMin(F.corner[2]);
    F.hi = F.corner[0].cwiseMax(F.corner[1]).cwiseMax(F.corner[2]);
    return F;
  }
};

/// The symbolic translation of a segment of mesh `side` relative to the other mesh's faces:
/// A is the body moved by +τ (exact_predicates.hpp).
int perturbationSign(int side) { return side == 0 ? 1 : -1; }

/// Side of the plane of triangle T each point P[i] lies on, judged in double with the
/// rounding bound of orient3d: +1 or −1 when certain (the exact sign then agrees and no
/// perturbation is involved), 0 when within rounding of the plane.
/// @return +1 or −1 when all three are certainly on that side, else 0
int planeSides(const PlacedFace& T, const Vector3d* P, int* side) {
  for (int i = 0; i < 3; ++i) {
    const Vector3d w = P[i] - T.corner[0];
    const double d = T.n.dot(w);
    const double bound = T.nBound * w.lpNorm<1>();
    side[i] = int(d > bound) - int(d < -bound);  // without branches: the sign is data
  }
  return (side[0] == side[1]) & (side[1] == side[2]) ? side[0] : 0;
}

bool allCertain(const int* side) { return side[0] * side[1] * side[2] != 0; }

/// Index of the corner whose side differs from the other two's. @pre not all three equal
int loneCorner(const int* side) { return side[0] == side[1] ? 2 : (side[0] == side[2] ? 1 : 0); }

/// Are two triangles, each with corners certainly on both sides of the other's plane, certainly
/// disjoint? Guigue & Devillers 2003 ("Fast and robust triangle-triangle overlap test using
/// orientation predicates"): with the corners named so that p1 is alone on the positive side of
/// (p2, q2, r2) and p2 alone on the positive side of (p1, q1, r1) (a cyclic shift keeps a
/// triangle's plane, swapping its last two corners flips it), the triangles meet iff
/// orient3d(q1, p2, p1, q2) ≤ 0 and orient3d(p1, p2, r1, r2) ≤ 0: the two segments
/// tᵢ ∩ plane(tⱼ) overlap on the planes' common line. Only a certain positive sign (the double
/// filter) rejects, so a rejected pair is disjoint exactly and, every sign used being non-zero,
/// also under the perturbation: none of its edge–face tests could report a crossing.
/// @param sideA, sideB  certain sides (±1, none 0, not all equal) of A's corners against B's
///   plane and of B's against A's
bool certainlyDisjoint(const Vector3d* A, const int* sideA, const Vector3d* B, const int* sideB) {
  const int i = loneCorner(sideA);
  const Vector3d* T1[3] = {&A[i], &A[(i + 1) % 3], &A[(i + 2) % 3]};
  int b[3] = {0, 1, 2};                     // B's corners in T2's order
  if (sideA[i] < 0) std::swap(b[1], b[2]);  // flip T2 so that p1 is on its positive side
  const int sideT2[3] = {sideB[b[0]], sideB[b[1]], sideB[b[2]]};
  const int j = loneCorner(sideT2);
  const Vector3d& p2 = B[b[j]];
  const Vector3d& q2 = B[b[(j + 1) % 3]];
  const Vector3d& r2 = B[b[(j + 2) % 3]];
  if (sideT2[j] < 0) std::swap(T1[1], T1[2]);  // flip T1 so that p2 is on its positive side
  const Vector3d &p1 = *T1[0], &q1 = *T1[1], &r1 = *T1[2];
  return orient3dFiltered(q1, p2, p1, q2) > 0 || orient3dFiltered(p1, p2, r1, r2) > 0;
}

/// Are all three of a ≤ b? Evaluated without short-circuit branches: in the descent the
/// outcome is data, and one branch on the combined flag mispredicts less than three.
bool allLessEqual(const Vector3d& a, const Vector3d& b) {
  return (a.x() <= b.x()) & (a.y() <= b.y()) & (a.z() <= b.z());
}

/// The faces' axis-aligned boxes overlap (grown by `margin`)?
bool faceBoxesOverlap(const PlacedFace& A, const PlacedFace& B, double margin) {
  const Vector3d grow = Vector3d::Constant(margin);
  return allLessEqual(A.lo, B.hi + grow) & allLessEqual(B.lo, A.hi + grow);
}

/// Axis-aligned box of a body-frame box placed by X (conservative), as {centre, half-size}.
std::pair<Vector3d, Vector3d> placedBox(const Isometry3d& X, const Vector3d& center,
                                        const Vector3d& half) {
  return {X * center, X.linear().cwiseAbs() * half};
}

/// Do two boxes {centre, half-sizes} of one frame overlap when grown by `grow` on every side?
/// Forced inline: the descent's node test (out of line it costs 2–3 % of a query).
[[gnu::always_inline]] inline bool boxesOverlap(const Vector3d& centerA, const Vector3d& halfA,
                                                const Vector3d& centerB, const Vector3d& halfB,
                                                double grow) {
  return allLessEqual((centerA - centerB).cwiseAbs(), halfA + halfB + Vector3d::Constant(grow));
}

/// Segment p0 + t (p1 − p0), t ∈ [0, 1], meets the box (centre c, half-sizes h)?
bool segmentMeetsBox(const Vector3d& p0, const Vector3d& p1, const Vector3d& c, const Vector3d& h) {
  double t0 = 0.0, t1 = 1.0;
  const Vector3d d = p1 - p0;
  for (int k = 0; k < 3; ++k) {
    const double lo = c[k] - h[k] - p0[k], hi = c[k] + h[k] - p0[k];
    if (d[k] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return false;
      continue;
    }
    double a = lo / d[k], b = hi / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

class Intersector {
 public:
  Intersector(Body a, Body b, Scratch& scratch) : body_{a, b}, w_(scratch) {
    for (int side = 0; side < 2; ++side) {
      Body& m = body_[side];
      const auto nv = static_cast<std::size_t>(m.mesh().vertexCount());
      const auto nf = static_cast<std::size_t>(m.mesh().triangleCount());
      m.s.p_W.reset(nv);
      m.s.faces.reset(nf);
      m.s.feet.reset(nf);
      m.s.inside.reset(nv);
      m.s.insideList.clear();
      m.s.cut.reset(nf);
      m.s.cutList.clear();
      m.s.crossingEdge.reset(m.topo.edges().size());
      m.s.coplanarSame.reset(nf);
      m.s.coplanarOpposite.reset(nf);
      m.s.seeded.assign(m.topo.components().size(), 0);
    }
    const auto nodeCount = body_[0].bvh.nodes().size();
    w_.nodesA.reset(nodeCount);
    w_.crossings.clear();
    w_.endpoints.clear();
    w_.pieces.clear();
    w_.wholes.clear();
    const auto extent = [](const Body& m) {
      const BvhNode& r = m.bvh.root();
      return m.X_WM.translation().norm() + r.center.norm() + r.halfExtent.norm();
    };
    margin_ = kBoxMargin * (extent(body_[0]) + extent(body_[1]));
  }

  ContactVolume run(MeshMeshCache* cache) {
    findCrossings(cache);
    walkEdges();
    buildSegments();
    for (int side = 0; side < 2; ++side) {
      floodInside(side);
      classifyUnseededComponents(side);
      addWholeEdgesOfCutFaces(side);
      collectWholeFaces(side);
    }
    return integrate();
  }

  std::string describeFailure(const std::string& what) const {
    std::ostringstream s;
    s.precision(17);
    s << "fast mesh-mesh: " << what << "; X_WA =\n"
      << body_[0].X_WM.matrix() << "\nX_WB =\n"
      << body_[1].X_WM.matrix();
    return s.str();
  }

 private:
  // --- 1, 2: candidate face pairs and their crossings --------------------------------------

  void findCrossings(MeshMeshCache* cache) {
    const Isometry3d X_BA = body_[1].X_WM.inverse() * body_[0].X_WM;
    const Matrix3d absR = X_BA.linear().cwiseAbs();
    const auto& nodesA = body_[0].bvh.nodes();
    const auto& nodesB = body_[1].bvh.nodes();
    // Inlined: it is the descent's inner loop.
    const auto overlap = [&](int ia, int ib) __attribute__((always_inline)) {
      const BvhNode& na = nodesA[static_cast<std::size_t>(ia)];
      const BvhNode& nb = nodesB[static_cast<std::size_t>(ib)];
      const PlacedNode& pa = placeNodeOfA(ia, na, X_BA, absR);
      return boxesOverlap(pa.center, pa.halfExtent, nb.center, nb.halfExtent, margin_) &&
             slabsOverlap(na, pa.center, pa.normalAxis, nb);
    };
    const auto atLeaves = [&](int ia, int ib) __attribute__((always_inline)) {
      testLeaves(nodesA[static_cast<std::size_t>(ia)], nodesB[static_cast<std::size_t>(ib)]);
    };
    if (cache == nullptr) {
      descend(overlap, atLeaves);
      return;
    }
    if (cache->covers(body_[0].bvh, body_[1].bvh, X_BA)) {
      ++cache->reuses;
    } else {
      record(*cache, X_BA, absR);
    }
    for (const auto& [ia, ib] : cache->leafPairs) {
      if (overlap(ia, ib)) atLeaves(ia, ib);
    }
  }

  /// Descends both trees together from the roots: the up to four child pairs of a pair that
  /// `overlap`s are tested before they are pushed (both nodes are split at once, skipping the
  /// intermediate (child, parent) tests); `atLeaves` gets every overlapping pair of leaves.
  template <typename Overlap, typename AtLeaves>
  void descend(const Overlap& overlap, const AtLeaves& atLeaves) {
    const auto& nodesA = body_[0].bvh.nodes();
    const auto& nodesB = body_[1].bvh.nodes();
    auto& stack = w_.nodeStack;
    stack.clear();
    if (overlap(0, 0)) stack.emplace_back(0, 0);
    while (!stack.empty()) {
      const auto [ia, ib] = stack.back();
      stack.pop_back();
      const BvhNode& na = nodesA[static_cast<std::size_t>(ia)];
      const BvhNode& nb = nodesB[static_cast<std::size_t>(ib)];
      if (na.isLeaf() && nb.isLeaf()) {
        atLeaves(ia, ib);
        continue;
      }
      const int childrenA[2] = {na.isLeaf() ? ia : na.left, na.right};
      const int childrenB[2] = {nb.isLeaf() ? ib : nb.left, nb.right};
      for (int i = 0; i < (na.isLeaf() ? 1 : 2); ++i) {
        for (int j = 0; j < (nb.isLeaf() ? 1 : 2); ++j) {
          if (overlap(childrenA[i], childrenB[j])) stack.emplace_back(childrenA[i], childrenB[j]);
        }
      }
    }
  }

  /// Records in `cache` the leaf pairs whose boxes, A's placed in B's frame at X_BA, overlap
  /// when grown by the cache's reach m (MeshMeshCache): boxes only, since the slab bound of a
  /// turned node is not a grown copy of the old one. A node's placed box at a pose reached by
  /// moving A's points at most m lies within its box here grown by m, so any leaf pair that
  /// overlaps there is among those recorded.
  void record(MeshMeshCache& cache, const Isometry3d& X_BA, const Matrix3d& absR) {
    const auto& nodesA = body_[0].bvh.nodes();
    const auto& nodesB = body_[1].bvh.nodes();
    const BvhNode& rootA = body_[0].bvh.root();
    const BvhNode& rootB = body_[1].bvh.root();
    const double reach =
        MeshMeshCache::kReach * (rootA.halfExtent.norm() + rootB.halfExtent.norm());
    const auto grownOverlap = [&](int ia, int ib) {
      const BvhNode& na = nodesA[static_cast<std::size_t>(ia)];
      const BvhNode& nb = nodesB[static_cast<std::size_t>(ib)];
      const PlacedNode& pa = placeNodeOfA(ia, na, X_BA, absR);
      return boxesOverlap(pa.center, pa.halfExtent, nb.center, nb.halfExtent, margin_ + reach);
    };
    cache.leafPairs.clear();
    descend(grownOverlap, [&](int ia, int ib) { cache.leafPairs.emplace_back(ia, ib); });
    cache.a = &body_[0].bvh;
    cache.b = &body_[1].bvh;
    cache.X_BA = X_BA;
    cache.reach = reach;
    ++cache.refreshes;
  }

  /// Node ia of A's tree in B's frame, placed on first use in this query.
  const PlacedNode& placeNodeOfA(int ia, const BvhNode& na, const Isometry3d& X_BA,
                                 const Matrix3d& absR) {
    bool fresh;
    PlacedNode& P = w_.nodesA.slot(ia, fresh);
    if (!fresh) return P;
    P.center = X_BA * na.center;
    P.halfExtent = absR * na.halfExtent;
    P.normalAxis = X_BA.linear() * na.normalAxis;
    return P;
  }

  /// The slab bounds of two nodes (bvh.hpp: axial range along the normal axis, radius about
  /// it), both in B's frame: each node's vertices projected onto the other's axis must meet
  /// the other's axial range. Tight where boxes are not: two nearly flat, tilted patches.
  bool slabsOverlap(const BvhNode& na, const Vector3d& centerA, const Vector3d& axisA,
                    const BvhNode& nb) const {
    // cos and sin² of the angle between the axes, the same seen from either node. sin∠ from
    // the cross product: √(1 − k²) cancels for nearly parallel axes (two flat patches nearly
    // face to face) and can lose all its digits.
    const double k = axisA.dot(nb.normalAxis);
    const double sine2 = axisA.cross(nb.normalAxis).squaredNorm();
    // The gap between other's axial range (projected on slab's axis) and slab's own, before
    // other's radial part (≤ radialExtent·sin∠) is added: it must not exceed that part,
    // compared squared so that the descent needs no square root.
    const auto meets = [this, k, sine2](const BvhNode& slab, const Vector3d& slabCenter,
                                        const Vector3d& slabAxis, const BvhNode& other,
                                        const Vector3d& otherCenter) {
      // other's vertices: otherCenter + s·otherAxis + radial part (⟂ axis)
      const double c = (otherCenter - slabCenter).dot(slabAxis);
      const double below =
          c + std::min(k * other.axialLo, k * other.axialHi) - (slab.axialHi + margin_);
      const double above =
          (slab.axialLo - margin_) - (c + std::max(k * other.axialLo, k * other.axialHi));
      const double gap = std::max(below, above);
      return (gap <= 0.0) | (gap * gap <= other.radialExtent * other.radialExtent * sine2);
    };
    return meets(na, centerA, axisA, nb, nb.center) &
           meets(nb, nb.center, nb.normalAxis, na, centerA);
  }

  /// A node's slab (bvh.hpp) placed in W, its axial range grown by the box margin.
  struct PlacedSlab {
    Vector3d center, axis;
    double lo, hi;
  };
  PlacedSlab placedSlab(const Body& m, const BvhNode& n) const {
    return {m.X_WM * n.center, m.X_WM.linear() * n.normalAxis, n.axialLo - margin_,
            n.axialHi + margin_};
  }

  /// Does face F reach the axial range of slab S? Its axial coordinate is linear over the
  /// face, so the corners bound it; a face wholly beyond the range meets none of the slab's
  /// faces (the margin exceeds the rounding of both placements many times over).
  static bool faceMeetsSlab(const PlacedFace& F, const PlacedSlab& S) {
    const double s0 = (F.corner[0] - S.center).dot(S.axis);
    const double s1 = (F.corner[1] - S.center).dot(S.axis);
    const double s2 = (F.corner[2] - S.center).dot(S.axis);
    return std::max({s0, s1, s2}) >= S.lo && std::min({s0, s1, s2}) <= S.hi;
  }

  /// Every face pair of two leaves whose boxes overlap; a face that misses the other leaf's
  /// slab skips its row (column) at once. In shallow contact most faces of one leaf lie just
  /// inside the other body, beyond the thin slab of a nearly flat leaf of the other mesh.
  void testLeaves(const BvhNode& na, const BvhNode& nb) {
    const auto& orderA = body_[0].bvh.order();
    const auto& orderB = body_[1].bvh.order();
    const PlacedSlab slabA = placedSlab(body_[0], na);
    const PlacedSlab slabB = placedSlab(body_[1], nb);
    auto& columns = w_.columns;
    columns.clear();
    for (int j = nb.first; j < nb.first + nb.count; ++j) {
      const int tB = orderB[static_cast<std::size_t>(j)];
      const PlacedFace& FB = body_[1].face(tB);
      if (faceMeetsSlab(FB, slabA)) columns.push_back({tB, &FB});
    }
    if (columns.empty()) return;
    for (int i = na.first; i < na.first + na.count; ++i) {
      const int tA = orderA[static_cast<std::size_t>(i)];
      const PlacedFace& FA = body_[0].face(tA);
      if (!faceMeetsSlab(FA, slabB)) continue;
      for (const auto& [tB, FB] : columns) testFaces(tA, FA, tB, *FB);
    }
  }

  void testFaces(int tA, const PlacedFace& FA, int tB, const PlacedFace& FB) {
    if (!faceBoxesOverlap(FA, FB, margin_)) return;
    int sideA[3], sideB[3];  // corners of each face against the other's plane
    if (planeSides(FB, FA.corner, sideA) != 0 || planeSides(FA, FB.corner, sideB) != 0) return;
    if (sideA[0] == 0 && sideA[1] == 0 && sideA[2] == 0) {
      flagIfCoplanar(tA, FA.corner, tB, FB.corner);
    }
    if (allCertain(sideA) && allCertain(sideB) &&
        certainlyDisjoint(FA.corner, sideA, FB.corner, sideB)) {
      return;
    }
    // Each edge is tested by its owner face only: one decision per (edge, face) pair. An
    // edge with both ends certainly on one side of the plane cannot cross (the exact test
    // would say so too).
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      // The owner runs the edge v0 → v1, so corner k is v0.
      const int e = body_[0].topo.cornerEdge(tA, k);
      if ((sideA[k] == 0 || sideA[k] != sideA[l]) &&
          body_[0].topo.edges()[static_cast<std::size_t>(e)].tri[0] == tA) {
        testEdge(0, e, tB, sideA[k], sideA[l]);
      }
      const int f = body_[1].topo.cornerEdge(tB, k);
      if ((sideB[k] == 0 || sideB[k] != sideB[l]) &&
          body_[1].topo.edges()[static_cast<std::size_t>(f)].tri[0] == tB) {
        testEdge(1, f, tA, sideB[k], sideB[l]);
      }
    }
  }

  /// Faces in one plane (exactly): their shared patch belongs to both boundaries. Same
  /// orientation (flush faces of a body in a pocket): its normals cancel in MODEL.md §1's
  /// n (n_B − n_A = 0); opposite orientation (faces pressed together): a region of zero
  /// thickness. The perturbation keeps such a patch on one body only (or as a sliver on
  /// both), so the flagged faces are left out of n (and slivers out of area and depth), which
  /// makes those independent of the perturbation's direction, as the unperturbed region is.
  void flagIfCoplanar(int tA, const Vector3d* A, int tB, const Vector3d* B) {
    for (int k = 0; k < 3; ++k) {
      if (orient3d(B[0], B[1], B[2], A[k]) != 0) return;
    }
    const bool same = (A[1] - A[0]).cross(A[2] - A[0]).dot((B[1] - B[0]).cross(B[2] - B[0])) > 0.0;
    StampSet SideScratch::*flag =
        same ? &SideScratch::coplanarSame : &SideScratch::coplanarOpposite;
    anyCoplanar_ = true;
    (body_[0].s.*flag).insert(tA);
    (body_[1].s.*flag).insert(tB);
  }

  /// @param s0, s1  the certain sides (±1) of the edge's ends v0, v1 against the face's
  ///   plane, or 0 where the double evaluation was not conclusive
  void testEdge(int side, int e, int face, int s0, int s1) {
    Body& m = body_[side];
    Body& o = body_[1 - side];
    const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(e)];
    const Vector3d& p = m.p(E.v0);
    const Vector3d& q = m.p(E.v1);
    const PlacedFace& F = o.face(face);
    const Vector3d& a = F.corner[0];
    const Vector3d& b = F.corner[1];
    const Vector3d& c = F.corner[2];
    const int s = perturbationSign(side);
    const int sigma = s0 != 0 && s1 == -s0
                          ? perturbedSegmentCrossingStraddling(p, q, a, b, c, s, s0)
                          : perturbedSegmentCrossing(p, q, a, b, c, s, s0, s1);
    if (sigma == 0) return;
    // x where the segment meets the plane: λ = d_p / (d_p − d_q), d = n·(· − a). The exact
    // predicate has decided that it crosses; λ is clamped against rounding.
    const Vector3d& n = F.n;
    const double dp = n.dot(p - a), dq = n.dot(q - a);
    const double denom = dp - dq;
    const double lambda = denom != 0.0 ? std::clamp(dp / denom, 0.0, 1.0) : 0.5;
    w_.crossings.push_back({side, e, face, sigma, lambda, p + lambda * (q - p)});
  }

  // --- 3: boundary pieces -------------------------------------------------------------------

  void emitAlongEdge(int side, const MeshEdge& E, const Vector3d& from, const Vector3d& to) {
    w_.pieces.push_back({side, E.tri[0], from, to});  // the owner runs v0 → v1
    w_.pieces.push_back({side, E.tri[1], to, from});
  }

  void markInside(int side, int v) {
    if (body_[side].s.inside.insert(v)) body_[side].s.insideList.push_back(v);
  }

  /// The parts of each crossing edge inside the other body; seeds the inside flood.
  void walkEdges() {
    auto& order = w_.order;
    order.resize(w_.crossings.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    const auto& X = w_.crossings;
    std::sort(order.begin(), order.end(), [&X](int i, int j) {
      const Crossing& a = X[static_cast<std::size_t>(i)];
      const Crossing& b = X[static_cast<std::size_t>(j)];
      return std::tie(a.side, a.edge, a.lambda) < std::tie(b.side, b.edge, b.lambda);
    });
    for (std::size_t i = 0; i < order.size();) {
      const Crossing& first = X[static_cast<std::size_t>(order[i])];
      std::size_t end = i + 1;
      while (end < order.size() && X[static_cast<std::size_t>(order[end])].side == first.side &&
             X[static_cast<std::size_t>(order[end])].edge == first.edge) {
        ++end;
      }
      const auto begin = order.begin() + static_cast<std::ptrdiff_t>(i);
      bool inside = orderAlongEdge(begin, order.begin() + static_cast<std::ptrdiff_t>(end));
      Body& m = body_[first.side];
      const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(first.edge)];
      m.s.crossingEdge.insert(first.edge);
      m.s.seeded[static_cast<std::size_t>(m.topo.component(E.v0))] = 1;
      if (inside) markInside(first.side, E.v0);
      Vector3d from = m.p(E.v0);
      for (; i < end; ++i) {
        const Crossing& c = X[static_cast<std::size_t>(order[i])];
        if (inside) emitAlongEdge(first.side, E, from, c.x);
        from = c.x;
        inside = c.sigma > 0;
      }
      if (inside) {
        emitAlongEdge(first.side, E, from, m.p(E.v1));
        markInside(first.side, E.v1);
      }
    }
  }

  /// Puts one edge's crossings, sorted by λ, into their order along the perturbed edge and
  /// returns whether the edge's start v0 lies inside the other body. Along an edge the
  /// crossings alternate between entering and leaving. Sorted by λ they do, unless two of
  /// them lie within rounding of each other or at one point (an edge through an edge or a
  /// vertex of the other mesh, flush faces: the ties of the perturbed configuration), where
  /// the sort may have swapped them. Then the start's status comes from the exact parity test
  /// (as perturbed), and a crossing that breaks the alternation trades places with the next
  /// one of the expected direction, which the true sequence puts there.
  bool orderAlongEdge(std::vector<int>::iterator first, std::vector<int>::iterator last) {
    const auto& X = w_.crossings;
    const auto at = [&X](int k) -> const Crossing& { return X[static_cast<std::size_t>(k)]; };
    bool clean = true;
    for (auto it = first + 1; it != last && clean; ++it) {
      clean = at(*it).sigma == -at(*(it - 1)).sigma &&
              at(*it).lambda - at(*(it - 1)).lambda > kLambdaTie;
    }
    if (clean) return at(*first).sigma < 0;
    const Crossing& c = at(*first);
    const MeshEdge& E = body_[c.side].topo.edges()[static_cast<std::size_t>(c.edge)];
    const bool startsInside = contains(1 - c.side, body_[c.side].p(E.v0), perturbationSign(c.side));
    int expected = startsInside ? -1 : +1;
    for (auto it = first; it != last; ++it, expected = -expected) {
      if (at(*it).sigma == expected) continue;
      const auto next = std::find_if(it + 1, last, [&](int k) { return at(k).sigma == expected; });
      if (next == last) {
        throw std::logic_error(describeFailure("an edge's crossings do not alternate"));
      }
      std::rotate(it, next, next + 1);
    }
    return startsInside;
  }

  /// Pairs the crossings into the segments t_A ∩ t_B. With d = n_A × n_B, the region
  /// t_A ∩ B lies to the left of d seen from n_A, and t_B ∩ A to the left of −d. An edge of
  /// t_A that enters B ends the segment (t_A's boundary goes on along the edge, into B); an
  /// edge of t_B that enters A starts it (the same rule seen from t_B, whose segment runs −d).
  void buildSegments() {
    for (std::size_t i = 0; i < w_.crossings.size(); ++i) {
      const Crossing& c = w_.crossings[i];
      const MeshEdge& E = body_[c.side].topo.edges()[static_cast<std::size_t>(c.edge)];
      for (int j = 0; j < 2; ++j) {
        const bool enters = (j == 0 ? c.sigma : -c.sigma) > 0;  // along the face's own run
        const auto t = static_cast<std::uint64_t>(E.tri[j]);
        const auto f = static_cast<std::uint64_t>(c.face);
        if (c.side == 0) {
          w_.endpoints.push_back({(t << 32) | f, static_cast<int>(i), !enters});
        } else {
          w_.endpoints.push_back({(f << 32) | t, static_cast<int>(i), enters});
        }
      }
    }
    std::sort(w_.endpoints.begin(), w_.endpoints.end(),
              [](const Endpoint& a, const Endpoint& b) { return a.key < b.key; });
    for (std::size_t i = 0; i < w_.endpoints.size(); i += 2) {
      const Endpoint& e0 = w_.endpoints[i];
      if (i + 1 >= w_.endpoints.size() || w_.endpoints[i + 1].key != e0.key ||
          w_.endpoints[i + 1].start == e0.start ||
          (i + 2 < w_.endpoints.size() && w_.endpoints[i + 2].key == e0.key)) {
        throw std::logic_error(describeFailure("a face pair's crossings do not form one segment"));
      }
      const Endpoint& e1 = w_.endpoints[i + 1];
      const Vector3d& xs =
          w_.crossings[static_cast<std::size_t>(e0.start ? e0.crossing : e1.crossing)].x;
      const Vector3d& xe =
          w_.crossings[static_cast<std::size_t>(e0.start ? e1.crossing : e0.crossing)].x;
      const int tA = static_cast<int>(e0.key >> 32);
      const int tB = static_cast<int>(e0.key & 0xffffffffu);
      w_.pieces.push_back({0, tA, xs, xe});
      w_.pieces.push_back({1, tB, xe, xs});
      if (body_[0].s.cut.insert(tA)) body_[0].s.cutList.push_back(tA);
      if (body_[1].s.cut.insert(tB)) body_[1].s.cutList.push_back(tB);
    }
  }

  /// Inside status spreads over the edges that cross nothing.
  void floodInside(int side) {
    Body& m = body_[side];
    auto& stack = w_.stack;
    stack.assign(m.s.insideList.begin(), m.s.insideList.end());
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (const int* e = m.topo.edgesBegin(v); e != m.topo.edgesEnd(v); ++e) {
        if (m.s.crossingEdge.contains(*e)) continue;
        const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(*e)];
        const int w = E.v0 == v ? E.v1 : E.v0;
        if (m.s.inside.insert(w)) {
          m.s.insideList.push_back(w);
          stack.push_back(w);
        }
      }
    }
  }

  /// A connected part with no crossing edge is wholly inside or wholly outside (it may
  /// still be pierced by edges of the other mesh); one exact ray-parity test decides.
  void classifyUnseededComponents(int side) {
    Body& m = body_[side];
    Body& o = body_[1 - side];
    const auto otherBox = placedBox(o.X_WM, o.bvh.root().center, o.bvh.root().halfExtent);
    const auto& comps = m.topo.components();
    for (std::size_t c = 0; c < comps.size(); ++c) {
      if (m.s.seeded[c]) continue;
      const geometry::Aabb& bb = comps[c].bounds;
      const auto box = placedBox(m.X_WM, 0.5 * (bb.min + bb.max), 0.5 * bb.size());
      if (!boxesOverlap(box.first, box.second, otherBox.first, otherBox.second, margin_)) {
        continue;
      }
      if (!contains(1 - side, m.p(comps[c].vertices.front()), perturbationSign(side))) continue;
      for (const int v : comps[c].vertices) markInside(side, v);
    }
  }

  /// Is p_W (a point of the other mesh, moved by s·τ) inside mesh `side`? Parity of the
  /// crossings of a segment from p to beyond the mesh's box, through its tree.
  bool contains(int side, const Vector3d& p_W, int s) {
    Body& m = body_[side];
    const BvhNode& root = m.bvh.root();
    const Isometry3d X_MW = m.X_WM.inverse();
    const Vector3d p_M = X_MW * p_W;
    if (((p_M - root.center).cwiseAbs().array() > root.halfExtent.array() + margin_).any()) {
      return false;
    }
    // A fixed direction that no mesh built on axes or simple angles lies along.
    const Vector3d dir_M = Vector3d(0.5773, 0.2113, 0.7887).normalized();
    const double length = 2.0 * ((p_M - root.center).norm() + root.halfExtent.norm());
    const Vector3d f_M = p_M + length * dir_M;
    const Vector3d f_W = m.X_WM * f_M;
    const Vector3d grow = Vector3d::Constant(margin_);
    int crossings = 0;
    auto& stack = w_.stack;
    stack.assign(1, 0);
    while (!stack.empty()) {
      const BvhNode& n = m.bvh.nodes()[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (!segmentMeetsBox(p_M, f_M, n.center, n.halfExtent + grow)) continue;
      if (!n.isLeaf()) {
        stack.push_back(n.left);
        stack.push_back(n.right);
        continue;
      }
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = m.bvh.order()[static_cast<std::size_t>(i)];
        if (perturbedSegmentCrossing(p_W, f_W, m.corner(f, 0), m.corner(f, 1), m.corner(f, 2), s) !=
            0) {
          ++crossings;
        }
      }
    }
    return crossings % 2 == 1;
  }

  /// The edges of a cut face that cross nothing and lie inside bound its region whole.
  void addWholeEdgesOfCutFaces(int side) {
    Body& m = body_[side];
    for (const int t : m.s.cutList) {
      for (int k = 0; k < 3; ++k) {
        const int e = m.topo.cornerEdge(t, k);
        if (m.s.crossingEdge.contains(e) || !m.s.inside.contains(m.mesh().triangles(t, k))) {
          continue;
        }
        w_.pieces.push_back({side, t, m.corner(t, k), m.corner(t, (k + 1) % 3)});
      }
    }
  }

  /// Faces that are not cut and have an inside vertex are wholly inside.
  void collectWholeFaces(int side) {
    Body& m = body_[side];
    for (const int v : m.s.insideList) {
      for (const int* f = m.topo.facesBegin(v); f != m.topo.facesEnd(v); ++f) {
        if (m.mesh().triangles(*f, 0) == v && !m.s.cut.contains(*f))
          w_.wholes.push_back({side, *f});
      }
    }
  }

  // --- 4: integration -----------------------------------------------------------------------

  /// What a face's pieces add to n, and to area and depth (flagIfCoplanar).
  bool inNormal(int side, int face) const {
    return !anyCoplanar_ || (!body_[side].s.coplanarSame.contains(face) &&
                             !body_[side].s.coplanarOpposite.contains(face));
  }
  bool inArea(int side, int face) const {
    return !anyCoplanar_ || !body_[side].s.coplanarOpposite.contains(face);
  }

  ContactVolume integrate() {
    const ContactVolume none{.method = Method::kFast};
    Vector3d o;
    if (!w_.crossings.empty()) {
      o = w_.crossings.front().x;
    } else if (!w_.wholes.empty()) {
      o = body_[w_.wholes.front().side].corner(w_.wholes.front().face, 0);
    } else {
      return none;
    }
    // Every piece and whole face as a directed boundary patch: its face's unit normal and
    // its signed area (area and depth are evaluated once n is known).
    auto& patches = w_.patches;
    patches.clear();
    geometry::TetrahedronSum fan;
    double termSum6 = 0.0;           // 6 Σ |fan term volumes|
    double areaSum = 0.0;            // Σ |patch areas|
    Vector3d scale3 = o.cwiseAbs();  // largest |coordinate| of the patches' points, per axis
    Vector3d nSum = Vector3d::Zero();  // ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA (MODEL.md §1)
    const auto add = [&](int side, int face, const Vector3d& c, const Vector3d& p,
                         const Vector3d& q, const Vector3d& nrm, double area) {
      termSum6 += std::abs(fan.add(c - o, p - o, q - o));
      areaSum += std::abs(area);
      scale3 = scale3.cwiseMax(p.cwiseAbs()).cwiseMax(q.cwiseAbs());
      if (inNormal(side, face)) nSum += (side == 1 ? area : -area) * nrm;
      if (inArea(side, face)) patches.push_back({nrm, area, p, q});
    };
    // Every piece lies on a cut face: their feet first, in one loop whose square roots and
    // divisions do not wait on each other.
    for (int side = 0; side < 2; ++side) {
      for (const int f : body_[side].s.cutList) body_[side].foot(f, o);
    }
    for (const Piece& pc : w_.pieces) {
      const FaceFoot& F = body_[pc.side].foot(pc.face, o);
      const Vector3d& c = F.foot;
      add(pc.side, pc.face, c, pc.p, pc.q, F.normal,
          0.5 * F.normal.dot((pc.p - c).cross(pc.q - c)));
    }
    for (const WholeFace& wf : w_.wholes) {
      Body& m = body_[wf.side];
      const Vector3d &a = m.corner(wf.face, 0), &b = m.corner(wf.face, 1),
                     &c = m.corner(wf.face, 2);
      const Vector3d N = (b - a).cross(c - a);
      const double twiceArea = N.norm();
      const Vector3d nrm = N * (1.0 / twiceArea);
      add(wf.side, wf.face, a, b, c, nrm, 0.5 * twiceArea);
      if (inArea(wf.side, wf.face)) patches.push_back({nrm, 0.0, a, a});  // for depth
    }
    const geometry::Moments M = fan.moments();
    const double scale = scale3.maxCoeff(), termSum = termSum6 / 6.0;
    if (!(M.m0 > kVolumeNoise * kEps * (scale * areaSum + termSum))) return none;
    const Vector3d c_o = M.m1 / M.m0;
    const Vector3d n = contactNormal(nSum, areaSum, o + c_o);

    double area2 = 0.0, lo = INFINITY, hi = -INFINITY;
    for (const Patch& pt : patches) {
      area2 += std::abs(n.dot(pt.normal)) * pt.area;
      for (const Vector3d* p : {&pt.p, &pt.q}) {
        lo = std::min(lo, n.dot(*p - o));
        hi = std::max(hi, n.dot(*p - o));
      }
    }
    return contactFromMoments(M, o, n, 0.5 * area2, hi - lo, Method::kFast);
  }

  /// n from the area vectors; when they cancel (the region is bounded by one body's surface
  /// alone: a body wholly inside the other, or only flush faces besides), MODEL.md §1 leaves
  /// n undefined, and it is taken from B's box centre towards p_c (B's z axis if they meet).
  Vector3d contactNormal(const Vector3d& nSum, double areaSum, const Vector3d& p_c) const {
    if (nSum.norm() > kNormalNoise * areaSum) return nSum.normalized();
    const Vector3d d = p_c - body_[1].X_WM * body_[1].bvh.root().center;
    if (d.norm() > 0.0) return d.normalized();
    return body_[1].X_WM.linear().col(2);
  }

  Body body_[2];
  Scratch& w_;
  double margin_ = 0.0;
  bool anyCoplanar_ = false;  ///< flagIfCoplanar has flagged a face pair in this query
};

}  // namespace

bool MeshMeshCache::covers(const MeshBvh& treeA, const MeshBvh& treeB,
                           const Isometry3d& X_BA_now) const {
  if (a != &treeA || b != &treeB) return false;
  // Every point of A's root box is c + r with |r| ≤ ρ; it moved (in B's frame) by
  // |X_now c − X c + (R_now − R) r| ≤ |X_now c − X c| + ‖R_now − R‖_F ρ.
  const BvhNode& root = treeA.root();
  const double moved = (X_BA_now * root.center - X_BA * root.center).norm() +
                       (X_BA_now.linear() - X_BA.linear()).norm() * root.halfExtent.norm();
  return moved <= reach;
}

ContactVolume meshMeshContact(const MeshBvh& a, const MeshTopology& topoA, const Isometry3d& X_WA,
                              const MeshBvh& b, const MeshTopology& topoB, const Isometry3d& X_WB,
                              MeshMeshCache* cache) {
  thread_local Scratch scratch;
  Intersector query(Body{a, topoA, X_WA, scratch.sides[0]}, Body{b, topoB, X_WB, scratch.sides[1]},
                    scratch);
  return query.run(cache);
}

ContactVolume fastContact(const geometry::Shape& a, const Isometry3d& X_WA,
                          const geometry::Shape& b, const Isometry3d& X_WB, MeshMeshCache* cache) {
  assert(std::holds_alternative<geometry::Mesh>(a) && std::holds_alternative<geometry::Mesh>(b));
  const auto& meshA = std::get<geometry::Mesh>(a).mesh;
  const auto& meshB = std::get<geometry::Mesh>(b).mesh;
  return meshMeshContact(*bvhOf(meshA), *topologyOf(meshA), X_WA, *bvhOf(meshB), *topologyOf(meshB),
                         X_WB, cache);
}

}  // namespace vcontact::volume
