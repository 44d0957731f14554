#include "volume/fast/surface_integration.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>
#include <vector>

#include "geometry/moments.hpp"
#include "volume/fast/intersector.hpp"
#include "volume/kernels/bvh_cache.hpp"
#include "volume/kernels/exact_predicates.hpp"
#include "volume/kernels/mesh_topology_cache.hpp"

namespace vcontact::volume {
namespace internal {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Boxes are grown by this fraction of the largest coordinate in play. Placing a vertex in W
/// or in the other body's frame rounds it by a few ε of that size; 1e-12 (≈ 4500 ε) covers
/// it many times over, so the broad phase never drops a pair the exact predicates would see.
constexpr double kBoxMargin = 1e-12;
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

}  // namespace

Intersector::Intersector(Body a, Body b, Scratch& scratch) : body_{a, b}, scratch_(scratch) {
  for (int side = 0; side < 2; ++side) {
    Body& m = body_[side];
    const auto nv = static_cast<std::size_t>(m.mesh().vertexCount());
    const auto nf = static_cast<std::size_t>(m.mesh().triangleCount());
    m.scratch.p_W.reset(nv);
    m.scratch.faces.reset(nf);
    m.scratch.feet.reset(nf);
    m.scratch.inside.reset(nv);
    m.scratch.insideList.clear();
    m.scratch.vertexNode.reset(nv);
    m.scratch.cut.reset(nf);
    m.scratch.cutList.clear();
    m.scratch.crossingEdge.reset(m.topo.edges().size());
    m.scratch.coplanarSame.reset(nf);
    m.scratch.coplanarOpposite.reset(nf);
    m.scratch.seeded.assign(m.topo.components().size(), 0);
  }
  scratch_.crossings.clear();
  scratch_.endpoints.clear();
  scratch_.pieces.clear();
  scratch_.wholes.clear();
  const auto extent = [](const Body& m) {
    const BvhNode& r = m.bvh.root();
    return m.X_WM.translation().norm() + r.center.norm() + r.halfExtent.norm();
  };
  margin_ = kBoxMargin * (extent(body_[0]) + extent(body_[1]));
}

ContactPatches Intersector::run(MeshMeshCache* cache, bool deepest) {
  deepest_ = deepest;
  findCrossings(cache);
  walkEdges();
  buildSegments();
  for (int side = 0; side < 2; ++side) {
    floodInside(side);
    classifyUnseededComponents(side);
    addWholeEdgesOfCutFaces(side);
    collectWholeFaces(side);
  }
  ContactPatches out = singlePatch(integrate());
  if (!out.inContact() || (groupPieces() <= 1 && !wholeShellInside_)) return out;
  joinWholeFaces();
  if (joinHolesWithinFaces() == 1) return out;
  out.patches = integratePatches();
  sortPatches(out.patches);
  return out;
}

std::string Intersector::describeFailure(const std::string& what) const {
  std::ostringstream os;
  os.precision(17);
  os << "fast mesh-mesh: " << what << "; X_WA =\n"
     << body_[0].X_WM.matrix() << "\nX_WB =\n"
     << body_[1].X_WM.matrix();
  return os.str();
}

void Intersector::findCrossings(MeshMeshCache* cache) {
  const MeshBvh& treeA = body_[0].bvh;
  const MeshBvh& treeB = body_[1].bvh;
  TreePairDescent descent(treeA, treeB, body_[1].X_WM.inverse() * body_[0].X_WM, margin_,
                          scratch_.descent);
  descent.forEachLeafPair(cache, [&](int ia, int ib) {
    testLeaves(treeA.nodes()[static_cast<std::size_t>(ia)],
               treeB.nodes()[static_cast<std::size_t>(ib)]);
  });
}

Intersector::PlacedSlab Intersector::placedSlab(const Body& m, const BvhNode& n) const {
  return {m.X_WM * n.center, m.X_WM.linear() * n.normalAxis, n.axialLo - margin_,
          n.axialHi + margin_};
}

/// Does face F reach the axial range of slab S? Its axial coordinate is linear over the
/// face, so the corners bound it; a face wholly beyond the range meets none of the slab's
/// faces (the margin exceeds the rounding of both placements many times over).
bool Intersector::faceMeetsSlab(const PlacedFace& F, const PlacedSlab& S) {
  const double s0 = (F.corner[0] - S.center).dot(S.axis);
  const double s1 = (F.corner[1] - S.center).dot(S.axis);
  const double s2 = (F.corner[2] - S.center).dot(S.axis);
  return std::max({s0, s1, s2}) >= S.lo && std::min({s0, s1, s2}) <= S.hi;
}

/// Every face pair of two leaves whose boxes overlap; a face that misses the other leaf's
/// slab skips its row (column) at once. In shallow contact most faces of one leaf lie just
/// inside the other body, beyond the thin slab of a nearly flat leaf of the other mesh.
void Intersector::testLeaves(const BvhNode& na, const BvhNode& nb) {
  const auto& orderA = body_[0].bvh.order();
  const auto& orderB = body_[1].bvh.order();
  const PlacedSlab slabA = placedSlab(body_[0], na);
  const PlacedSlab slabB = placedSlab(body_[1], nb);
  auto& columns = scratch_.columns;
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

void Intersector::testFaces(int tA, const PlacedFace& FA, int tB, const PlacedFace& FB) {
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
void Intersector::flagIfCoplanar(int tA, const Vector3d* A, int tB, const Vector3d* B) {
  for (int k = 0; k < 3; ++k) {
    if (orient3d(B[0], B[1], B[2], A[k]) != 0) return;
  }
  const bool same = (A[1] - A[0]).cross(A[2] - A[0]).dot((B[1] - B[0]).cross(B[2] - B[0])) > 0.0;
  StampSet SideScratch::*flag = same ? &SideScratch::coplanarSame : &SideScratch::coplanarOpposite;
  anyCoplanar_ = true;
  (body_[0].scratch.*flag).insert(tA);
  (body_[1].scratch.*flag).insert(tB);
}

/// @param s0, s1  the certain sides (±1) of the edge's ends v0, v1 against the face's
///   plane, or 0 where the double evaluation was not conclusive
void Intersector::testEdge(int side, int e, int face, int s0, int s1) {
  Body& m = body_[side];
  Body& o = body_[1 - side];
  const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(e)];
  const Vector3d& p = m.placedVertex(E.v0);
  const Vector3d& q = m.placedVertex(E.v1);
  const PlacedFace& F = o.face(face);
  const Vector3d& a = F.corner[0];
  const Vector3d& b = F.corner[1];
  const Vector3d& c = F.corner[2];
  const int sign = perturbationSign(side);
  const int sigma = s0 != 0 && s1 == -s0
                        ? perturbedSegmentCrossingStraddling(p, q, a, b, c, sign, s0)
                        : perturbedSegmentCrossing(p, q, a, b, c, sign, s0, s1);
  if (sigma == 0) return;
  // x where the segment meets the plane: λ = d_p / (d_p − d_q), d = n·(· − a). The exact
  // predicate has decided that it crosses; λ is clamped against rounding.
  const Vector3d& n = F.n;
  const double dp = n.dot(p - a), dq = n.dot(q - a);
  const double denom = dp - dq;
  const double lambda = denom != 0.0 ? std::clamp(dp / denom, 0.0, 1.0) : 0.5;
  scratch_.crossings.push_back({side, e, face, sigma, lambda, p + lambda * (q - p)});
}

/// What a face's pieces add to n, and to area and depth (flagIfCoplanar).
bool Intersector::inNormal(int side, int face) const {
  return !anyCoplanar_ || (!body_[side].scratch.coplanarSame.contains(face) &&
                           !body_[side].scratch.coplanarOpposite.contains(face));
}

bool Intersector::inArea(int side, int face) const {
  return !anyCoplanar_ || !body_[side].scratch.coplanarOpposite.contains(face);
}

ContactVolume Intersector::integrate() {
  Vector3d o;
  if (!scratch_.crossings.empty()) {
    o = scratch_.crossings.front().x;
  } else if (!scratch_.wholes.empty()) {
    o = body_[scratch_.wholes.front().side].corner(scratch_.wholes.front().face, 0);
  } else {
    return ContactVolume{.method = Method::kFast};
  }
  // Every piece and whole face as a directed boundary patch: its face's unit normal and
  // its signed area (area and depth are evaluated once n is known).
  auto& patches = scratch_.patches;
  patches.clear();
  RegionSum sum(o);
  const auto add = [&](int side, int face, const Vector3d& c, const Vector3d& p, const Vector3d& q,
                       const Vector3d& nrm, double area) {
    sum.add(side, face, c, p, q, nrm, area, inNormal(side, face), inArea(side, face), patches);
  };
  // Every piece lies on a cut face: their feet first, in one loop whose square roots and
  // divisions do not wait on each other.
  for (int side = 0; side < 2; ++side) {
    for (const int f : body_[side].scratch.cutList) body_[side].foot(f, o);
  }
  for (const Piece& pc : scratch_.pieces) {
    const FaceFoot& F = body_[pc.side].foot(pc.face, o);
    const Vector3d& c = F.foot;
    add(pc.side, pc.face, c, pc.p, pc.q, F.n_W, 0.5 * F.n_W.dot((pc.p - c).cross(pc.q - c)));
  }
  for (const WholeFace& wf : scratch_.wholes) {
    Body& m = body_[wf.side];
    const Vector3d &a = m.corner(wf.face, 0), &b = m.corner(wf.face, 1), &c = m.corner(wf.face, 2);
    const Vector3d N = (b - a).cross(c - a);
    const double twiceArea = N.norm();
    const Vector3d nrm = N * (1.0 / twiceArea);
    add(wf.side, wf.face, a, b, c, nrm, 0.5 * twiceArea);
    if (inArea(wf.side, wf.face)) addOtherEdges(wf, nrm, patches);
  }
  return contactOf(sum, patches);
}

ContactVolume Intersector::contactOf(const RegionSum& sum, const std::vector<Patch>& parts) const {
  const geometry::Moments M = sum.fan.moments();
  const double scale = sum.scale3.maxCoeff(), termSum = sum.termSum6 / 6.0;
  if (!(M.m0 > kVolumeNoise * kEps * (scale * sum.areaSum + termSum))) {
    return ContactVolume{.method = Method::kFast};
  }
  const Vector3d& o = sum.o;
  const Vector3d c_o = M.m1 / M.m0;
  const Vector3d n = contactNormal(sum.nSum, sum.areaSum, o + c_o);

  double area2 = 0.0;
  for (const Patch& pt : parts) area2 += std::abs(n.dot(pt.n_W)) * pt.area;
  double d = std::numeric_limits<double>::quiet_NaN();
  if (deepest_) {
    ColumnDepth& depth = scratch_.depth;
    depth.clear();
    for (const Patch& pt : parts) depth.add(pt.face, pt.n_W, pt.p, pt.q);
    d = depth.deepest(n, o, scale);
  }
  return contactFromMoments(M, o, n, 0.5 * area2, d, Method::kFast);
}

/// A whole face's edges a → b and c → a for the depth pass (RegionSum::add has filed b → c).
void Intersector::addOtherEdges(const WholeFace& wf, const Vector3d& nrm,
                                std::vector<Patch>& parts) {
  Body& m = body_[wf.side];
  const Vector3d &a = m.corner(wf.face, 0), &b = m.corner(wf.face, 1), &c = m.corner(wf.face, 2);
  parts.push_back({faceKey(wf.side, wf.face), nrm, 0.0, a, b});
  parts.push_back({faceKey(wf.side, wf.face), nrm, 0.0, c, a});
}

/// n from the area vectors; when they cancel (the region is bounded by one body's surface
/// alone: a body wholly inside the other, or only flush faces besides), MODEL.md §1 leaves
/// n undefined, and it is taken from B's box centre towards p_c (B's z axis if they meet).
Vector3d Intersector::contactNormal(const Vector3d& nSum, double areaSum,
                                    const Vector3d& p_c) const {
  if (nSum.norm() > kNormalNoise * areaSum) return nSum.normalized();
  const Vector3d d = p_c - body_[1].X_WM * body_[1].bvh.root().center;
  if (d.norm() > 0.0) return d.normalized();
  return body_[1].X_WM.linear().col(2);
}

Scratch& threadScratch() {
  thread_local Scratch scratch;
  return scratch;
}

const ColumnDepth& lastDepthPass() { return threadScratch().depth; }

}  // namespace internal

using internal::Isometry3d;
using internal::MeshBvh;
using internal::MeshTopology;

ContactPatches meshMeshContact(const MeshBvh& a, const MeshTopology& topoA, const Isometry3d& X_WA,
                               const MeshBvh& b, const MeshTopology& topoB, const Isometry3d& X_WB,
                               MeshMeshCache* cache, bool deepest) {
  // A closed mesh has every edge in two faces: 2 E = 3 F (an open one has more edges).
  assert(2 * topoA.edges().size() == 3 * std::size_t(a.mesh().triangleCount()));
  assert(2 * topoB.edges().size() == 3 * std::size_t(b.mesh().triangleCount()));
  internal::Scratch& scratch = internal::threadScratch();
  internal::Intersector query(internal::Body{a, topoA, X_WA, scratch.sides[0]},
                              internal::Body{b, topoB, X_WB, scratch.sides[1]}, scratch);
  return query.run(cache, deepest);
}

ContactPatches fastContact(const geometry::Shape& a, const Isometry3d& X_WA,
                           const geometry::Shape& b, const Isometry3d& X_WB, MeshMeshCache* cache,
                           bool deepest) {
  assert(std::holds_alternative<geometry::Mesh>(a) && std::holds_alternative<geometry::Mesh>(b));
  const auto& meshA = std::get<geometry::Mesh>(a).mesh;
  const auto& meshB = std::get<geometry::Mesh>(b).mesh;
  return meshMeshContact(*bvhOf(meshA), *topologyOf(meshA), X_WA, *bvhOf(meshB), *topologyOf(meshB),
                         X_WB, cache, deepest);
}

}  // namespace vcontact::volume
