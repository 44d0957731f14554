#include "geometry/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace vcontact::geometry {
namespace {

Eigen::Vector3d unitNormal(const TriangleMesh& m, int f) {
  const Eigen::Vector3d a = m.corner(f, 0);
  return (m.corner(f, 1) - a).cross(m.corner(f, 2) - a).normalized();
}

}  // namespace

MeshBvh::MeshBvh(TriangleMesh mesh, int maxLeafSize) : mesh_(std::move(mesh)) {
  const int n = static_cast<int>(mesh_.triangleCount());
  if (n == 0 || maxLeafSize < 1) throw std::invalid_argument("MeshBvh: empty mesh or leaf size");
  order_.resize(static_cast<std::size_t>(n));
  std::iota(order_.begin(), order_.end(), 0);
  centroids_.resize(order_.size());
  for (int f = 0; f < n; ++f) {
    centroids_[f] = (mesh_.corner(f, 0) + mesh_.corner(f, 1) + mesh_.corner(f, 2)) / 3.0;
  }
  nodes_.reserve(static_cast<std::size_t>(2 * n / maxLeafSize + 1));
  build(0, n, maxLeafSize);
  centroids_.clear();
  centroids_.shrink_to_fit();
}

int MeshBvh::build(int first, int count, int maxLeafSize) {
  const int index = static_cast<int>(nodes_.size());
  BvhNode node;
  node.first = first;
  node.count = count;
  fillNode(node);
  nodes_.push_back(node);
  if (count <= maxLeafSize) return index;
  Eigen::Vector3d lo = centroids_[order_[first]], hi = lo;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(centroids_[order_[i]]);
    hi = hi.cwiseMax(centroids_[order_[i]]);
  }
  Eigen::Index axis;
  (hi - lo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count,
                   [&](int a, int b) { return centroids_[a][axis] < centroids_[b][axis]; });
  const int left = build(first, half, maxLeafSize);
  const int right = build(first + half, count - half, maxLeafSize);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void MeshBvh::fillNode(BvhNode& node) const {
  Eigen::Vector3d lo = mesh_.corner(order_[node.first], 0), hi = lo;
  Eigen::Vector3d normalSum = Eigen::Vector3d::Zero();
  for (int i = node.first; i < node.first + node.count; ++i) {
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(mesh_.corner(order_[i], k));
      hi = hi.cwiseMax(mesh_.corner(order_[i], k));
    }
    normalSum += unitNormal(mesh_, order_[i]);
  }
  node.center = 0.5 * (lo + hi);
  node.halfExtent = 0.5 * (hi - lo);
  node.normalAxis =
      normalSum.norm() > 0.0 ? Eigen::Vector3d(normalSum.normalized()) : Eigen::Vector3d::UnitZ();
  double minCos = 1.0;
  for (int i = node.first; i < node.first + node.count; ++i) {
    const int f = order_[i];
    minCos = std::min(minCos, node.normalAxis.dot(unitNormal(mesh_, f)));
    node.integrals +=
        triangleFanIntegrals(mesh_.corner(f, 0) - node.center, mesh_.corner(f, 1) - node.center,
                             mesh_.corner(f, 2) - node.center);
  }
  node.axialLo = INFINITY;
  node.axialHi = -INFINITY;
  for (int i = node.first; i < node.first + node.count; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d r = mesh_.corner(order_[i], k) - node.center;
      const double s = r.dot(node.normalAxis);
      node.axialLo = std::min(node.axialLo, s);
      node.axialHi = std::max(node.axialHi, s);
      node.radialExtent = std::max(node.radialExtent, (r - s * node.normalAxis).norm());
    }
  }
  // Beyond a half-angle of π/2 the cone test is never conclusive; > 1 says so.
  node.normalSinHalfAngle = minCos > 0.0 ? std::sqrt(1.0 - minCos * minCos) : 2.0;
}

}  // namespace vcontact::geometry
