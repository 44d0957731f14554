#pragma once
// Column integration of the interference of two bodies (MODEL.md §1, V = ∫_S δ dS): lines
// along the contact normal n on a square grid over the plate S; along each line the exact
// in/out intervals of both bodies come from its crossings with their surfaces (triangles
// found through the bounding-volume tree and rasterised onto the grid with watertight edge
// functions, so a line through an edge or vertex crosses once), their overlap gives δ and the
// exact line integrals of 1, t, t²; across lines the midpoint rule. The grid is refined (×2
// per level) until two successive level-to-level changes of V are within the requested
// tolerance, and the larger of them is reported as the error estimate.
//
// Between two meshes the first axis passes also run over the whole overlap box at the fine
// passes' resolution, so that a second, thinner region that no coarse line meets still counts
// (and gives the regions of columnsPatches).
//
// The normal comes from three passes along the world axes: a line along e_k crossing
// ∂A inside B at a face with normal n_A contributes sign(n_A·e_k) dS to
// (∫_{∂A∩B} n_A dA)_k (and likewise for ∂B inside A), so
// n ∝ ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA needs only crossing signs (MODEL.md §1).

#include <Eigen/Geometry>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/primitives.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// A body for the column method: a meshed solid, or the half-space z ≤ 0 of its frame when
/// `bvh` is null. `X_WB` is its pose.
struct ColumnBody {
  const geometry::MeshBvh* bvh = nullptr;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

struct ColumnOptions {
  double relativeTolerance = 1e-3;  ///< stop when two grid levels agree on V to this
  int initialResolution = 16;       ///< lines per side of the first grid
  int maxResolution = 512;          ///< lines per side at most

  /// One grid of `lines` per side, never refined: the same cost at every call (a simulation's
  /// right-hand side) and no error estimate (relative_error is inf). Against a half-space the
  /// normal is the plane's, without the axis passes, and the grid is laid in the mesh's own
  /// frame over the bound (in that frame) of the tree's leaves that reach below the plane: it
  /// moves with the body, so a face sliding or spinning on the plate keeps its columns and V
  /// is smooth in the pose. Two meshes keep the axis passes and the overlap box.
  static ColumnOptions fixed(int lines) { return {0.0, lines, lines}; }
  bool isFixed() const { return initialResolution >= maxResolution; }
};

/// ContactVolume of body A (the payload) and body B (the plate or other body); at least one of them
/// must be a mesh. The result's relative_error is the difference of the last two grid levels in V.
/// @param[out] field  if not null, filled with the δ map of the finest grid: a sample at every
///                    line with δ > 0, cell_area the grid's cell (left as it was when apart)
ContactVolume columnsContact(const ColumnBody& a, const ColumnBody& b,
                             const ColumnOptions& options = {}, DepthField* field = nullptr);

/// The same for shapes: A and B each a mesh (its tree from kernels/bvh_cache.hpp) or a half-space,
/// at least one a mesh.
/// @param[out] field  the δ map of the finest grid, if not null
/// @param options      grid and tolerance (default: refined to 1e-3)
/// @throws InputError when the pair is not handled, naming both shapes
ContactVolume columnsContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                             const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                             DepthField* field, const ColumnOptions& options = {});

/// The patches of A and B by columns, and the method table's backend of `columns`
/// (methods.hpp), with columnsContact as the aggregate.
/// - Two meshes (refined grids): the regions of A ∩ B are the 26-connected groups of the voxels
///   (1/64 of the overlap box) that the wet pieces of three axis passes over the whole overlap
///   box pass through; each region is then integrated alone, with the normal of its own axis
///   passes (MODEL.md §1 over its own boundary) and its own grid refined to the tolerance, so
///   that two regions on opposite walls, whose pair normal runs along both, are each seen face
///   on. Regions closer than about two voxels are one patch; one a line spacing of those passes
///   across can be missed (fast and cgal find every region exactly).
/// - A mesh on a half-space, or a fixed grid: the wet lines of the finest grid grouped into
///   patches (lines joined to the four neighbours whose wet spans along n overlap), each summed
///   alone with the pair's normal n, and the pair's error estimate. Two regions crossed by the
///   same lines are one patch.
/// Each patch: area = its lines × dS, depth = its largest δ.
/// @param[out] field  the δ map of the finest grid, if not null
/// @throws InputError when the pair is not handled, naming both shapes
ContactPatches columnsPatches(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                              const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                              DepthField* field, const ColumnOptions& options = {});

}  // namespace vcontact::volume
