// The branch and bound of the depth pass (depth/deepest_column.hpp): the segments are filed in
// blocks of kBlock × kBlock cells, each block bounded by the heights of the parts of its segments
// and faces inside it; a block is filed finely into its cells only when its bound can still beat
// the deepest column found, and a cell is evaluated only when its own bound can.

#include <algorithm>
#include <cmath>
#include <functional>

#include "volume/depth/deepest_column.hpp"

namespace vcontact::volume {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

/// τ as a fraction of the largest coordinate: two boundary points on one column (a vertex of
/// one body straight above a crossing on the other) differ in projection by their rounding, a
/// few ε of that size (≈ 1e-15); 1e-12 covers it a thousand times (as the box margin of
/// fast/surface_integration.cpp does). The column's span is taken over this reach, which adds at
/// most τ times the boundary's slope to the depth (a 1 m part at the origin, slope 1: 1e-12 m).
constexpr double kReach = 1e-12;
/// The boxes of the bounds (a cell's or a block's) are grown by this many τ: the points the
/// pass evaluates for a cell lie in it, or within τ of a point in it (a vertex's column reaches
/// τ; a crossing's bottom edge is taken within τ of its top edge's point), up to the rounding
/// of the cells' indices and of the clipping parameters, a few ε of the coordinates.
constexpr double kClipGrowth = 4.0;
/// The blocks are filed with this reach (in τ), the cells with 1: the blocks' edges and those
/// of their cells differ by the rounding of kBlock · h against the cells' own, far below τ,
/// so a block holds every segment that the cells inside it hold.
constexpr double kBlockReach = 2.0;
/// Regions of fewer segments are filed in cells directly, with the whole segments' and faces'
/// bounds (deepestInCells, clip_ false). Filing in blocks and clipping pay where most blocks
/// cannot beat the depth (the trays resting flat or on the rim: 3.5k and 6.4k segments, a few
/// per cent of their blocks refined); the small regions of the landing (the pins in the
/// chamfers: 0.3k to 2k segments) refine 80 to 95 % of their blocks, which would then be filed
/// twice, and bin_of_ten's small flat regions pay for the clipping more than it saves.
/// Measured on cad_tray_drop and bin_of_ten (docs/DISCRETE.md §4.2).
constexpr std::size_t kBlocksFrom = 3000;

}  // namespace

