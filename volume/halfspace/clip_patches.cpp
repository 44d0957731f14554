// The clip of a mesh by a half-space split into its connected components (PatchClip): face
// labels flooded below the plane, joined through the cap loops by a union-find (LabelUnion),
// each component clipped about its own apex. Used by meshHalfspacePatches (halfspace/clip.cpp).

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "volume/halfspace/clip_internal.hpp"
#include "volume/kernels/stamp_set.hpp"

namespace vcontact::volume::internal {
namespace {

using geometry::BvhNode;

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

}  // namespace

std::vector<ClippedMoments> clipPatches(const geometry::TriangleMesh& mesh,
                                        const MeshTopology& topo, const Placement& X_HM,
                                        PlacedVertices& placed,
                                        const std::vector<const BvhNode*>& straddling,
                                        const std::vector<int>& order) {
  return PatchClip(mesh, topo, X_HM, placed).run(straddling, order);
}

}  // namespace vcontact::volume::internal
