#include "volume/recovered/recovered_surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "geometry/surface_refinement.hpp"
#include "volume/analytic/primitive_on_plane.hpp"
#include "volume/analytic/revolution_on_plane.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/kernels/mesh_cache.hpp"
#include "volume/recovered/refinement.hpp"

namespace vcontact::volume {
namespace {

using geometry::RecognisedSurface;
using geometry::SurfaceKind;
using geometry::TriangleMesh;

RecoveredContact fromClosedForm(ContactVolume cv, Representation kind, double max_residual) {
  RecoveredContact r{cv, kind, "", 0.0, {}, 0, true, {}};
  const double method_error = std::isfinite(cv.relative_error) ? cv.relative_error : 1e-12;
  r.volume_error_bound = cv.area * max_residual + cv.volume * method_error;
  return r;
}

RecoveredContact onMesh(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                        const Eigen::Isometry3d& X_WH, std::string reason, double gap) {
  RecoveredContact r{meshHalfspaceContact(mesh, X_WM, X_WH),
                     Representation::kShape,
                     std::move(reason),
                     0.0,
                     {},
                     0,
                     true,
                     {}};
  r.volume_error_bound = r.cv.area * gap;
  return r;
}

}  // namespace

RecoveredBody::RecoveredBody(const TriangleMesh& mesh,
                             const geometry::SurfaceRecognition& recognition)
    : mesh_(mesh),
      recognition_(recognition),
      bvh_(mesh),
      gap_(recognition.surfaces.size(), 0.0),
      faceGap_(static_cast<std::size_t>(mesh.triangleCount()), 0.0) {
  // How far outside its faces the true surface may lie: the largest chord gap of any
  // recognised face (free-form faces are their own surface, gap 0).
  for (int f = 0; f < static_cast<int>(mesh.triangleCount()); ++f) {
    const int s = recognition.face_surface[f];
    faceGap_[f] = geometry::chordGap(mesh, recognition, f);
    if (s >= 0) gap_[s] = std::max(gap_[s], faceGap_[f]);
  }
  margin_ = gap_.empty() ? 0.0 : *std::max_element(gap_.begin(), gap_.end());
  if (recognition.free_form_faces > 0) return;
  std::set<int> all;
  for (int s = 0; s < static_cast<int>(recognition.surfaces.size()); ++s) all.insert(s);
  std::string reason;
  whole_ = closedForm(all, reason);
}

std::optional<RecoveredBody::ClosedForm> RecoveredBody::closedForm(const std::set<int>& touched,
                                                                   std::string& reason) const {
  if (touched.count(-1)) {
    reason = "free-form faces reach the plane";
    return std::nullopt;
  }
  std::vector<const RecognisedSurface*> curved;
  for (int s : touched)
    if (recognition_.surfaces[s].kind != SurfaceKind::kPlane)
      curved.push_back(&recognition_.surfaces[s]);
  if (curved.empty()) {
    reason = "only planes reach the plane (exact already)";
    return std::nullopt;
  }
  ClosedForm form;
  if (touched.size() == 1 && curved[0]->kind == SurfaceKind::kSphere && curved[0]->convex) {
    form.sphere = curved[0];
    return form;
  }
  std::string why;
  if (auto body = revolutionOf(mesh_, recognition_, touched, why)) {
    form.revolution = std::move(*body);
    return form;
  }
  std::ostringstream out;
  out << "the faces that reach the plane lie on";
  for (int t : touched)
    out << ' ' << (recognition_.surfaces[t].convex ? "" : "concave ")
        << geometry::surfaceKindName(recognition_.surfaces[t].kind);
  out << ", not one solid of revolution (" << why << ")";
  reason = out.str();
  return std::nullopt;
}

RecoveredContact RecoveredBody::onClosedForm(const ClosedForm& form, const Eigen::Isometry3d& X_WM,
                                             const Eigen::Isometry3d& X_WH) {
  if (const RecognisedSurface* s = form.sphere) {
    const Eigen::Isometry3d X_WS = X_WM * Eigen::Translation3d(s->point);
    return fromClosedForm(sphereHalfspace(s->radius, X_WS, X_WH), Representation::kSphere,
                          s->max_residual);
  }
  const RevolutionBody& b = form.revolution;
  ContactPatches c = revolutionHalfspacePatches(b.profile, X_WM * b.X_MR, X_WH);
  RecoveredContact r = fromClosedForm(
      c.aggregate, b.capped_cylinder ? Representation::kCylinder : Representation::kRevolution,
      b.max_residual);
  if (c.patches.size() > 1) r.patches = std::move(c.patches);  // runs apart along the axis
  return r;
}

std::optional<RecoveredContact> RecoveredBody::closedFormContact(const Eigen::Isometry3d& X_WM,
                                                                 const Eigen::Isometry3d& X_WH,
                                                                 std::string& reason) const {
  if (whole_) return onClosedForm(*whole_, X_WM, X_WH);  // the body is one closed form
  const std::set<int> touched = reachingSurfaces(X_WH.inverse() * X_WM);
  if (touched.empty()) {
    reason = "no face reaches the plane";
    return std::nullopt;
  }
  if (const std::optional<ClosedForm> form = closedForm(touched, reason))
    return onClosedForm(*form, X_WM, X_WH);
  return std::nullopt;
}

RecoveredContact RecoveredBody::halfspaceContact(const Eigen::Isometry3d& X_WM,
                                                 const Eigen::Isometry3d& X_WH) const {
  std::string reason;
  if (auto r = closedFormContact(X_WM, X_WH, reason)) return *r;
  const std::vector<int> zone = reachingFaces(X_WH.inverse() * X_WM);
  std::set<int> touched;
  for (int f : zone) touched.insert(recognition_.face_surface[f]);
  // A curved recognised surface without a closed form here: refine it around the patch.
  const bool curved = std::any_of(touched.begin(), touched.end(), [&](int s) {
    return s >= 0 && recognition_.surfaces[s].kind != SurfaceKind::kPlane;
  });
  if (curved) {
    RecoveredContact r = refinedHalfspaceContact(*this, zone, X_WM, X_WH);
    r.reason = reason;
    return r;
  }
  if (touched.empty()) return onMesh(mesh_, X_WM, X_WH, reason, 0.0);
  double gap = 0.0;  // a plane's faces have none; unknown (NaN) on free-form faces
  for (int s : touched)
    if (s >= 0) gap = std::max(gap, gap_[s]);
  if (touched.count(-1)) gap = std::numeric_limits<double>::quiet_NaN();
  return onMesh(mesh_, X_WM, X_WH, reason, gap);
}

std::set<int> RecoveredBody::reachingSurfaces(const Eigen::Isometry3d& X_HM) const {
  std::set<int> touched;
  for (int f : reachingFaces(X_HM)) touched.insert(recognition_.face_surface[f]);
  return touched;
}

std::vector<int> RecoveredBody::reachingFaces(const Eigen::Isometry3d& X_HM) const {
  // Height above the plane of a point p of M: n·p + h0, with n the plane's normal in M.
  const Eigen::Vector3d n = X_HM.linear().row(2).transpose();
  const double h0 = X_HM.translation().z();
  std::vector<int> faces;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const geometry::BvhNode& node = bvh_.nodes()[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    const double lowest = n.dot(node.center) + h0 - n.cwiseAbs().dot(node.halfExtent);
    if (lowest > margin_) continue;
    if (!node.isLeaf()) {
      stack.push_back(node.left);
      stack.push_back(node.right);
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int f = bvh_.order()[static_cast<std::size_t>(i)];
      double low = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) low = std::min(low, n.dot(mesh_.corner(f, k)) + h0);
      if (low <= margin_) faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

RecoveredSurface::RecoveredSurface(const TriangleMesh& mesh) {
  const auto start = std::chrono::steady_clock::now();
  recognition = geometry::recogniseSurfaces(mesh);
  recognition_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  body = std::make_unique<RecoveredBody>(mesh, recognition);
}

std::shared_ptr<const RecoveredSurface> recoverSurface(
    const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  return derivedOf<RecoveredSurface>(mesh);
}

const geometry::SurfaceRecognition& recognition(const RecoveredSurface& surface) {
  return surface.recognition;
}

double recognitionSeconds(const RecoveredSurface& surface) { return surface.recognition_seconds; }

std::string recognisedKinds(const geometry::SurfaceRecognition& recognition) {
  std::map<std::string, int> counts;
  for (const RecognisedSurface& s : recognition.surfaces) {
    ++counts[std::string(s.convex ? "" : "concave ") + geometry::surfaceKindName(s.kind)];
  }
  std::ostringstream out;
  const char* sep = "";
  for (const auto& [kind, n] : counts) {
    out << sep << n << ' ' << kind << (n > 1 ? "s" : "");
    sep = ", ";
  }
  if (recognition.free_form_faces > 0) {
    out << sep << recognition.free_form_faces << " free-form faces";
  } else if (counts.empty()) {
    out << "nothing";
  }
  return out.str();
}

RecoveredContact recoveredHalfspaceContact(const TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const Eigen::Isometry3d& X_WM,
                                           const Eigen::Isometry3d& X_WH) {
  return RecoveredBody(mesh, recognition).halfspaceContact(X_WM, X_WH);
}

}  // namespace vcontact::volume