/// The cells of g that segment s passes within `reach` of, rows range[0] .. range[1] and
/// columns range[2] .. range[3] only, row by row, each with bounds [lo, hi] of the heights of
/// s's part inside the cell's box grown by kClipGrowth τ: emit(cell, lo, hi). The height is
/// linear along s: over the parameter interval [t0, t1] of that part it lies between its
/// values at t0 and t1, computed by the pass's own formula and widened by s's slack, which
/// covers the rounding of both evaluations.
template <class Emit>
void ColumnDepth::walk(const Grid& g, const Seg& s, double reach, const int (&range)[4],
                       Emit&& emit) const {
  const double ylo = std::min(s.a.y(), s.b.y()), yhi = std::max(s.a.y(), s.b.y());
  const double dx = s.b.x() - s.a.x(), dy = s.b.y() - s.a.y(), dh = s.hb - s.ha;
  const double ix = dx != 0.0 && clip_ ? 1.0 / dx : 0.0, iy = dy != 0.0 && clip_ ? 1.0 / dy : 0.0;
  const double grow = kClipGrowth * tau_;
  const int r0 = std::max(g.row(ylo - reach), range[0]);
  const int r1 = std::min(g.row(yhi + reach), range[1]);
  for (int r = r0; r <= r1; ++r) {
    double xlo = std::min(s.a.x(), s.b.x()), xhi = std::max(s.a.x(), s.b.x());
    double ty0 = 0.0, ty1 = 1.0;  // the parameters of its part in the row's grown slab
    if (dy != 0.0) {              // the x range of the segment within this row's slab
      const double y0 = std::clamp(g.y0 + r * g.hy - reach, ylo, yhi);
      const double y1 = std::clamp(g.y0 + (r + 1) * g.hy + reach, ylo, yhi);
      const double x0 = s.a.x() + (y0 - s.a.y()) * dx / dy;
      const double x1 = s.a.x() + (y1 - s.a.y()) * dx / dy;
      xlo = std::max(xlo, std::min(x0, x1));
      xhi = std::min(xhi, std::max(x0, x1));
    }
    if (dy != 0.0 && clip_) {
      const double ta = (g.y0 + r * g.hy - grow - s.a.y()) * iy;
      const double tb = (g.y0 + (r + 1) * g.hy + grow - s.a.y()) * iy;
      ty0 = std::max(0.0, std::min(ta, tb));
      ty1 = std::min(1.0, std::max(ta, tb));
    }
    const int c0 = std::max(g.col(xlo - reach), range[2]);
    const int c1 = std::min(g.col(xhi + reach), range[3]);
    for (int c = c0; c <= c1; ++c) {
      if (!clip_) {
        emit(r * g.nx + c, s.hmin, s.hmax);
        continue;
      }
      double t0 = ty0, t1 = ty1;
      if (dx != 0.0) {
        const double ta = (g.x0 + c * g.hx - grow - s.a.x()) * ix;
        const double tb = (g.x0 + (c + 1) * g.hx + grow - s.a.x()) * ix;
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      double lo = s.hmin, hi = s.hmax;
      if (t0 <= t1) {  // else filed by the reach of the filing alone: all of it is kept
        const double h0 = s.ha + t0 * dh, h1 = s.ha + t1 * dh;
        lo = std::max(lo, std::min(h0, h1) - s.slack);
        hi = std::min(hi, std::max(h0, h1) + s.slack);
      }
      emit(r * g.nx + c, lo, hi);
    }
  }
}

/// The box of cell c of g grown by kClipGrowth τ.
void ColumnDepth::box(const Grid& g, int c, Vector2d& lo, Vector2d& hi) const {
  const int r = c / g.nx, k = c % g.nx;
  const double grow = kClipGrowth * tau_;
  lo = {g.x0 + k * g.hx - grow, g.y0 + r * g.hy - grow};
  hi = {g.x0 + (k + 1) * g.hx + grow, g.y0 + (r + 1) * g.hy + grow};
}

/// Widens b by segment s's bounds [lo, hi] in it.
void ColumnDepth::bound(CellBound& b, const Seg& s, double lo, double hi) {
  b.hi = std::max(b.hi, hi);
  b.lo = std::min(b.lo, lo);
  if (s.side > 0) b.topHi = std::max(b.topHi, hi);
  if (s.side < 0) b.bottomLo = std::min(b.bottomLo, lo);
}

/// Files a top or bottom face in the blocks its projection's bounding box covers (a point of
/// the face lies in one of them; a wall holds no column's inside and is not filed).
void ColumnDepth::fileFace(int index) {
  const Face& f = faces_[static_cast<std::size_t>(index)];
  if (f.side == 0) return;
  const int r0 = grid_.row(f.bmin.y()) / kBlock, r1 = grid_.row(f.bmax.y()) / kBlock;
  const int c0 = grid_.col(f.bmin.x()) / kBlock, c1 = grid_.col(f.bmax.x()) / kBlock;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) facePairs_.emplace_back(blockOf(r, c), index);
  }
}

