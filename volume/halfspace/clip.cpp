#include "volume/halfspace/clip.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "volume/halfspace/clip_internal.hpp"
#include "volume/kernels/bvh_cache.hpp"
#include "volume/kernels/mesh_convexity.hpp"
#include "volume/kernels/mesh_topology_cache.hpp"
#include "volume/kernels/stamp_set.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;
using geometry::MeshTopology;
using internal::Apex;
using internal::CapLoop;
using internal::CapLoops;
using internal::capSegment;
using internal::clipFace;
using internal::clipPatches;
using internal::clipPlacedTriangle;
using internal::FanSum;
using internal::PlacedVertices;
using internal::Placement;
using internal::toHalfspaceFrame;
using internal::traceCapLoops;

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

  /// The connected components of the last run()'s clip (PatchClip, halfspace/clip_patches.cpp),
  /// or none when it is one (the merged clip is then the patch). @pre run() found contact
  std::vector<ClippedMoments> patches() const {
    return clipPatches(mesh_, *topo_, placement_, *placed_, *straddling_, bvh_.order());
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
