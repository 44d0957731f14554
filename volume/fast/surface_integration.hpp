#pragma once
// Exact interference of two closed triangle meshes by local surface integration (the "fast"
// method): the moments of A ∩ B are summed over the boundary of the region,
// ∂(A ∩ B) = (∂A ∩ B) ∪ (∂B ∩ A), without building the region as a mesh.
//
// Steps (1: fast/tree_pair_descent.hpp, fast/triangle_pair.hpp; 2 and 4:
// fast/surface_integration.cpp; 3: fast/intersection_boundary.cpp):
//  1. Broad phase: the two bounding-volume trees are descended together, both nodes of a
//     pair split at once (A's boxes taken into B's frame, each node once per query; box and
//     normal-slab bounds); or, with a MeshMeshCache, the leaf pairs recorded at a nearby pose
//     are retested instead. In an overlapping leaf pair, a face that misses the other leaf's
//     slab skips its row (column); a face pair then survives a box test, a conservative
//     plane-side test and, when each face certainly straddles the other's plane, the
//     Guigue–Devillers interval test (two filtered orientations: a pair is dropped only when
//     it certainly misses).
//  2. Crossings: every edge of one mesh is tested against every candidate face of the other
//     with exact orientation predicates and a symbolic perturbation (kernels/exact_predicates.hpp),
//     each (edge, face) pair exactly once, so every face that uses the decision sees the same
//     one (the double filter decides when it is certain, the exact predicate otherwise). A
//     crossing records its direction (entering or leaving the other body).
//  3. Boundary pieces: for a face t of one mesh, the region R_t = t ∩ (other body) is bounded
//     by (i) the segments t ∩ t' for the faces t' of the other mesh, whose two ends are two of
//     the crossings above and whose direction follows from theirs, and (ii) the parts of t's
//     edges inside the other body (crossings sorted along the edge; inside and outside
//     alternate). Faces that no crossing reaches are wholly inside or outside: inside ones are
//     found by a flood over the edges that cross nothing, starting from the inner ends of the
//     crossing edges; a connected part of a mesh with no crossing edge at all takes one exact
//     ray-parity test (through the other tree).
//  4. Integration (divergence theorem, fan from an apex o at a crossing): for a planar region
//     R with boundary edges (p, q) counter-clockwise about its outward normal, the moments of
//     the cone from o over R are Σ tet(o, c, p, q) for any point c of R's plane (here o
//     projected onto it), so the pieces need not be joined into polygons.
//
// Exactness: every topological decision is exact (for the double coordinates of the vertices
// placed in W, p_W = X_WM p_M, as the CGAL reference places them); only the crossing points
// and the integrals are rounded. Touching and coplanar faces are decided as for A moved by an
// infinitesimal translation, so they add nothing, and the result is the limit of the generic
// answer (never NaN).

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "volume/contact_volume.hpp"

namespace vcontact::volume {

/// What one pair of meshes keeps between queries at nearby poses (a simulation's right-hand
/// sides, micrometres apart): the leaf pairs of the two trees whose boxes overlap at a
/// recorded relative pose X_BA when grown by a reach m. While every point of A has moved, in
/// B's frame, by at most m since, every leaf pair that overlaps now is among them, and a
/// query tests those instead of descending both trees; a query beyond that re-records them.
/// The result is the same as without the cache up to the rounding of the sums (the order in
/// which crossings are found changes the integration's apex). One cache per pair and thread.
/// A recording that no query reused (the pair moves farther than m between queries, as in a
/// landing) is not repeated at the next miss: that query descends as without the cache and
/// keeps only its pose (`recorded` false), and the pairs are recorded again once a query
/// finds itself within m of the last pose kept.
struct MeshMeshCache {
  /// m as a fraction of the two root boxes' half-diagonals: for 30 mm parts, 40 µm, some
  /// steps of a stiff contact; large enough to be reused across a step's evaluations, small
  /// enough to add few leaf pairs.
  static constexpr double kReach = 1e-3;