/// (bin, item) pairs to compressed rows: bin b's items are items[start[b] .. start[b + 1]).
void ColumnDepth::toCsr(std::vector<std::pair<int, int>>& pairs, int bins, std::vector<int>& start,
                        std::vector<int>& items) {
  start.assign(static_cast<std::size_t>(bins) + 1, 0);
  for (const auto& [bin, item] : pairs) ++start[static_cast<std::size_t>(bin) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  items.resize(pairs.size());
  std::vector<int>& next = next_;
  next.assign(start.begin(), start.end() - 1);
  for (const auto& [bin, item] : pairs) items[static_cast<std::size_t>(next[bin]++)] = item;
  pairs.clear();
}

/// The cell of segment s's first end, and its block.
int ColumnDepth::vertexCell(const Seg& s) const {
  return grid_.row(s.a.y()) * grid_.nx + grid_.col(s.a.x());
}

// Segment i's first vertex into its cell's vertex list, its height into the cell's bound.
void ColumnDepth::fileVertex(int i) {
  const Seg& s = segs_[static_cast<std::size_t>(i)];
  const int c = vertexCell(s);
  segPairs_.emplace_back(c, i);
  CellBound& b = cellBounds_[static_cast<std::size_t>(c)];
  b.vertices = true;
  b.hi = std::max(b.hi, s.ha);
  b.lo = std::min(b.lo, s.ha);
}

int ColumnDepth::blockOfCell(int c) const {
  return blockOf(c / grid_.nx / kBlock, c % grid_.nx / kBlock);
}

/// The first ends of the segments (the ends of a face's loops are the first ends of its
/// segments) by block; each block's bounds hold their heights.
void ColumnDepth::listVertices() {
  for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
    const Seg& s = segs_[static_cast<std::size_t>(i)];
    const int block = blockOfCell(vertexCell(s));
    segPairs_.emplace_back(block, i);
    CellBound& b = blockBounds_[static_cast<std::size_t>(block)];
    b.vertices = true;
    b.hi = std::max(b.hi, s.ha);  // the column's own height (its segment is filed here too)
    b.lo = std::min(b.lo, s.ha);
  }
  toCsr(segPairs_, blockOf(0, 0, true), blockVertexStart_, blockVertices_);
}

/// Widens [lo, hi] by the heights height(F, x) takes at the points x of the box [blo, bhi]
/// that lie in F's bounding box (the only ones where the pass evaluates it). Each rounded
/// operation of height() is monotonic, so the computed height is monotonic in x and in y,
/// and over the box it lies between its values at the two corners the slopes' signs pick.
void ColumnDepth::faceHeights(const Face& F, const Vector2d& blo, const Vector2d& bhi, double& lo,
                              double& hi) {
  if (F.bmax.x() < blo.x() || F.bmin.x() > bhi.x() || F.bmax.y() < blo.y() ||
      F.bmin.y() > bhi.y()) {
    return;
  }
  const Vector2d up(F.slope_u >= 0.0 ? blo.x() : bhi.x(), F.slope_v >= 0.0 ? blo.y() : bhi.y());
  const Vector2d down(F.slope_u >= 0.0 ? bhi.x() : blo.x(), F.slope_v >= 0.0 ? bhi.y() : blo.y());
  hi = std::max(hi, height(F, up));
  lo = std::min(lo, height(F, down));
}

/// An upper bound of every candidate value of a cell or block with bounds b and box [lo, hi],
/// whose faces are those of `block`. A crossing located in it has a top height minus a bottom
/// one, each within the bounds of its segment's part in the box; a vertex column's span is a
/// difference of heights of its vertex, of the segments' parts within τ of it and of the
/// faces of its block at it (faceHeights). Rounding is monotonic, so the computed difference
/// of the bounds bounds the computed difference of the values. −∞ without a candidate.
double ColumnDepth::upperBound(CellBound& b, int block, const Vector2d& lo,
                               const Vector2d& hi) const {
  double value = b.topHi - b.bottomLo;  // −∞ without a top and a bottom segment
  if (b.vertices) {
    for (int k = faceStart_[block]; k < faceStart_[block + 1]; ++k) {
      const Face& F = faces_[static_cast<std::size_t>(cellFaces_[k])];
      if (clip_) {
        faceHeights(F, lo, hi, b.lo, b.hi);
      } else {
        b.lo = std::min(b.lo, F.lo);
        b.hi = std::max(b.hi, F.hi);
      }
    }
    value = std::max(value, b.hi - b.lo);
  }
  return value;
}

