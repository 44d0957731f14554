#include "volume/recovered/recovered_query.hpp"

#include <algorithm>
#include <cassert>
#include <optional>
#include <string>
#include <variant>

#include "geometry/error.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/recovered/bore_pair.hpp"
#include "volume/recovered/recovered_surface.hpp"
#include "volume/recovered/refinement.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;

// Every region labelled with the method that produced it.
ContactPatches labelled(ContactPatches c) {
  c.aggregate.method = Method::kRecovered;
  for (ContactVolume& p : c.patches) p.method = Method::kRecovered;
  return c;
}

// A result on the recovered surfaces: its regions (one, or the bore's runs) and what it used.
ContactPatches onSurfaces(const RecoveredContact& r) {
  ContactPatches c = singlePatch(r.cv);
  if (r.cv.inContact() && !r.patches.empty()) c.patches = r.patches;
  c.surface.representation = r.representation;
  c.surface.reason = r.reason;
  c.surface.volume_error_bound = r.volume_error_bound;
  c.surface.parts = r.parts;
  c.surface.level = r.level;
  c.surface.converged = r.converged;
  return labelled(std::move(c));
}

// The fallback on the polyhedra: the exact method's patches, the reason, and the bound on
// |V − V_true| of a polyhedron.
ContactPatches onPolyhedra(ContactPatches c, std::string reason, double bound) {
  c.surface.representation = Representation::kShape;
  c.surface.reason = std::move(reason);
  c.surface.volume_error_bound = bound;
  return labelled(std::move(c));
}

const std::shared_ptr<const geometry::TriangleMesh>& meshOf(const geometry::Shape& s) {
  return std::get<geometry::Mesh>(s).mesh;
}

// A mesh M on the half-space H, n out of H into M.
ContactPatches onPlane(const geometry::Shape& m, const Isometry3d& X_WM, const geometry::Shape& h,
                       const Isometry3d& X_WH, const QueryOptions& options) {
  const RecoveredBody& body = *recoverSurface(meshOf(m))->body;
  std::string reason;
  if (std::optional<RecoveredContact> r = body.closedFormContact(X_WM, X_WH, reason))
    return onSurfaces(*r);
  if (options.refine) {  // refined where curved faces reach, else the clip with its own bound
    const RecoveredContact r = body.halfspaceContact(X_WM, X_WH);
    if (r.representation != Representation::kShape) return onSurfaces(r);
    return onPolyhedra(halfspaceClipContact(m, X_WM, h, X_WH), r.reason, r.volume_error_bound);
  }
  ContactPatches clip = halfspaceClipContact(m, X_WM, h, X_WH);
  // the area times the largest chord gap of the body's faces: how far outside them the true
  // surface may lie
  const double bound = clip.aggregate.area * body.margin();
  return onPolyhedra(std::move(clip), std::move(reason), bound);
}

// Two meshes, n out of B into A.
ContactPatches meshInMesh(const geometry::Shape& a, const Isometry3d& X_WA,
                          const geometry::Shape& b, const Isometry3d& X_WB,
                          const QueryOptions& options, ContactCache* cache) {
  const RecoveredBody& bodyA = *recoverSurface(meshOf(a))->body;
  const RecoveredBody& bodyB = *recoverSurface(meshOf(b))->body;
  const bool deepest = options.depth == DepthMode::kDeepest;
  std::string aInB, bInA;
  if (std::optional<RecoveredContact> r = boreContact(bodyA, X_WA, bodyB, X_WB, aInB))
    return onSurfaces(*r);
  if (std::optional<RecoveredContact> r = boreContact(bodyB, X_WB, bodyA, X_WA, bInA))
    return swapped(onSurfaces(*r));
  std::string reason = "no slices (A in a bore of B: " + aInB + "; B in a bore of A: " + bInA + ")";
  if (options.refine) {
    RefinementOptions refinement;
    refinement.exact_depth = deepest;
    RecoveredContact r = refinedMeshMeshContact(bodyA, X_WA, bodyB, X_WB, refinement);
    if (r.representation != Representation::kShape) {
      r.reason = r.reason.empty() ? reason : r.reason + "; " + reason;
      return onSurfaces(r);
    }
  }
  ContactPatches polyhedra =
      fastContact(a, X_WA, b, X_WB, cache ? &cache->meshMesh() : nullptr, deepest);
  const double bound = polyhedra.aggregate.area * (bodyA.margin() + bodyB.margin());
  return onPolyhedra(std::move(polyhedra), std::move(reason), bound);
}

}  // namespace

ContactPatches recoveredContact(const geometry::Shape& a, const Isometry3d& X_WA,
                                const geometry::Shape& b, const Isometry3d& X_WB,
                                const QueryOptions& options, ContactCache* cache) {
  const bool meshA = std::holds_alternative<geometry::Mesh>(a);
  const bool meshB = std::holds_alternative<geometry::Mesh>(b);
  if (meshA && meshB) return meshInMesh(a, X_WA, b, X_WB, options, cache);
  if (meshA) return onPlane(a, X_WA, b, X_WB, options);
  assert(meshB);
  return swapped(onPlane(b, X_WB, a, X_WA, options));
}

}  // namespace vcontact::volume
