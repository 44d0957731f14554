#pragma once
// Contact of a mesh body on its recovered surfaces (geometry/surface_recognition.hpp) against
// a half-space (docs/SURFACES.md).
//
// A tessellation is inscribed in its part: the vertices lie on the true surface and the faces
// cut chords inside it, so at the micrometre depths of metal contact the polyhedron misses
// most of the interference (a 10,000-triangle sphere at d/R = 1e-4 by 96 %). Where the part of
// the body that can reach the plane lies on one recognised sphere, or on one recognised
// cylinder closed by flat ends, the contact is that of the true solid: the closed forms of
// the analytic backend. Anywhere else (free-form faces, several surfaces, kinds without a
// closed form against a plane yet) the result is the polyhedral one, and says so.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/surface_recognition.hpp"
#include "geometry/triangle_mesh.hpp"
#include "volume/contact.hpp"
#include "volume/contact_volume.hpp"
#include "volume/recovered/revolution_body.hpp"

namespace vcontact::volume {

struct RecoveredContact {
  ContactVolume cv;
  /// What the contact was computed on: a sphere or a cylinder closed by flat ends (kSphere,
  /// kCylinder) or a solid of revolution (kRevolution: cylinders, cones, spheres and tori on one
  /// axis closed by planes across it, volume/recovered/revolution_body.hpp), by closed-form
  /// slices; a solid of revolution in a cylindrical bore of the other mesh (kRevolutionInBore,
  /// volume/recovered/bore_pair.hpp, by slices); the polyhedron refined towards its recognised
  /// surfaces around the patch until V converged (kRefined, surface_refinement.hpp), or the
  /// polyhedron itself (kShape, "mesh").
  Representation representation = Representation::kShape;
  /// Why no closed form applied, for the polyhedron and a refinement; empty otherwise.
  std::string reason;
  /// A bound on |V − V_true|, m³: for a recovered surface the contact area times the largest
  /// distance of the surface's vertices to it (the fit residual) plus the closed form's own
  /// error; refined: the Richardson estimate of the last level's error plus the same fit
  /// residual term; for the polyhedron, the area times the largest chord gap of the faces that can
  /// reach the plane (how far the true surface may lie outside the faces).
  double volume_error_bound = 0.0;
  /// What the faces that can reach the partner were computed on, per body and surface: for
  /// kRefined, one entry per recognised surface or the free-form faces (PatchPart).
  std::vector<PatchPart> parts;
  /// kRefined: the refinement level k of the finest evaluation, and whether the error estimate
  /// met the tolerance asked for (false: the level cap was reached first).
  int level = 0;
  bool converged = true;
  /// The connected regions, where the representation splits them (kRevolutionInBore: the
  /// runs of the pin's axis, recovered/pin_in_bore.hpp; kRevolution on a plane: the runs of
  /// wetted slices, analytic/revolution_on_plane.hpp); empty: the contact is one region, cv.
  std::vector<ContactVolume> patches;
};

/// A mesh body with its recognised surfaces, prepared once for many queries: the chord gap
/// of each surface, and whether the whole body is one sphere or one solid of revolution (then
/// a query is the closed form alone, with no pass over the mesh).
class RecoveredBody {
 public:
  /// @param recognition  recogniseSurfaces(mesh); both must outlive the body
  RecoveredBody(const geometry::TriangleMesh& mesh,
                const geometry::SurfaceRecognition& recognition);

  /// @param X_WM, X_WH  poses of the mesh and of the half-space (solid z ≤ 0 of H)
  RecoveredContact halfspaceContact(const Eigen::Isometry3d& X_WM,
                                    const Eigen::Isometry3d& X_WH) const;