  const geometry::MeshBvh* a = nullptr;  ///< the trees the pairs were recorded for
  const geometry::MeshBvh* b = nullptr;
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();  ///< pose they were recorded at
  double reach = 0.0;                                      ///< m, in metres
  std::vector<std::pair<int, int>> leafPairs;              ///< node indices (A, B)
  bool recorded = false;    ///< leafPairs are those of X_BA (false: X_BA is a plain descent's)
  long reuses = 0;          ///< queries answered from the recorded pairs
  long refreshes = 0;       ///< descents that recorded them
  long plain = 0;           ///< descents that did not record (the last recording went unused)
  long reusesAtRecord = 0;  ///< `reuses` when the pairs were last recorded

  /// Are the recorded pairs valid for these trees at relative pose X_BA_now?
  bool covers(const geometry::MeshBvh& treeA, const geometry::MeshBvh& treeB,
              const Eigen::Isometry3d& X_BA_now) const;
};

/// The contact of mesh A (the payload, pose X_WA) and mesh B (the plate or other body, pose X_WB),
/// Method::kFast, as the whole region (the aggregate) and its connected components (the patches,
/// each by the same formulas from its own boundary pieces, about its own apex, in sortPatches
/// order):
///   V, p_c, J_v, J_s: the moments of A ∩ B (exact up to rounding; relative_error NaN);
///   n ∝ ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA (MODEL.md §1);
///   area = ½ Σ_faces |n_f·n| A_f over the region's boundary faces, the projection of the
///   region onto the plate, exact when every column along n crosses the region once (as in
///   cgal/corefinement.hpp, so the two methods report the same area);
///   depth = max over the plate of δ(s), the longest column along n (depth/deepest_column.hpp),
///   only with `deepest`; NaN by default (the pass makes a query on two curved meshes 3–4× as long,
///   benchmarks/README.md, "Depth on demand").
/// Apart, or touching without overlap: V = 0 (inContact() false).
/// Patches (step 5, fast/intersection_patches.cpp): the pieces of ∂(A ∩ B) join through their end
/// nodes (crossings, inside vertices; whole faces through their corners); a face whose region
/// is bounded by several such groups joins each hole loop to the smallest outer loop around
/// it on that face. With no cavities in A or B, each component of A ∩ B has one connected
/// boundary, so the groups are exactly its components. A query whose pieces form one group
/// (and with no shell wholly inside the other body) pays one union-find pass over its pieces;
/// only multi-group queries join whole faces and integrate again.
/// All outputs in W.
/// @param a, b        the trees of the two meshes (body frames A and B)
/// @param topoA, topoB the topology of the same meshes
/// @param cache        if not null, the pair's leaf pairs kept between queries (MeshMeshCache)
/// @param deepest      compute depth (false, the default: depth is NaN, everything else the
///                     same to the bit)
/// @pre both meshes closed, outward-oriented, without degenerate faces or self-intersections
///   (geometry/mesh_check.hpp), without cavities; thread-safe (per-thread scratch memory).
/// @throws std::logic_error, with both poses to 17 digits, if the crossings do not close
///   up into segments (an internal invariant; it would mean a predicate bug)
ContactPatches meshMeshContact(const geometry::MeshBvh& a, const geometry::MeshTopology& topoA,
                               const Eigen::Isometry3d& X_WA, const geometry::MeshBvh& b,
                               const geometry::MeshTopology& topoB, const Eigen::Isometry3d& X_WB,
                               MeshMeshCache* cache = nullptr, bool deepest = false);

/// The method table's backend of `fast` (methods.hpp): meshMeshContact of two mesh shapes,
/// their trees and topologies from kernels/bvh_cache.hpp and kernels/mesh_topology_cache.hpp;
/// `deepest` as there (QueryOptions::depth == DepthMode::kDeepest through computeContact).
/// @pre a and b both meshes
ContactPatches fastContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                           const geometry::Shape& b, const Eigen::Isometry3d& X_WB,
                           MeshMeshCache* cache, bool deepest = false);

}  // namespace vcontact::volume
