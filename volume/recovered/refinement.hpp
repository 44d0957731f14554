#pragma once
// Contact on recovered surfaces that have no closed form (tori off a common axis, concave
// surfaces, two meshes other than a pin in a parallel bore: recovered/bore_pair.hpp), by the exact
// polyhedral methods run on the mesh refined towards its recognised surfaces around the patch
// (geometry/surface_refinement.hpp), at a level raised until V converges (docs/SURFACES.md,
// "Refinement").
//
// Error model. The refined faces are inscribed: a chord of length L on a radius R misses the
// surface by its sagitta L²/(8R), so splitting a face k×k divides its chord gap G by k², and V
// converges from below as V_k = V − C/k² + o(1/k²). For a contact whose volume grows as d^m
// with the depth d (m = 2 for a sphere, 3/2 for a cylinder on its side, 3 for a cone's tip;
// m ≤ 3), moving the surface in by g changes V by about m·g/d of itself, so a relative error ε
// asks for G/k² ≤ ε·d/2 (a conservative 2: the mean gap over a face is 2/3 of its largest):
// the first level is k = ⌈√(2G/(ε·d))⌉ from the depth, not found by doubling. The estimate
// of the finest level's error is Richardson's, from levels k and k' = ⌈k/2⌉:
// |V_k − V_k'|·k'²/(k² − k'²). When it exceeds ε·V the level is raised once more from it.
//
// Level cap: refining beyond the level where a face's chord gap falls below the recognised
// surface's own fit residual gains nothing (the refinement would then be closer to the fitted
// surface than the part's vertices are), and the refined faces cost memory and time as k²; the
// level is capped by both, and a result that met the cap before the tolerance says so.

#include <Eigen/Geometry>
#include <vector>

#include "volume/recovered/recovered_surface.hpp"

namespace vcontact::volume {

struct RefinementOptions {
  /// ε: the relative error of V aimed at (0.1 %).
  double tolerance = 1e-3;
  /// The largest level k: 256² = 65,536 faces per split face.
  int max_level = 256;
  /// The most faces the split faces of one body may become at one level (memory: ~100 bytes
  /// each with the tree and topology of the mesh–mesh method).
  long max_faces = 2'000'000;
  /// Whether refinedMeshMeshContact fills ContactVolume::depth: one more query of the converged
  /// level with `fast`'s exact depth pass (a library query leaves it out, QueryOptions::depth;
  /// the levels themselves never compute it). The half-space and bore paths fill it always.
  bool exact_depth = false;
};

/// The contact of `body` (pose X_WM) on the half-space (pose X_WH, solid z_H ≤ 0) with the
/// faces in `zone` (RecoveredBody::reachingFaces) refined; representation kRefined. Several
/// connected regions at the finest level are its `patches` (the clip's components there,
/// meshHalfspacePatches); cv is the whole.
RecoveredContact refinedHalfspaceContact(const RecoveredBody& body, const std::vector<int>& zone,
                                         const Eigen::Isometry3d& X_WM,
                                         const Eigen::Isometry3d& X_WH,
                                         const RefinementOptions& options = {});

/// The faces of `a` that can reach `b`: those whose box in B's frame, grown by both bodies'
/// margins (how far outside its mesh each true surface may lie) and by `depth`, overlaps the
/// box of a face of b. `depth` must bound how far inside b a face of a may lie (a face of a
/// bore wall wholly inside a pin pressed into it touches no face of the pin).
std::vector<int> facesWithinReach(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                  const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                  double depth);

/// Two meshes on their recovered surfaces by refinement alone: both bodies' faces within
/// reach of the other refined, the exact `fast` method (fast/surface_integration.hpp) on the two
/// refinements. representation kRefined when a curved recognised surface of either body can reach
/// the other, else kShape (the polyhedra, exact for planes; free-form faces stay polyhedral).
/// `parts` names the body ("A", "B") of each part; several connected regions at the finest
/// level are its `patches` (that level's `fast` patches).
/// @pre both meshes as meshMeshContact requires
RecoveredContact refinedMeshMeshContact(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                        const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                        const RefinementOptions& options = {});

/// Two meshes on their recovered surfaces: a pin in a bore by slices when one body is a
/// solid of revolution in a cylindrical bore of the other parallel to it
/// (volume/recovered/bore_pair.hpp, representation kRevolutionInBore, tried with A as the pin,
/// then B), else refinedMeshMeshContact, whose `reason` then says why the slices did not apply.
/// @pre both meshes as meshMeshContact requires
RecoveredContact recoveredMeshMeshContact(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                          const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                          const RefinementOptions& options = {});

}  // namespace vcontact::volume