  /// The contact by a closed form when one applies at this pose (the part of the body that can
  /// reach the plane lies on one sphere, or on surfaces of revolution about one axis and the
  /// planes across it that close them); otherwise nothing, and
  /// `reason` says why, for a caller that clips the polyhedron its own way (a simulation wants
  /// the clip's patches).
  std::optional<RecoveredContact> closedFormContact(const Eigen::Isometry3d& X_WM,
                                                    const Eigen::Isometry3d& X_WH,
                                                    std::string& reason) const;

  const geometry::TriangleMesh& mesh() const { return mesh_; }
  const geometry::SurfaceRecognition& recognition() const { return recognition_; }
  const geometry::MeshBvh& bvh() const { return bvh_; }
  /// Per face: the largest distance between its chord and its surface, m (0: free-form).
  const std::vector<double>& faceGaps() const { return faceGap_; }
  /// The body's profile when its whole surface is one solid of revolution (a cylinder or
  /// cone, sphere and torus pieces on one axis closed by planes), else null.
  const RevolutionBody* revolution() const {
    return whole_ && !whole_->sphere ? &whole_->revolution : nullptr;
  }
  /// The largest chord gap of any face, m: how far outside the mesh the true surface may lie.
  double margin() const { return margin_; }
  /// The faces whose lowest vertex is within margin() of the plane z_H = 0 or below it.
  /// @param X_HM  pose of the mesh in the half-space frame
  std::vector<int> reachingFaces(const Eigen::Isometry3d& X_HM) const;

 private:
  /// A closed form: one sphere, or else a solid of revolution.
  struct ClosedForm {
    const geometry::RecognisedSurface* sphere = nullptr;
    RevolutionBody revolution;
  };
  /// The closed form of the contact when the faces in `touched` (surface indices, −1 for
  /// free-form) reach the plane; nothing with the reason otherwise.
  std::optional<ClosedForm> closedForm(const std::set<int>& touched, std::string& reason) const;
  static RecoveredContact onClosedForm(const ClosedForm& form, const Eigen::Isometry3d& X_WM,
                                       const Eigen::Isometry3d& X_WH);

  /// The surfaces (−1: free-form) of the faces whose lowest vertex is within margin_ of the
  /// plane or below it, found by descending the tree.
  std::set<int> reachingSurfaces(const Eigen::Isometry3d& X_HM) const;

  const geometry::TriangleMesh& mesh_;
  const geometry::SurfaceRecognition& recognition_;
  geometry::MeshBvh bvh_;
  std::vector<double> gap_;      ///< per surface: largest chord gap of its faces, m
  std::vector<double> faceGap_;  ///< per face, m
  double margin_ = 0.0;          ///< the largest gap
  /// The body's closed form when its whole surface is one sphere or one solid of revolution.
  std::optional<ClosedForm> whole_;
};

/// A mesh's recovered surface: what recognition found on it (and how long that took), and the
/// body prepared for queries. Made once per mesh and shared (recoverSurface): the scenario and
/// dataset readers make it at load for "surface": "recovered", and every `recovered` query on
/// that mesh finds it. It refers to the mesh, which must outlive it.
struct RecoveredSurface {
  /// @throws InputError when recognition refuses the mesh (not closed, not oriented)
  explicit RecoveredSurface(const geometry::TriangleMesh& mesh);
  RecoveredSurface(const RecoveredSurface&) = delete;  // the body refers to `recognition`
  RecoveredSurface& operator=(const RecoveredSurface&) = delete;

  geometry::SurfaceRecognition recognition;
  double recognition_seconds = 0.0;  ///< wall time of recogniseSurfaces, s
  std::unique_ptr<RecoveredBody> body;
};

// recoverSurface, recognition, recognitionSeconds and recognisedKinds are declared in the query
// header (volume/contact.hpp), for the readers above volume/.

/// One query on a body prepared for it alone (RecoveredBody).
RecoveredContact recoveredHalfspaceContact(const geometry::TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const Eigen::Isometry3d& X_WM,
                                           const Eigen::Isometry3d& X_WH);

}  // namespace vcontact::volume
