// The rasteriser and grid integration of the column method: the crossings of every line of a
// grid with each body (a mesh rasterised with watertight edge functions, or a half-space), the
// sweep of both bodies' crossings along one line, and the sums over a grid (integrate).

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "volume/columns/columns_internal.hpp"

namespace vcontact::volume::internal {
namespace {

using geometry::MeshBvh;

// A node's footprint on the grid is widened by this fraction of its size and distance before
// it is culled, so that rounding in the cull never drops a triangle that the edge functions
// would count.
constexpr double kBoxInflation = 1e-9;

// Fraction of a cell by which a triangle's footprint is widened when choosing the lines to
// test against it: far above the rounding of the footprint (~1e-15 cell), far below a cell.
constexpr double kCellMargin = 1e-6;

/// A crossing of a body's boundary along a line: +1 entering, −1 leaving, at parameter t.
struct Crossing {
  double t;
  int delta;
  bool operator<(const Crossing& o) const { return t < o.t; }
};

/// Twice the signed area of (0, a, b) in the plane; exact antisymmetry cross2(b, a) =
/// −cross2(a, b) is what makes the shared-edge test consistent between neighbours.
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Side of the point q relative to the edge a→b (all in the plate plane), with ties (q on
/// the edge's line) given to exactly one of the two triangles sharing the edge (they traverse
/// it in opposite directions): the "top-left" rule of rasterisers.
bool positiveSide(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double e = cross2(a, b);
  if (e != 0.0) return e > 0.0;
  const Eigen::Vector2d d = b - a;
  return d.x() > 0.0 || (d.x() == 0.0 && d.y() > 0.0);
}

/// The crossings of every line of a grid with one body, bucketed by line and sorted by t.
/// A mesh is rasterised: each triangle whose projection meets the grid is tested against
/// the lines through its footprint with edge functions (every vertex is projected the same
/// way wherever it appears, and ties follow positiveSide), so a line through an edge or a
/// vertex crosses the surface exactly once.
class GridCrossings {
 public:
  /// @param other  the other body. When it is a half-space and the lines run out of it
  ///   (u·z_H ≥ 0), nodes wholly above its plane are not rasterised: their crossings come
  ///   after every point of the overlap along the line (or, for u·z_H = 0, lie on lines that
  ///   miss it), so they change neither the winding inside it nor any sum. Lines running into
  ///   the half-space meet those crossings first, and they set the winding: no cull then.
  GridCrossings(const Grid& g, const ColumnBody& body, const ColumnBody& other)
      : g_(g),
        start_(g.n * g.n + 1, 0),
        cullAbove_(!other.bvh && other.X_WB.linear().col(2).dot(g.u) >= 0.0),
        X_WH_(other.X_WB) {
    std::vector<std::pair<int, Crossing>> hits;
    if (body.bvh) {
      rasterize(*body.bvh, body.X_WB, body.bvh->root(), hits);
    } else {
      halfspace(body.X_WB, hits);
    }
    bucket(hits);
  }

  std::span<const Crossing> at(int i, int j) const {
    const int c = i * g_.n + j;
    return {crossings_.data() + start_[c], crossings_.data() + start_[c + 1]};
  }

 private:
  /// Plate coordinates (along e1, e2) of line (i, j); one expression for every use.
  Eigen::Vector2d lineAt(int i, int j) const {
    return {-g_.r1 + (i + 0.5) * 2.0 * g_.r1 / g_.n, -g_.r2 + (j + 0.5) * 2.0 * g_.r2 / g_.n};
  }

  /// Half-space z_B ≤ 0 along line (i, j): z_B(t) = a + b t, inside where it is negative.
  void halfspace(const Isometry3d& X_WB, std::vector<std::pair<int, Crossing>>& hits) const {
    const Vector3d z_W = X_WB.linear().col(2);
    const double b = z_W.dot(g_.u);
    for (int i = 0; i < g_.n; ++i) {
      for (int j = 0; j < g_.n; ++j) {
        const double a = z_W.dot(g_.o + g_.offset(i, j) - X_WB.translation());
        const int c = i * g_.n + j;
        if (b > 0.0 || (b == 0.0 && a <= 0.0)) hits.push_back({c, {-kInf, +1}});
        if (b != 0.0) hits.push_back({c, {-a / b, b < 0.0 ? +1 : -1}});
      }
    }
  }

  void rasterize(const MeshBvh& bvh, const Isometry3d& X_WM, const BvhNode& node,
                 std::vector<std::pair<int, Crossing>>& hits) const {
    const WorldBox wb = worldBox(node, X_WM);
    const Vector3d c = 0.5 * (wb.lo + wb.hi) - g_.o, h = 0.5 * (wb.hi - wb.lo);
    const double slack = kBoxInflation * (h.norm() + c.norm());
    if (cullAbove_) {
      const Vector3d z_H = X_WH_.linear().col(2);
      const Vector3d c_H = 0.5 * (wb.lo + wb.hi) - X_WH_.translation();
      if (z_H.dot(c_H) - z_H.cwiseAbs().dot(h) > slack) return;
    }
    if (std::abs(c.dot(g_.e1)) > g_.r1 + g_.e1.cwiseAbs().dot(h) + slack ||
        std::abs(c.dot(g_.e2)) > g_.r2 + g_.e2.cwiseAbs().dot(h) + slack) {
      return;
    }
    if (!node.isLeaf()) {
      rasterize(bvh, X_WM, bvh.nodes()[node.left], hits);
      rasterize(bvh, X_WM, bvh.nodes()[node.right], hits);
      return;
    }
    for (int k = node.first; k < node.first + node.count; ++k) {
      rasterizeTriangle(bvh.mesh(), X_WM, bvh.order()[k], hits);
    }
  }

  void rasterizeTriangle(const geometry::TriangleMesh& mesh, const Isometry3d& X_WM, int f,
                         std::vector<std::pair<int, Crossing>>& hits) const {
    Eigen::Vector2d q[3];
    double z[3];
    for (int k = 0; k < 3; ++k) {
      const Vector3d p = X_WM * mesh.corner(f, k) - g_.o;
      q[k] = {p.dot(g_.e1), p.dot(g_.e2)};
      z[k] = p.dot(g_.u);
    }
    const Eigen::Vector2d lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]);
    const Eigen::Vector2d hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
    const double cell1 = 2.0 * g_.r1 / g_.n, cell2 = 2.0 * g_.r2 / g_.n;
    // Lines whose plate point may lie in the footprint; the margin only has to exceed the
    // rounding of these expressions, the edge functions decide.
    const int i0 = std::max(0, int(std::ceil((lo.x() + g_.r1) / cell1 - 0.5 - kCellMargin)));
    const int i1 =
        std::min(g_.n - 1, int(std::floor((hi.x() + g_.r1) / cell1 - 0.5 + kCellMargin)));
    const int j0 = std::max(0, int(std::ceil((lo.y() + g_.r2) / cell2 - 0.5 - kCellMargin)));
    const int j1 =
        std::min(g_.n - 1, int(std::floor((hi.y() + g_.r2) / cell2 - 0.5 + kCellMargin)));
    for (int i = i0; i <= i1; ++i) {
      for (int j = j0; j <= j1; ++j) {
        const Eigen::Vector2d s = lineAt(i, j);
        const Eigen::Vector2d a = q[0] - s, b = q[1] - s, c = q[2] - s;
        const bool side0 = positiveSide(b, c);
        if (positiveSide(c, a) != side0 || positiveSide(a, b) != side0) continue;
        const double w0 = cross2(b, c), w1 = cross2(c, a), w2 = cross2(a, b);
        const double sum = w0 + w1 + w2;  // 2 × projected area; sign: n·u
        if (sum == 0.0) continue;         // edge-on: its neighbours carry the crossing
        // (e1, e2, u) is right-handed, so sum > 0 ⇔ n·u > 0 ⇔ the line leaves the solid.
        hits.push_back(
            {i * g_.n + j, {(w0 * z[0] + w1 * z[1] + w2 * z[2]) / sum, sum > 0.0 ? -1 : +1}});
      }
    }
  }

