// The connected regions of A ∩ B for the column method: the wet pieces of the axis passes
// marked on a voxel grid and grouped into 26-connected components (VoxelRegions).

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "volume/columns/columns_internal.hpp"

namespace vcontact::volume::internal {
namespace {

// Voxels of margin on every side of the box: the two rings a region's label is grown by.
constexpr int kMargin = 2;

/// The 26 neighbour offsets, in a fixed order.
std::array<Eigen::Vector3i, 26> neighbourOffsets() {
  std::array<Eigen::Vector3i, 26> out;
  int k = 0;
  for (int z = -1; z <= 1; ++z) {
    for (int y = -1; y <= 1; ++y) {
      for (int x = -1; x <= 1; ++x) {
        if (x != 0 || y != 0 || z != 0) out[static_cast<std::size_t>(k++)] = {x, y, z};
      }
    }
  }
  return out;
}

class VoxelGrid {
 public:
  explicit VoxelGrid(const VoxelRegions& r) : dims_(r.dims) {}
  std::size_t index(const Eigen::Vector3i& v) const { return voxelIndex(dims_, v); }
  Eigen::Vector3i voxel(std::size_t i) const {
    const int x = static_cast<int>(i % static_cast<std::size_t>(dims_.x()));
    const std::size_t yz = i / static_cast<std::size_t>(dims_.x());
    return {x, static_cast<int>(yz % static_cast<std::size_t>(dims_.y())),
            static_cast<int>(yz / static_cast<std::size_t>(dims_.y()))};
  }
  bool inside(const Eigen::Vector3i& v) const {
    return (v.array() >= 0).all() && (v.array() < dims_.array()).all();
  }

 private:
  Eigen::Vector3i dims_;
};

/// Marks voxels along a segment, sampled at most a voxel apart, both ends included: two
/// samples within a voxel's side of each other lie in the same or 26-adjacent voxels, so the
/// marks of one segment are connected.
void mark(const WetSegment& s, VoxelRegions& r, const VoxelGrid& grid, std::vector<char>& marked) {
  const double length = (s.to - s.from).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / r.size)));
  for (int k = 0; k <= steps; ++k) {
    const Vector3d p = s.from + (s.to - s.from) * (double(k) / steps);
    const Eigen::Vector3i v = ((p - r.lo) / r.size).array().floor().cast<int>();
    if (grid.inside(v)) marked[grid.index(v)] = 1;
  }
}

/// Labels the 26-connected components of the marked voxels, in index order.
void label(const std::vector<char>& marked, VoxelRegions& r, const VoxelGrid& grid) {
  static const std::array<Eigen::Vector3i, 26> kNeighbours = neighbourOffsets();
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < marked.size(); ++seed) {
    if (!marked[seed] || r.label[seed] >= 0) continue;
    r.label[seed] = r.count;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const Eigen::Vector3i v = grid.voxel(stack.back());
      stack.pop_back();
      for (const Eigen::Vector3i& d : kNeighbours) {
        const Eigen::Vector3i w = v + d;
        if (!grid.inside(w)) continue;
        const std::size_t i = grid.index(w);
        if (!marked[i] || r.label[i] >= 0) continue;
        r.label[i] = r.count;
        stack.push_back(i);
      }
    }
    ++r.count;
  }
}

/// Grows every region by `rings` voxels into unlabelled ones: each ring gives a voxel the
/// label of the first labelled neighbour found from the previous ring's voxels, in order.
void grow(VoxelRegions& r, const VoxelGrid& grid, int rings) {
  static const std::array<Eigen::Vector3i, 26> kNeighbours = neighbourOffsets();
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < r.label.size(); ++i) {
    if (r.label[i] >= 0) front.push_back(i);
  }
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<std::size_t> next;
    for (const std::size_t i : front) {
      const Eigen::Vector3i v = grid.voxel(i);
      for (const Eigen::Vector3i& d : kNeighbours) {
        const Eigen::Vector3i w = v + d;
        if (!grid.inside(w) || r.label[grid.index(w)] >= 0) continue;
        r.label[grid.index(w)] = r.label[i];
        next.push_back(grid.index(w));
      }
    }
    front = std::move(next);
  }
}

}  // namespace

VoxelRegions voxelRegions(const std::vector<WetSegment>& segments, const WorldBox& box,
                          double size) {
  VoxelRegions r;
  r.size = size;
  r.lo = box.lo - Vector3d::Constant(kMargin * size);
  r.dims = ((box.hi - box.lo) / size).array().ceil().cast<int>().max(1) + 2 * kMargin;
  const VoxelGrid grid(r);
  const std::size_t voxels = static_cast<std::size_t>(r.dims.prod());
  std::vector<char> marked(voxels, 0);
  for (const WetSegment& s : segments) mark(s, r, grid, marked);
  r.label.assign(voxels, -1);
  label(marked, r, grid);
  if (r.count > 1) grow(r, grid, kMargin);
  r.boxes.assign(static_cast<std::size_t>(r.count),
                 WorldBox{Vector3d::Constant(kInf), Vector3d::Constant(-kInf)});
  for (std::size_t i = 0; i < voxels; ++i) {
    if (r.label[i] < 0) continue;
    const Vector3d corner = r.lo + grid.voxel(i).cast<double>() * size;
    WorldBox& b = r.boxes[static_cast<std::size_t>(r.label[i])];
    b = {b.lo.cwiseMin(corner), b.hi.cwiseMax(corner + Vector3d::Constant(size))};
  }
  return r;
}

}  // namespace vcontact::volume::internal
