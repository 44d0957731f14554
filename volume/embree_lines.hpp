#pragma once
// The columns' line casting on Embree 3 (volume/columns.hpp): the crossings of a grid of lines
// with a mesh, found by casting one ray per line through an Embree scene of the mesh built once
// in its own frame M.
//
// Exactness. Embree works in single precision: its rays and vertices are rounded to float
// (~6e-8 relative), so it is used only to FIND the triangles a line meets. Each triangle it
// reports is then tested in double with the same watertight edge functions and top-left tie
// rule as the tree rasteriser (volume/columns.cpp), which also gives the crossing parameter
// t, so interval lengths keep the rasteriser's accuracy and, for the same set of crossings,
// its bits. Where Embree and the double test may disagree (the line passes within
// kNearEdge of an edge of the reported triangle in the plate plane, or outside it), the
// triangle across that edge is tested too (near two edges: every triangle at their common
// corner), and each (line, triangle) pair is tested once: a line exactly through a shared
// edge or vertex therefore crosses once, at the one triangle the tie rule picks. Embree's
// robust mode is not fully watertight (a ray through an edge can miss both triangles, embree
// issue #387), so a line whose crossings of the closed mesh do not sum to zero is reported as
// unresolved, and the caller rasterises instead.

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::volume {

/// A square-celled grid of lines along u: line (i, j), 0 ≤ i, j < n, passes through
/// o + (−r1 + (i + ½) 2 r1/n) e1 + (−r2 + (j + ½) 2 r2/n) e2, all in W.
struct LineGrid {
  Eigen::Vector3d o, u, e1, e2;
  double r1, r2;  ///< half-widths along e1, e2, m
  int n;
};

/// A crossing of the mesh boundary by line `line` = i n + j at o + (plate point) + t u:
/// delta = +1 entering, −1 leaving.
struct LineCrossing {
  int line;
  double t;
  int delta;
};

/// The Embree scene of a closed mesh (in M) and, for each triangle, the triangles that share
/// a corner with it.
class EmbreeLines {
 public:
  /// @pre `mesh` is closed, with vertices shared between its triangles (welded)
  explicit EmbreeLines(const geometry::TriangleMesh& mesh);
  ~EmbreeLines();
  EmbreeLines(const EmbreeLines&) = delete;
  EmbreeLines& operator=(const EmbreeLines&) = delete;

  /// The crossings of every line of `grid` with the mesh at pose X_WM, in no particular order.
  /// @return false (and `out` unspecified) when some line's crossings do not balance
  bool cross(const Eigen::Isometry3d& X_WM, const LineGrid& grid,
             std::vector<LineCrossing>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vcontact::volume