/// Appends the (cell, item) pairs of one block's cells (rows range[0 .. 1], columns
/// range[2 .. 3]) to `pool`, by cell and in their order: cell c's are pool[begin[c] .. end[c]).
void ColumnDepth::distribute(const int (&range)[4], std::vector<int>& begin, std::vector<int>& end,
                             std::vector<int>& pool) {
  int count[kBlock * kBlock] = {}, next[kBlock * kBlock];
  const auto local = [&](int c) {
    return (c / grid_.nx - range[0]) * kBlock + (c % grid_.nx - range[2]);
  };
  for (const auto& [c, item] : segPairs_) ++count[local(c)];
  int at = static_cast<int>(pool.size());
  for (int r = range[0]; r <= range[1]; ++r) {
    for (int c = r * grid_.nx + range[2]; c <= r * grid_.nx + range[3]; ++c) {
      next[local(c)] = begin[static_cast<std::size_t>(c)] = at;
      at += count[local(c)];
      end[static_cast<std::size_t>(c)] = at;
    }
  }
  pool.resize(static_cast<std::size_t>(at));
  for (const auto& [c, item] : segPairs_) pool[static_cast<std::size_t>(next[local(c)]++)] = item;
  segPairs_.clear();
}

/// Files the segments and vertices of block B in its cells, bounds each cell, and queues those
/// whose bound exceeds best. The cells' lists are those a filing of the whole grid would give
/// (the same walk, restricted to the block), in the same order: top segments, then bottom
/// ones, then walls', each by index.
void ColumnDepth::refine(int B, double best) {
  const int R = B / blocks_.nx * kBlock, K = B % blocks_.nx * kBlock;
  const int range[4] = {R, std::min(R + kBlock, grid_.ny) - 1, K,
                        std::min(K + kBlock, grid_.nx) - 1};
  for (int r = range[0]; r <= range[1]; ++r) {
    for (int c = r * grid_.nx + range[2]; c <= r * grid_.nx + range[3]; ++c) {
      cellBounds_[static_cast<std::size_t>(c)] = CellBound{};
    }
  }
  for (int k = blockSegStart_[B]; k < blockSegStart_[B + 1]; ++k) {
    const int i = blockSegs_[k];
    const Seg& s = segs_[static_cast<std::size_t>(i)];
    walk(grid_, s, tau_, range, [&](int c, double lo, double hi) {
      segPairs_.emplace_back(c, i);
      bound(cellBounds_[static_cast<std::size_t>(c)], s, lo, hi);
    });
  }
  distribute(range, segBegin_, segEnd_, cellSegs_);
  for (int k = blockVertexStart_[B]; k < blockVertexStart_[B + 1]; ++k) {
    fileVertex(blockVertices_[k]);
  }
  distribute(range, vertexBegin_, vertexEnd_, cellVertices_);
  for (int r = range[0]; r <= range[1]; ++r) {
    for (int c = r * grid_.nx + range[2]; c <= r * grid_.nx + range[3]; ++c) {
      Vector2d lo, hi;
      box(grid_, c, lo, hi);
      const double value = upperBound(cellBounds_[static_cast<std::size_t>(c)], B, lo, hi);
      if (value > best) queue(value, c);
    }
  }
}

/// The pass without blocks, for small regions: every cell filed and bounded by its segments'
/// and faces' whole ranges, then evaluated largest bound first.
double ColumnDepth::deepestInCells() {
  cellBounds_.assign(cellBounds_.size(), CellBound{});
  for (const int side : {1, -1, 0}) {
    for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
      const Seg& s = segs_[static_cast<std::size_t>(i)];
      if (s.side != side) continue;
      const int all[4] = {0, grid_.ny - 1, 0, grid_.nx - 1};
      walk(grid_, s, tau_, all, [&](int c, double lo, double hi) {
        segPairs_.emplace_back(c, i);
        bound(cellBounds_[static_cast<std::size_t>(c)], s, lo, hi);
      });
    }
  }
  const int cells = grid_.nx * grid_.ny;
  const auto toLists = [&](std::vector<int>& begin, std::vector<int>& end, std::vector<int>& pool) {
    toCsr(segPairs_, cells, cellStart_, pool);
    std::copy(cellStart_.begin(), cellStart_.end() - 1, begin.begin());
    std::copy(cellStart_.begin() + 1, cellStart_.end(), end.begin());
  };
  toLists(segBegin_, segEnd_, cellSegs_);
  for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
    fileVertex(i);
  }
  toLists(vertexBegin_, vertexEnd_, cellVertices_);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) fileFace(f);
  toCsr(facePairs_, blockOf(0, 0, true), faceStart_, cellFaces_);
  const Vector2d lo = Vector2d::Zero(), hi = lo;  // unused without clipping
  for (int c = 0; c < cells; ++c) {
    const double value =
        upperBound(cellBounds_[static_cast<std::size_t>(c)], blockOfCell(c), lo, hi);
    if (value > 0.0) queue_.emplace_back(value, c);
  }
  // The cell of the largest bound first, then those still above its best, largest first (a
  // sort of the few left rather than a heap of all).
  if (queue_.empty()) return 0.0;
  const auto first = std::max_element(queue_.begin(), queue_.end());
  const int c0 = first->second;
  double best = evaluateCell(c0, 0.0);
  const auto beaten = [&](const std::pair<double, int>& b) { return b.first <= best; };
  queue_.erase(std::remove_if(queue_.begin(), queue_.end(), beaten), queue_.end());
  std::sort(queue_.begin(), queue_.end(), std::greater<>());
  for (const auto& [value, c] : queue_) {
    if (value <= best) break;
    if (c != c0) best = evaluateCell(c, best);
  }
  return best;
}

