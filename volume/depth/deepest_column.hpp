#pragma once
// The depth of a polyhedral contact region (MODEL.md §1): d = max over the contact plate S of
// δ(s), the length of the region's column along n through s. The exact mesh–mesh methods
// (`fast`, `cgal`) know the region only as its planar boundary faces; this pass takes those
// faces' boundary segments and finds the deepest column without building the region.
//
// Why the candidates below suffice. Where every column along n crosses the region once, δ(s)
// = h_top(s) − h_bot(s), the heights (along n) of the faces the column leaves and enters by.
// Both are linear over each cell of the overlay of the projected boundary edges, so δ is too,
// and its maximum lies at an overlay vertex: a projected vertex of the region (a column through
// a vertex), or a point where a projected edge of a top face (n_f·n > 0) crosses one of a
// bottom face (n_f·n < 0). The pass evaluates the column at every such point:
//  - through a vertex: the lowest and highest point of the closed boundary on that column,
//    from the faces whose projection holds it (crossing number over the face's own boundary
//    loops) and the edges that pass within τ = 1e-12 of the coordinates of it (a wall,
//    n_f·n = 0, counts through its edges only);
//  - at a top/bottom edge crossing: the difference of the two edges' heights there.
// So d is exact (up to rounding and τ) where the columns cross the region once, the condition
// under which `area` is exact too. Where a column crosses it several times, the vertex columns
// count the gaps between the crossings (the column's span, an upper bound of its δ).
//
// Cost: a uniform grid over the projections' bounding box with about one cell per segment. A
// segment is filed in the cells its projection passes within τ of, a face (top or bottom) in
// the cells its projected bounding box covers. A vertex column looks at the segments and faces
// of its own cell only, and a crossing is sought among the segments that share a cell, so the
// pass is linear in the segment count for pieces of similar size (a lens seen along n: two
// triangulated caps over one disk, each cell holding a few faces of each). Before the exact
// formulas, a segment whose bounding box (grown by 2τ) misses the vertex, or a top/bottom pair
// whose boxes miss each other, is passed over: such a segment lies more than 2τ from the
// point, far beyond the formulas' rounding, so they would reject it too and the answer is the
// same bit for bit (each candidate's value is a min, max or difference of the same numbers,
// whatever the grid or the order). The buffers are kept from query to query.
//
// Branch and bound (issue 18). d is a maximum, and most candidates of a thin, wide region (a
// part resting flat: 0.01–0.2 µm deep, tens of mm wide) cannot come near it. Every height the
// pass computes on a segment lies within its ends' range widened by a few ulps (Seg::hmin,
// hmax), and a face's height is clamped to its range [lo, hi]; rounding is monotonic, so a
// difference of such bounds bounds the computed value. Each cell gets the bound of its
// candidates (crossings: its top segments' highest minus its bottom segments' lowest; vertex
// columns: all its segments' and its block's faces' range), and the cells are evaluated
// largest bound first until the bound does not exceed the best value found. A large region
// (kBlocksFrom segments or more, depth/deepest_column_bounds.cpp) is first filed and bounded in
// blocks of 4 × 4 cells only, and a block is filed into its cells when its bound comes first (the
// resting tray files a few of its 400 blocks finely instead of its 6,400 cells); there each
// segment and face is taken over its part inside the block's or cell's box grown by 4τ only
// (heights linear along a segment, monotonic over a face's plane: their values at the part's
// ends or the box's corners bound them), which keeps a tilted region's bounds near its depth
// (the upper tray on the rim: half the cells evaluated). Within a cell a
// top/bottom pair whose own bound does not exceed it is passed over, and a vertex column whose
// faces (taken from their boxes, before the crossing-number test) cannot lift its span above
// it; a face whose height lies within the column's span so far is not tested at all. Only
// candidates that cannot raise the maximum are left out, so d is the same to the bit as with
// every candidate evaluated (deepest_column_test, against the pass of 89ea7e6).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vcontact::volume {

class ColumnDepth {
 public:
  /// Forgets the segments of the previous region (keeps the memory).
  void clear();

