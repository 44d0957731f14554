#include "volume/recovered/refinement.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "geometry/mesh_topology.hpp"
#include "geometry/surface_refinement.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/recovered/bore_pair.hpp"

namespace vcontact::volume {
namespace {

using geometry::RecognisedSurface;
using geometry::SurfaceKind;

// What refinement of one body's zone involves: the largest chord gap G of its faces on curved
// recognised surfaces, how many such faces, and the largest fit residual of their surfaces.
struct Zone {
  std::vector<int> faces;
  double gap = 0.0;       ///< G, m
  int curved = 0;         ///< faces that will be split
  double residual = 0.0;  ///< m
};

Zone zoneOf(const RecoveredBody& body, std::vector<int> faces) {
  Zone z;
  z.faces = std::move(faces);
  const geometry::SurfaceRecognition& rec = body.recognition();
  for (int f : z.faces) {
    const int s = rec.face_surface[static_cast<std::size_t>(f)];
    if (s < 0 || rec.surfaces[static_cast<std::size_t>(s)].kind == SurfaceKind::kPlane) continue;
    ++z.curved;
    z.gap = std::max(z.gap, body.faceGaps()[static_cast<std::size_t>(f)]);
    z.residual = std::max(z.residual, rec.surfaces[static_cast<std::size_t>(s)].max_residual);
  }
  return z;
}

// One entry per surface (and the free-form faces) of the zone, for RecoveredContact::parts.
void addParts(const RecoveredBody& body, const Zone& z, const char* label,
              std::vector<PatchPart>& parts) {
  const geometry::SurfaceRecognition& rec = body.recognition();
  std::map<int, int> count;
  for (int f : z.faces) ++count[rec.face_surface[static_cast<std::size_t>(f)]];
  for (const auto& [s, n] : count) {
    if (s < 0) {
      parts.push_back({label, "free-form", n, "polyhedral"});
      continue;
    }
    const RecognisedSurface& S = rec.surfaces[static_cast<std::size_t>(s)];
    const bool plane = S.kind == SurfaceKind::kPlane;
    parts.push_back({label, std::string(S.convex ? "" : "concave ") + surfaceKindName(S.kind), n,
                     plane ? "exact" : "refined"});
  }
}

// The level cap (recovered/refinement.hpp): the fit residual, the face budget, max_level.
int levelCap(const Zone& z, const RefinementOptions& o) {
  double cap = o.max_level;
  if (z.residual > 0.0) cap = std::min(cap, std::ceil(std::sqrt(z.gap / z.residual)));
  if (z.curved > 0)
    cap = std::min(cap, std::floor(std::sqrt(static_cast<double>(o.max_faces) / z.curved)));
  return std::max(2, static_cast<int>(cap));
}

// k = ⌈√(2G/(ε·d))⌉, the first level for depth d, within [2, cap].
int levelFor(double gap, double depth, double tolerance, int cap) {
  const double k = std::ceil(std::sqrt(2.0 * gap / (tolerance * depth)));
  return static_cast<int>(std::clamp(k, 2.0, static_cast<double>(cap)));
}

double depthOf(const ContactVolume& cv) {
  if (std::isfinite(cv.depth) && cv.depth > 0.0) return cv.depth;
  // the mean depth V/A of a shallow segment is about 2/3 of its largest
  return cv.area > 0.0 ? 1.5 * cv.volume / cv.area : 0.0;
}

struct Converged {
  ContactVolume cv;
  int level = 1;
  double error = 0.0;  ///< Richardson estimate of |V_level − V|, m³
  bool converged = true;
};

// Raises the level until the depth seen asks for no more, then estimates the error from the
// level below (recovered/refinement.hpp, "Error model").
Converged converge(const std::function<ContactVolume(int)>& eval, double gap, double depthHint,
                   int cap, double tolerance) {
  int k = depthHint > 0.0 ? levelFor(gap, depthHint, tolerance, cap) : std::min(4, cap);
  ContactVolume cv = eval(k);
  for (int round = 0; round < 8; ++round) {
    if (!cv.inContact()) {
      // the true surfaces may still overlap by up to the chord gap G/k²: look closer
      if (k >= cap) return {cv, k, 0.0, true};
      k = std::min(cap, 4 * k);
    } else {
      const int need = levelFor(gap, std::max(depthHint, depthOf(cv)), tolerance, cap);
      if (need <= k) break;
      k = need;
    }
    cv = eval(k);
  }
  if (!cv.inContact()) return {cv, k, 0.0, true};
  int coarse = (k + 1) / 2;
  ContactVolume cvCoarse = eval(coarse);
  const auto richardson = [&] {
    const double k2 = static_cast<double>(k) * k, c2 = static_cast<double>(coarse) * coarse;
    return std::abs(cv.volume - cvCoarse.volume) * c2 / (k2 - c2);
  };
  double error = richardson();
  if (error > tolerance * cv.volume && k < cap) {
    const int next = std::min(
        cap, static_cast<int>(std::ceil(1.1 * k * std::sqrt(error / (tolerance * cv.volume)))));
    coarse = k;
    cvCoarse = cv;
    k = std::max(next, k + 1);
    cv = eval(k);
    error = richardson();
  }
  return {cv, k, error, error <= tolerance * cv.volume};
}

// `patches`: the connected regions of the finest level (c.level), kept when there are several.
RecoveredContact fromConverged(const Converged& c, double residual, std::vector<PatchPart> parts,
                               std::vector<ContactVolume> patches) {
  RecoveredContact r{c.cv, Representation::kRefined, "", 0.0, {}, 0, true, {}};
  if (c.cv.inContact() && patches.size() > 1) r.patches = std::move(patches);
  r.parts = std::move(parts);
  r.level = c.level;
  r.converged = c.converged;
  r.volume_error_bound = c.error + c.cv.area * residual;
  return r;
}

// The level of a body whose largest gap is `gap` when the pair's level is k for the larger
// gap G: its faces' gaps then stay below G/k² as well.
int bodyLevel(int k, double gap, double G) {
  if (gap <= 0.0 || G <= 0.0) return 1;
  return std::max(1, static_cast<int>(std::ceil(k * std::sqrt(gap / G))));
}

// Boxes of face f of `mesh` in another frame (X: mesh to that frame), grown by `grow`.
geometry::Aabb faceBox(const geometry::TriangleMesh& mesh, int f, const Eigen::Isometry3d& X,
                       double grow) {
  geometry::Aabb box{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d p = X * mesh.corner(f, c);
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

bool overlaps(const geometry::Aabb& a, const Eigen::Vector3d& center, const Eigen::Vector3d& half) {
  return ((a.min - center - half).array() <= 0.0).all() &&
         ((a.max - center + half).array() >= 0.0).all();
}

}  // namespace

RecoveredContact refinedHalfspaceContact(const RecoveredBody& body, const std::vector<int>& zone,
                                         const Eigen::Isometry3d& X_WM,
                                         const Eigen::Isometry3d& X_WH,
                                         const RefinementOptions& options) {
  const Zone z = zoneOf(body, zone);
  // The zone's vertices lie on the true surface: the deepest of them is a lower bound of the
  // true depth, and sets the first level.
  const Eigen::Isometry3d X_HM = X_WH.inverse() * X_WM;
  double depth = 0.0;
  for (int f : z.faces)
    for (int c = 0; c < 3; ++c) depth = std::max(depth, -(X_HM * body.mesh().corner(f, c)).z());
  const auto eval = [&](int k) {
    const geometry::SurfaceRefinement r =
        geometry::refineSurfaces(body.mesh(), body.recognition(), z.faces, k);
    return meshHalfspaceContact(r.mesh, X_WM, X_WH);
  };
  std::vector<PatchPart> parts;
  addParts(body, z, "A", parts);
  const Converged c = converge(eval, z.gap, depth, levelCap(z, options), options.tolerance);
  // the regions of the finest level: its clip labelled by components (whose aggregate is the
  // accelerated clip's, equal to the reference clip's above up to rounding)
  std::vector<ContactVolume> patches;
  if (c.cv.inContact()) {
    const geometry::SurfaceRefinement r =
        geometry::refineSurfaces(body.mesh(), body.recognition(), z.faces, c.level);
    patches =
        meshHalfspacePatches(geometry::MeshBvh(r.mesh), geometry::MeshTopology(r.mesh), X_WM, X_WH)
            .patches;
  }
  return fromConverged(c, z.residual, std::move(parts), std::move(patches));
}

std::vector<int> facesWithinReach(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                  const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                  double depth) {
  const Eigen::Isometry3d X_BA = X_WB.inverse() * X_WA;
  const double grow = a.margin() + b.margin() + depth;
  const geometry::MeshBvh& tree = b.bvh();
  std::vector<int> faces;
  for (int f = 0; f < static_cast<int>(a.mesh().triangleCount()); ++f) {
    const geometry::Aabb box = faceBox(a.mesh(), f, X_BA, grow);
    const bool hit = geometry::visitTrianglesNear(tree, box, [&](int g) {
      const geometry::Aabb other = faceBox(b.mesh(), g, Eigen::Isometry3d::Identity(), 0.0);
      return overlaps(box, 0.5 * (other.min + other.max), 0.5 * (other.max - other.min));
    });
    if (hit) faces.push_back(f);
  }
  return faces;
}

RecoveredContact refinedMeshMeshContact(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                        const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                        const RefinementOptions& options) {
  // A face of one body may lie inside the other as deep as the true surfaces overlap, beyond
  // the reach of the other's faces' boxes: the boxes grow by the polyhedra's overlap depth
  // and both chord margins, 1.5 times (the polyhedra's depth misses the true one by at most
  // the margins; the factor covers a face whose box is tight to its chord).
  const ContactVolume poly =
      meshMeshContact(a.bvh(), geometry::MeshTopology(a.mesh()), X_WA, b.bvh(),
                      geometry::MeshTopology(b.mesh()), X_WB, nullptr, true)
          .aggregate;
  const double depth = poly.inContact() && std::isfinite(poly.depth)
                           ? 1.5 * (poly.depth + a.margin() + b.margin())
                           : 0.0;
  const Zone za = zoneOf(a, facesWithinReach(a, X_WA, b, X_WB, depth));
  const Zone zb = zoneOf(b, facesWithinReach(b, X_WB, a, X_WA, depth));
  std::vector<PatchPart> parts;
  addParts(a, za, "A", parts);
  addParts(b, zb, "B", parts);
  const double G = std::max(za.gap, zb.gap);
  const auto evalAt = [&](int k, bool deepest) {
    const geometry::SurfaceRefinement ra =
        geometry::refineSurfaces(a.mesh(), a.recognition(), za.faces, bodyLevel(k, za.gap, G));
    const geometry::SurfaceRefinement rb =
        geometry::refineSurfaces(b.mesh(), b.recognition(), zb.faces, bodyLevel(k, zb.gap, G));
    const geometry::MeshBvh ta(ra.mesh), tb(rb.mesh);
    const geometry::MeshTopology topoA(ra.mesh), topoB(rb.mesh);
    return meshMeshContact(ta, topoA, X_WA, tb, topoB, X_WB, nullptr, deepest);
  };
  // every level's regions; the finest's are the result's
  std::map<int, std::vector<ContactVolume>> regions;
  const auto eval = [&](int k) {
    ContactPatches c = evalAt(k, false);
    regions[k] = std::move(c.patches);
    return c.aggregate;
  };
  if (za.curved + zb.curved == 0) {
    RecoveredContact r{evalAt(1, options.exact_depth).aggregate,
                       Representation::kShape,
                       "no curved recognised surface can reach the other body",
                       0.0,
                       {},
                       1,
                       true,
                       {}};
    r.parts = std::move(parts);
    const bool freeForm = std::any_of(r.parts.begin(), r.parts.end(),
                                      [](const PatchPart& p) { return p.surface == "free-form"; });
    r.volume_error_bound = freeForm ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    return r;
  }
  const Zone& finer = za.gap >= zb.gap ? za : zb;
  Zone both = finer;
  both.curved = za.curved + zb.curved;
  both.residual = std::max(za.residual, zb.residual);
  Converged c = converge(eval, G, 0.0, levelCap(both, options), options.tolerance);
  std::vector<ContactVolume> patches = std::move(regions[c.level]);
  if (options.exact_depth && c.cv.inContact()) {
    const ContactPatches exact = evalAt(c.level, true);
    c.cv.depth = exact.aggregate.depth;
    patches = exact.patches;
  }
  return fromConverged(c, both.residual, std::move(parts), std::move(patches));
}

RecoveredContact recoveredMeshMeshContact(const RecoveredBody& a, const Eigen::Isometry3d& X_WA,
                                          const RecoveredBody& b, const Eigen::Isometry3d& X_WB,
                                          const RefinementOptions& options) {
  std::string aInB, bInA;
  if (std::optional<RecoveredContact> r = boreContact(a, X_WA, b, X_WB, aInB)) return *r;
  if (std::optional<RecoveredContact> r = boreContact(b, X_WB, a, X_WA, bInA)) {
    r->cv = swapped(r->cv);
    for (ContactVolume& patch : r->patches) patch = swapped(patch);
    return *r;
  }
  RecoveredContact r = refinedMeshMeshContact(a, X_WA, b, X_WB, options);
  const std::string why =
      "no slices (A in a bore of B: " + aInB + "; B in a bore of A: " + bInA + ")";
  r.reason = r.reason.empty() ? why : r.reason + "; " + why;
  return r;
}

}  // namespace vcontact::volume