  /// Counting sort of the hits by line, then by t within each line.
  void bucket(const std::vector<std::pair<int, Crossing>>& hits) {
    for (const auto& [c, x] : hits) ++start_[c + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    crossings_.resize(hits.size());
    std::vector<int> next(start_.begin(), start_.end() - 1);
    for (const auto& [c, x] : hits) crossings_[next[c]++] = x;
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) {
      std::sort(crossings_.begin() + start_[c], crossings_.begin() + start_[c + 1]);
    }
  }

  const Grid& g_;
  std::vector<int> start_;
  bool cullAbove_;   ///< skip nodes above the other body's plane (see the constructor)
  Isometry3d X_WH_;  ///< the other body's pose
  std::vector<Crossing> crossings_;
};

/// One line's place in the world, for the pieces and crossings that a region filter or the
/// segment list needs as points: p(t) = origin + t u.
struct LineInWorld {
  Vector3d origin, u;
  const RegionFilter* only = nullptr;         ///< keep this region's pieces alone
  std::vector<WetSegment>* pieces = nullptr;  ///< append every kept piece
  Vector3d at(double t) const { return origin + t * u; }
  bool keeps(double t) const { return !only || only->keeps(at(t)); }
};

/// Sweeps the merged crossings keeping both winding numbers (inside: winding > 0). A piece
/// between two crossings lies in one connected region of A ∩ B, so a region filter decides it
/// by its midpoint, and a crossing by its own point.
/// A line whose every piece and crossing counts, and whose pieces are not listed: the plain
/// integration compiles to the sweep alone.
struct AnyLine {
  bool keeps(double) const { return true; }
  void list(double, double) const {}
};

/// A line seen through a region filter or listing its pieces (LineInWorld).
struct TrackedLine {
  LineInWorld line;
  bool keeps(double t) const { return line.keeps(t); }
  void list(double t0, double t1) const {
    if (line.pieces) line.pieces->push_back({line.at(t0), line.at(t1)});
  }
};

template <class Line>
LineIntegrals overlap(std::span<const Crossing> a, std::span<const Crossing> b, const Line& line) {
  LineIntegrals r;
  int wa = 0, wb = 0;
  std::size_t i = 0, j = 0;
  double tPrev = -kInf;
  while (i < a.size() || j < b.size()) {
    const bool fromA = j == b.size() || (i < a.size() && a[i].t <= b[j].t);
    const Crossing& c = fromA ? a[i++] : b[j++];
    if (wa > 0 && wb > 0 && line.keeps(0.5 * (tPrev + c.t))) {
      r.tFirst = std::min(r.tFirst, tPrev);
      r.tLast = c.t;
      r.L += c.t - tPrev;
      r.T1 += (c.t * c.t - tPrev * tPrev) / 2.0;
      r.T2 += (c.t * c.t * c.t - tPrev * tPrev * tPrev) / 3.0;
      line.list(tPrev, c.t);
    }
    const bool counted = (fromA ? wb : wa) > 0 && line.keeps(c.t);
    if (counted) (fromA ? r.surfaceA : r.surfaceB) -= c.delta;
    (fromA ? wa : wb) += c.delta;
    tPrev = c.t;
  }
  return r;
}

}  // namespace

