#pragma once
// The exact depth pass of volume/depth/deepest_column.hpp as it was at 89ea7e6, before its
// speed-ups (docs/DISCRETE.md §4.2): the reference that the current pass must equal bit for bit
// (depth/deepest_column_test.cpp) and the old side of the depth benchmark (mesh_query_bench.cpp).
// Same candidates, same formulas; the class is renamed and moved to the tests, nothing else
// changed.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace vcontact::volume::test {

class ReferenceColumnDepth {
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

 private:
  struct Input {
    std::uint64_t key;
    Eigen::Vector3d n_f, p, q;
  };
  struct Seg {
    Eigen::Vector2d a, b;  ///< projection on the plate
    double ha, hb;         ///< heights along n
    int face;              ///< dense face index
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
    double x0 = 0, y0 = 0, hx = 1, hy = 1;
    int nx = 1, ny = 1;
    int col(double x) const;
    int row(double y) const;
  };

  void project(const Eigen::Vector3d& n, const Eigen::Vector3d& o);
  void buildGrid();
  void fileSegment(int s);
  void fileFace(int f);
  void toCsr(std::vector<std::pair<int, int>>& pairs, int bins, std::vector<int>& start,
             std::vector<int>& items);
  bool holds(const Face& f, const Eigen::Vector2d& x) const;
  double columnSpanAt(const Eigen::Vector2d& x, double h) const;
  double crossingsIn(int cell) const;

  std::vector<Input> input_;
  std::vector<int> order_;
  std::vector<Seg> segs_;
  std::vector<Face> faces_;
  Grid grid_;
  double tau_ = 0.0;
  std::vector<std::pair<int, int>> segPairs_, facePairs_;  ///< (cell, item) before CSR
  std::vector<int> segStart_, cellSegs_, faceStart_, cellFaces_;
  std::vector<int> next_;  ///< CSR fill cursor
};

}  // namespace vcontact::volume::test