  /// A boundary segment p–q of the face `faceKey` (any direction; each face's segments form
  /// closed loops), whose unit outward normal is n_f (the same for all its segments).
  void add(std::uint64_t faceKey, const Eigen::Vector3d& n_f, const Eigen::Vector3d& p,
           const Eigen::Vector3d& q);

  /// max δ along the unit direction n over the segments added (0 without any).
  /// @param o      a point near the region: coordinates are taken relative to it
  /// @param scale  the largest |coordinate| of the region's points in their frame, m: the
  ///               rounding of the points (a few ε of it) sets the tolerance τ
  double deepest(const Eigen::Vector3d& n, const Eigen::Vector3d& o, double scale);

  /// A segment as add() took it.
  struct Input {
    std::uint64_t key;
    Eigen::Vector3d n_f, p, q;
  };
  /// The segments added since clear(), in order, and the arguments of the last deepest(): a
  /// test replays a query's pass through another implementation with them.
  const std::vector<Input>& inputs() const { return input_; }
  struct Arguments {
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), o = Eigen::Vector3d::Zero();
    double scale = 0.0;
  };
  const Arguments& lastArguments() const { return last_; }

 private:
  struct Seg {
    Eigen::Vector2d a, b;    ///< projection on the plate
    double ha, hb;           ///< heights along n
    int face;                ///< dense face index
    int side;                ///< its face's side (Face::side)
    Eigen::Vector2d lo, hi;  ///< bounding box of a, b
    double len;              ///< |b − a|
    double hmin, hmax;       ///< bounds of any height the pass interpolates on it (kSlack)
    double slack;            ///< hmax − max(ha, hb): the rounding allowed for on its heights
  };
  struct Face {
    double slope_u, slope_v;     ///< n_f·u / n_f·n, n_f·v / n_f·n (0 for a wall)
    double h0;                   ///< height of the plane at the plate's origin
    double lo, hi;               ///< height range of its segments' ends
    Eigen::Vector2d bmin, bmax;  ///< bounding box of its projection
    int side;                    ///< +1 top (n_f·n > 0), −1 bottom, 0 wall
    int s0, s1;                  ///< its segments: segs_[s0 .. s1)
  };
  /// Row-major cells of hx × hy from (x0, y0); nx × ny of them.
  struct Grid {
    double x0 = 0, y0 = 0, hx = 1, hy = 1, inv_hx = 1, inv_hy = 1;
    int nx = 1, ny = 1;
    int col(double x) const {
      return std::clamp(static_cast<int>(std::floor((x - x0) * inv_hx)), 0, nx - 1);
    }
    int row(double y) const {
      return std::clamp(static_cast<int>(std::floor((y - y0) * inv_hy)), 0, ny - 1);
    }
  };

  /// Cells of kBlock × kBlock cells: the bins of the faces and the first filing (deepest()).
  static constexpr int kBlock = 4;
  struct CellBound;
  void groupByFace();
  void project(const Eigen::Vector3d& n, const Eigen::Vector3d& o);
  void buildGrid();
  template <class Emit>
  void walk(const Grid& g, const Seg& s, double reach, const int (&range)[4], Emit&& emit) const;
  void box(const Grid& g, int c, Eigen::Vector2d& lo, Eigen::Vector2d& hi) const;
  void fileFace(int f);
  int blockOf(int r, int c, bool count = false) const;
  int vertexCell(const Seg& s) const;
  void fileVertex(int i);  ///< segment i's vertex column into its cell, with its bound
  int blockOfCell(int c) const;
  void toCsr(std::vector<std::pair<int, int>>& pairs, int bins, std::vector<int>& start,
             std::vector<int>& items);
  void distribute(const int (&range)[4], std::vector<int>& begin, std::vector<int>& end,
                  std::vector<int>& pool);
  bool holds(const Face& f, const Eigen::Vector2d& x) const;
  static bool misses(const Seg& s, const Eigen::Vector2d& x, double g);
  static bool inBox(const Face& f, const Eigen::Vector2d& x);
  static double height(const Face& f, const Eigen::Vector2d& x);
  static void faceHeights(const Face& F, const Eigen::Vector2d& blo, const Eigen::Vector2d& bhi,
                          double& lo, double& hi);
  double columnBound(const Eigen::Vector2d& x, double h, int cell, int block) const;
  double columnSpanAt(const Eigen::Vector2d& x, double h, double best) const;
  double crossingsIn(int cell, double best) const;
  double crossingDepth(const Seg& s, const Seg& t) const;
  static bool beyondLine(const Seg& s, const Seg& t, double g);
  static bool sameEnds(const Seg& s, const Seg& t);
  /// Upper and lower bounds of the heights of a cell's (or block's) candidates.
  struct CellBound {
    double hi = -kInf, lo = kInf;           ///< any segment filed, vertex, face of its block
    double topHi = -kInf, bottomLo = kInf;  ///< top and bottom segments filed
    bool vertices = false;                  ///< holds the first end of a segment
  };
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static void bound(CellBound& b, const Seg& s, double lo, double hi);
  void listVertices();
  double upperBound(CellBound& b, int block, const Eigen::Vector2d& lo,
                    const Eigen::Vector2d& hi) const;
  void refine(int block, double best);
  void queue(double value, int id);
  double deepestInCells();
  double branchAndBound();
  double evaluateCell(int c, double best);
  /// The segment of cell list position k (cellSegs_).
  const Seg& cellSeg(int k) const {
    return segs_[static_cast<std::size_t>(cellSegs_[static_cast<std::size_t>(k)])];
  }
  // The detrended bounds (depth/deepest_column_trend.cpp).
  struct Trend {
    Eigen::Vector2d g = Eigen::Vector2d::Zero();  ///< subtracted gradient of the heights
    double gAbs = 0.0;                            ///< |g|₁
    double err = 0.0;    ///< largest rounding allowed for on a detrended height
    double dAbs = 0.0;   ///< largest |h − g·y| of the cell's segments' ends
    bool valid = false;  ///< g is set (the cell has a top or bottom segment)
  };
  bool detrend(int c);
  double detrended(const Eigen::Vector2d& y, double h);
  void detrendedFace(const Face& F, const Eigen::Vector2d& blo, const Eigen::Vector2d& bhi,
                     double& lo, double& hi);
  double detrendedBound(int c);
  double trendMargin(double gx) const;

  std::vector<Input> input_;
  std::vector<int> order_;  ///< input indices by face, then in the order added
  std::vector<std::pair<std::uint64_t, int>> keyed_, keyedSpare_;  ///< (key, input) radix sort
  std::vector<Seg> segs_;
  std::vector<Face> faces_;
  Grid grid_;
  double tau_ = 0.0;
  Grid blocks_;       ///< the blocks of kBlock × kBlock cells as cells of their own
  bool clip_ = true;  ///< bounds from the parts of segments and faces in a cell (large regions)
  std::vector<std::pair<int, int>> segPairs_, facePairs_;  ///< (bin, item) before CSR
  std::vector<int> blockSegStart_, blockSegs_;             ///< segments by block
  std::vector<int> blockVertexStart_, blockVertices_;      ///< segments by block of first end
  std::vector<int> faceStart_, cellFaces_;                 ///< faces by block (fileFace)
  std::vector<int> next_;                                  ///< CSR fill cursor
  std::vector<int> cellStart_;                             ///< CSR rows (deepestInCells)
  std::vector<CellBound> blockBounds_, cellBounds_;        ///< cells': of refined blocks only
  /// Of the cells of refined blocks: segments filed in cell c, cellSegs_[segBegin_[c] ..
  /// segEnd_[c]); segments whose first end lies in it, likewise in cellVertices_.
  std::vector<int> segBegin_, segEnd_, cellSegs_;
  std::vector<int> vertexBegin_, vertexEnd_, cellVertices_;
  std::vector<int> cellScratch_;               ///< a cell's vertices, sorted (evaluateCell)
  std::vector<std::pair<double, int>> queue_;  ///< heap of (bound, cell or −1 − block)
  Trend trend_;                                ///< of cell cellOfTrend_ (detrend)
  int cellOfTrend_ = -1;
  std::vector<std::pair<double, double>> trendRange_;  ///< its segments' detrended [lo, hi]
  Arguments last_;
};

}  // namespace vcontact::volume
