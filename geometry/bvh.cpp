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

// Bins per axis of the surface-area heuristic; 16 is within a few per cent of the exact
// sweep in the SAH literature (Wald 2007) and keeps the build O(n log n).
constexpr int kSahBins = 16;

struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-INFINITY);

  void grow(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  /// Half the surface area; 0 for an empty box.
  double halfArea() const {
    if (!(hi.x() >= lo.x())) return 0.0;
    const Eigen::Vector3d d = hi - lo;
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
};

struct Bin {
  Box box;  ///< of the triangles (not the centroids) in the bin
  int count = 0;
};

/// Splits order[first, first + count) in two and returns the size of the first part.
///
/// Binned surface-area heuristic (Wald, "On fast construction of SAH-based bounding volume
/// hierarchies", 2007): the centroids are binned along each axis, and of the planes between
/// bins the one minimising area(left box)·n_left + area(right box)·n_right is taken, the
/// expected number of triangle tests of a query that meets the node. CAD meshes mix large
/// flat triangles with finely faceted pins and fillets; the median split puts both in one
/// node, whose box then spans a face and a feature at once and overlaps everything near
/// either. Falls back to the median along the widest centroid axis when no plane separates
/// the centroids (all in one bin).
int splitTriangles(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& centroids,
                   std::vector<int>& order, int first, int count) {
  const auto begin = order.begin() + first;
  const auto end = begin + count;
  Box centroidBox;
  for (auto it = begin; it != end; ++it) centroidBox.grow(centroids[static_cast<std::size_t>(*it)]);
  const Eigen::Vector3d extent = centroidBox.hi - centroidBox.lo;
  const auto binOf = [&](int f, int axis) {
    const double u =
        (centroids[static_cast<std::size_t>(f)][axis] - centroidBox.lo[axis]) / extent[axis];
    return std::clamp(static_cast<int>(kSahBins * u), 0, kSahBins - 1);
  };

  Bin bins[3][kSahBins];
  for (auto it = begin; it != end; ++it) {
    Box triangle;
    for (int k = 0; k < 3; ++k) triangle.grow(mesh.corner(*it, k));
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0)) continue;
      Bin& bin = bins[axis][binOf(*it, axis)];
      bin.box.grow(triangle);
      ++bin.count;
    }
  }
  double bestCost = INFINITY;
  int bestAxis = -1, bestBin = 0;  // the left part takes bins [0, bestBin]
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0)) continue;
    double rightCost[kSahBins];  // of bins [b, kSahBins)
    Bin right;
    for (int b = kSahBins - 1; b > 0; --b) {
      right.box.grow(bins[axis][b].box);
      right.count += bins[axis][b].count;
      rightCost[b] = right.box.halfArea() * right.count;
    }
    Bin left;
    for (int b = 0; b + 1 < kSahBins; ++b) {
      left.box.grow(bins[axis][b].box);
      left.count += bins[axis][b].count;
      if (left.count == 0 || left.count == count) continue;
      const double cost = left.box.halfArea() * left.count + rightCost[b + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestAxis = axis;
        bestBin = b;
      }
    }
  }
  if (bestAxis >= 0) {
    const auto mid =
        std::partition(begin, end, [&](int f) { return binOf(f, bestAxis) <= bestBin; });
    return static_cast<int>(mid - begin);
  }
  Eigen::Index axis;
  extent.maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(begin, begin + half, end, [&](int a, int b) {
    return centroids[static_cast<std::size_t>(a)][axis] <
           centroids[static_cast<std::size_t>(b)][axis];
  });
  return half;
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
  const int half = splitTriangles(mesh_, centroids_, order_, first, count);
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
  double minCos = 1.0, maxSin = 0.0;
  for (int i = node.first; i < node.first + node.count; ++i) {
    const int f = order_[i];
    const Eigen::Vector3d n = unitNormal(mesh_, f);
    minCos = std::min(minCos, node.normalAxis.dot(n));
    maxSin = std::max(maxSin, node.normalAxis.cross(n).norm());
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
  // The sine from the cross product: √(1 − cos²) cancels for a nearly flat patch.
  node.normalSinHalfAngle = minCos > 0.0 ? maxSin : 2.0;
}

}  // namespace vcontact::geometry