void ColumnDepth::queue(double value, int id) {
  queue_.emplace_back(value, id);
  std::push_heap(queue_.begin(), queue_.end());
}

double ColumnDepth::deepest(const Vector3d& n, const Vector3d& o, double scale) {
  last_ = {n, o, scale};
  if (input_.empty()) return 0.0;
  tau_ = kReach * scale;
  project(n, o);
  buildGrid();
  const int blocks = blockOf(0, 0, true);
  const std::size_t cells = static_cast<std::size_t>(grid_.nx) * grid_.ny;
  blockBounds_.assign(static_cast<std::size_t>(blocks), CellBound{});
  cellBounds_.resize(cells);  // set block by block (refine)
  segBegin_.resize(cells);
  segEnd_.resize(cells);
  vertexBegin_.resize(cells);
  vertexEnd_.resize(cells);
  cellSegs_.clear();
  cellVertices_.clear();
  queue_.clear();
  clip_ = segs_.size() >= kBlocksFrom;
  if (!clip_) return deepestInCells();
  // Top edges first, then bottom ones, then walls': each block's list keeps that order.
  const int all[4] = {0, blocks_.ny - 1, 0, blocks_.nx - 1};
  for (const int side : {1, -1, 0}) {
    for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
      const Seg& s = segs_[static_cast<std::size_t>(i)];
      if (s.side != side) continue;
      walk(blocks_, s, kBlockReach * tau_, all, [&](int b, double lo, double hi) {
        segPairs_.emplace_back(b, i);
        bound(blockBounds_[static_cast<std::size_t>(b)], s, lo, hi);
      });
    }
  }
  toCsr(segPairs_, blocks, blockSegStart_, blockSegs_);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) fileFace(f);
  toCsr(facePairs_, blocks, faceStart_, cellFaces_);
  listVertices();
  // Branch and bound: the maximum of the candidates' values does not depend on their order,
  // and a block or cell whose bound does not exceed the best value so far holds none that
  // would raise it. Blocks (−1 − B) and cells (c) in one queue, largest bound first.
  for (int B = 0; B < blocks; ++B) {
    Vector2d lo, hi;
    box(blocks_, B, lo, hi);
    const double value = upperBound(blockBounds_[static_cast<std::size_t>(B)], B, lo, hi);
    if (value > 0.0) queue(value, -1 - B);
  }
  return branchAndBound();
}

/// The queue's blocks refined and its cells evaluated, largest bound first, until the largest
/// bound left does not exceed the deepest column found.
double ColumnDepth::branchAndBound() {
  double best = 0.0;
  while (!queue_.empty() && queue_.front().first > best) {
    std::pop_heap(queue_.begin(), queue_.end());
    const int id = queue_.back().second;
    queue_.pop_back();
    if (id < 0) {
      refine(-1 - id, best);
    } else {
      best = evaluateCell(id, best);
    }
  }
  return best;
}

}  // namespace vcontact::volume