/// Grid rows per task of the deterministic reduction: a 64-line grid splits into 16 tasks, a
/// 512-line grid into 128, enough for the two cores to share while the join order stays fixed.
constexpr int kRowsPerTask = 4;

/// The grid's sums; with `depth` (`lines`), also δ (the line integrals) of every line; with
/// `only`, of region only->id alone; with `segments`, the wet pieces of every line appended.
GridSums integrate(const ColumnBody& a, const ColumnBody& b, const Grid& g,
                   std::vector<double>* depth, std::vector<LineIntegrals>* lines,
                   const RegionFilter* only, std::vector<WetSegment>* segments) {
  if (depth) depth->assign(static_cast<std::size_t>(g.n) * g.n, 0.0);
  if (lines) lines->assign(static_cast<std::size_t>(g.n) * g.n, LineIntegrals{});
  // Each row appends its pieces to its own list; the lists are joined in row order below.
  std::vector<std::vector<WetSegment>> rowPieces(segments ? static_cast<std::size_t>(g.n) : 0);
  const GridCrossings crossA(g, a, b), crossB(g, b, a);
  // Deterministic: the rows are split into the same chunks and joined in the same order
  // whatever the threads do, so a query gives the same bits on any machine and run (the
  // plain parallel_reduce joined in scheduling order: 3e-13 relative from run to run).
  // The line kind is chosen once per grid (lineAt), so that the plain integration's sweep
  // carries no test for a filter or a list.
  const auto reduce = [&](const auto& lineAt) {
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<int>(0, g.n, kRowsPerTask), GridSums{},
        [&](const tbb::blocked_range<int>& rows, GridSums sums) {
          for (int i = rows.begin(); i < rows.end(); ++i) {
            for (int j = 0; j < g.n; ++j) {
              const LineIntegrals li = overlap(crossA.at(i, j), crossB.at(i, j), lineAt(i, j));
              sums.add(li, g.offset(i, j), g.u, g.cellArea());
              if (depth) (*depth)[static_cast<std::size_t>(i) * g.n + j] = li.L;
              if (lines) (*lines)[static_cast<std::size_t>(i) * g.n + j] = li;
            }
          }
          return sums;
        },
        [](GridSums x, const GridSums& y) { return x += y; });
  };
  const GridSums sums = only || segments ? reduce([&](int i, int j) {
    return TrackedLine{{g.o + g.offset(i, j), g.u, only,
                        segments ? &rowPieces[static_cast<std::size_t>(i)] : nullptr}};
  })
                                         : reduce([](int, int) { return AnyLine{}; });
  for (const std::vector<WetSegment>& row : rowPieces) {
    segments->insert(segments->end(), row.begin(), row.end());
  }
  return sums;
}

}  // namespace vcontact::volume::internal
