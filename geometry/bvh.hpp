#pragma once
// A static bounding-volume hierarchy of axis-aligned boxes over the triangles of a mesh, in
// the mesh's body frame M. Besides its box, every node caches what the exact volume queries
// need to treat a whole subtree in O(1):
//   - FanIntegrals of its triangles about the box centre (fan moments for any apex, see
//     fan_integrals.hpp);
//   - a cone bounding its face normals (axis, sin of the half-angle), so a query can tell
//     when every face of the subtree faces one way relative to a plane.
// Built top-down by the binned surface-area heuristic over the triangle centroids (bvh.cpp).

#include <Eigen/Core>
#include <vector>

#include "geometry/fan_integrals.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

struct BvhNode {
  Eigen::Vector3d center;           ///< box centre in M, the reference r of `integrals`, m
  Eigen::Vector3d halfExtent;       ///< box half-sizes, m
  FanIntegrals integrals;           ///< of the node's triangles about `center`
  Eigen::Vector3d normalAxis;       ///< unit axis of the normal cone
  double normalSinHalfAngle = 2.0;  ///< sin of the cone half-angle; > 1: wider than π/2
  /// A slab bound aligned with normalAxis, tight for a nearly flat patch in any orientation
  /// (where the axis-aligned box is not): every vertex p has s = (p − center)·normalAxis in
  /// [axialLo, axialHi] and lies within radialExtent of the axis line through center.
  double axialLo = 0.0, axialHi = 0.0, radialExtent = 0.0;
  int first = 0;  ///< first index into MeshBvh::order()
  int count = 0;  ///< number of triangles
  int left = -1;  ///< child nodes, −1 for a leaf (right = left + 1 is not assumed)
  int right = -1;

  bool isLeaf() const { return left < 0; }
};

class MeshBvh {
 public:
  /// Triangles per leaf at most, by default. 8 rather than 4 since the fast mesh–mesh
  /// method rejects a leaf's faces against the other leaf's slab before its face pairs
  /// (sphere_pair_10k 103 → 97 µs, 100k 680 → 615 µs; the half-space clip and the CAD
  /// drop unchanged or slightly faster), with half the nodes.
  static constexpr int kDefaultLeafSize = 8;

  /// Builds the hierarchy; keeps a copy of the mesh. @pre the mesh has at least one triangle.
  explicit MeshBvh(TriangleMesh mesh, int maxLeafSize = kDefaultLeafSize);

  const TriangleMesh& mesh() const { return mesh_; }
  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const BvhNode& root() const { return nodes_.front(); }
  /// Triangle indices, permuted so that each node's triangles are contiguous.
  const std::vector<int>& order() const { return order_; }

 private:
  int build(int first, int count, int maxLeafSize);
  void fillNode(BvhNode& node) const;

  TriangleMesh mesh_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroids_;
  std::vector<BvhNode> nodes_;
};

/// Calls `visit(f)` for each triangle f in the leaves whose boxes overlap `box` (in M), until
/// it returns true; returns whether it did. The triangles' own boxes are the caller's to test.
template <class Visit>
bool visitTrianglesNear(const MeshBvh& tree, const Aabb& box, Visit&& visit) {
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const BvhNode& node = tree.nodes()[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (((node.center - node.halfExtent).array() > box.max.array()).any() ||
        ((node.center + node.halfExtent).array() < box.min.array()).any())
      continue;
    if (!node.isLeaf()) {
      stack.push_back(node.left);
      stack.push_back(node.right);
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i)
      if (visit(tree.order()[static_cast<std::size_t>(i)])) return true;
  }
  return false;
}

}  // namespace vcontact::geometry
