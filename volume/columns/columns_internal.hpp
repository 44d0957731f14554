#pragma once
// Internal to the column method (columns/columns.cpp, columns/raster.cpp); not part of the public
// API. The grid of lines, the world boxes, the per-line integrals and the grid sums shared by the
// driver in columns/columns.cpp and the rasteriser and grid integration in columns/raster.cpp.

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/moments.hpp"
#include "volume/columns/columns.hpp"

namespace vcontact::volume::internal {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::BvhNode;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct WorldBox {
  Vector3d lo = Vector3d::Constant(-kInf), hi = Vector3d::Constant(kInf);
  bool empty() const { return (lo.array() > hi.array()).any(); }
  WorldBox intersected(const WorldBox& o) const { return {lo.cwiseMax(o.lo), hi.cwiseMin(o.hi)}; }
};

inline WorldBox worldBox(const BvhNode& node, const Isometry3d& X_WB) {
  const Vector3d c = X_WB * node.center;
  const Vector3d h = X_WB.linear().cwiseAbs() * node.halfExtent;
  return {c - h, c + h};
}

/// A square-celled N × N grid of lines along u over the projection of `box` onto the plane
/// ⟂ u through the box centre o.
struct Grid {
  Vector3d o, u, e1, e2;
  double r1, r2;  ///< half-widths along e1, e2
  int n;

  Grid(const WorldBox& box, const Vector3d& dir, int resolution) : u(dir), n(resolution) {
    o = 0.5 * (box.lo + box.hi);
    const Vector3d h = 0.5 * (box.hi - box.lo);
    e1 = u.unitOrthogonal();
    e2 = u.cross(e1);
    r1 = e1.cwiseAbs().dot(h);
    r2 = e2.cwiseAbs().dot(h);
  }
  /// Lines along `dir` through the rectangle o ± r1 e1 ± r2 e2 (e1 ⟂ dir, unit).
  Grid(const Vector3d& origin, const Vector3d& dir, const Vector3d& axis1, double half1,
       double half2, int resolution)
      : o(origin), u(dir), e1(axis1), e2(dir.cross(axis1)), r1(half1), r2(half2), n(resolution) {}
  double cellArea() const { return 4.0 * r1 * r2 / (double(n) * n); }
  /// In-plate offset from o of line (i, j), at the cell centre.
  Vector3d offset(int i, int j) const {
    return (-r1 + (i + 0.5) * 2.0 * r1 / n) * e1 + (-r2 + (j + 0.5) * 2.0 * r2 / n) * e2;
  }
};

/// What one line contributes, in the line's own parameter t.
struct LineIntegrals {
  double L = 0.0, T1 = 0.0, T2 = 0.0;   ///< ∫dt, ∫t dt, ∫t² dt over A ∩ B
  double tFirst = kInf, tLast = -kInf;  ///< where the line enters and finally leaves A ∩ B
  double surfaceA = 0.0;                ///< Σ sign(n_A·u) over crossings of ∂A inside B
  double surfaceB = 0.0;                ///< the same for ∂B inside A
};

/// Sums over a grid: moments about o (W axes), the surface sums, and δ per line.
struct GridSums {
  geometry::Moments M;
  double surfaceA = 0.0, surfaceB = 0.0;
  double maxDepth = 0.0;
  int wetLines = 0;
  WorldBox wet{Vector3d::Constant(kInf), Vector3d::Constant(-kInf)};  ///< of the wet segments

  void add(const LineIntegrals& li, const Vector3d& x, const Vector3d& u, double dS) {
    surfaceA += li.surfaceA * dS;
    surfaceB += li.surfaceB * dS;
    if (li.L <= 0.0) return;
    // p − o = x + t u: ∫1 = L, ∫(x + t u) = L x + T1 u, ∫(x + t u)(x + t u)ᵀ = L x xᵀ +
    // T1 (x uᵀ + u xᵀ) + T2 u uᵀ (exact along the line; midpoint rule across, MODEL.md §1).
    M.m0 += li.L * dS;
    M.m1 += (li.L * x + li.T1 * u) * dS;
    M.m2 += (li.L * x * x.transpose() + li.T1 * (x * u.transpose() + u * x.transpose()) +
             li.T2 * u * u.transpose()) *
            dS;
    maxDepth = std::max(maxDepth, li.L);
    ++wetLines;
    for (double t : {li.tFirst, li.tLast}) {
      wet.lo = wet.lo.cwiseMin(x + t * u);
      wet.hi = wet.hi.cwiseMax(x + t * u);
    }
  }
  GridSums& operator+=(const GridSums& o) {
    M += o.M;
    surfaceA += o.surfaceA;
    surfaceB += o.surfaceB;
    maxDepth = std::max(maxDepth, o.maxDepth);
    wetLines += o.wetLines;
    wet = {wet.lo.cwiseMin(o.wet.lo), wet.hi.cwiseMax(o.wet.hi)};
    return *this;
  }
};

/// A piece of a line inside A ∩ B, from `from` to `to` (world points).
struct WetSegment {
  Vector3d from, to;
};

/// The connected regions of A ∩ B as seen by a set of wet segments: the voxels (cubes of side
/// `size` from `lo`) that the segments pass through, grouped into 26-connected components
/// (columns/regions.cpp). A region's label is its component's; the voxels within two of a
/// labelled one carry its label too (the nearest, first in index order on a tie), so that a
/// boundary point or a wet piece that a finer grid sees just beside the sampled voxels is still
/// given to its region.
/// The index of voxel v in a grid of `dims` voxels stored x fastest, then y, then z.
inline std::size_t voxelIndex(const Eigen::Vector3i& dims, const Eigen::Vector3i& v) {
  return static_cast<std::size_t>((v.z() * dims.y() + v.y()) * dims.x() + v.x());
}

struct VoxelRegions {
  Vector3d lo = Vector3d::Zero();
  double size = 0.0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  std::vector<int> label;       ///< per voxel, x fastest; −1 outside every region
  int count = 0;                ///< regions
  std::vector<WorldBox> boxes;  ///< per region, of its labelled voxels

  /// The label of the voxel holding p, −1 outside the grid or every region.
  int labelAt(const Vector3d& p) const {
    const Vector3d c = (p - lo) / size;
    if (!(c.array() >= 0.0).all()) return -1;
    const Eigen::Vector3i v = c.cast<int>();
    if ((v.array() >= dims.array()).any()) return -1;
    return label[voxelIndex(dims, v)];
  }
};

/// The regions of the wet segments in `box`, with voxels of side `size`.
VoxelRegions voxelRegions(const std::vector<WetSegment>& segments, const WorldBox& box,
                          double size);

/// Which region's pieces a grid integration keeps: those whose midpoint (crossings: whose
/// point) lies in region `id` of `regions`.
struct RegionFilter {
  const VoxelRegions* regions;
  int id;
  bool keeps(const Vector3d& p_W) const { return regions->labelAt(p_W) == id; }
};

/// The grid's sums; with `depth` (`lines`), also δ (the line integrals) of every line; with
/// `only`, of region only->id alone; with `segments`, the wet pieces of every line appended.
GridSums integrate(const ColumnBody& a, const ColumnBody& b, const Grid& g,
                   std::vector<double>* depth, std::vector<LineIntegrals>* lines = nullptr,
                   const RegionFilter* only = nullptr, std::vector<WetSegment>* segments = nullptr);

}  // namespace vcontact::volume::internal
