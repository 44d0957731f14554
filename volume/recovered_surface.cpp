#include "volume/recovered_surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "geometry/surface_refinement.hpp"
#include "volume/analytic.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/recovered_refinement.hpp"

namespace vcontact::volume {
namespace {

using geometry::RecognisedSurface;
using geometry::SurfaceKind;
using geometry::TriangleMesh;

// The extent [lo, hi] of a cylinder's vertices along its axis, from its axis point.
std::pair<double, double> axialExtent(const TriangleMesh& mesh, const RecognisedSurface& c) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int f : c.faces)
    for (int k = 0; k < 3; ++k) {
      const double t = c.axis.dot(mesh.corner(f, k) - c.point);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
  return {lo, hi};
}

// True when plane p closes cylinder c at one of its ends [lo, hi].
bool isEndCap(const RecognisedSurface& p, const RecognisedSurface& c,
              std::pair<double, double> ends, double tolerance) {
  if (p.kind != SurfaceKind::kPlane || std::abs(std::abs(p.axis.dot(c.axis)) - 1.0) > 1e-9)
    return false;
  const double t = c.axis.dot(p.point - c.point);
  return std::abs(t - ends.first) <= tolerance || std::abs(t - ends.second) <= tolerance;
}

RecoveredContact fromClosedForm(ContactVolume cv, const char* kind, const RecognisedSurface& s) {
  RecoveredContact r{cv, kind, "", 0.0, {}, 0, true};
  const double method_error = std::isfinite(cv.relative_error) ? cv.relative_error : 1e-12;
  r.volume_error_bound = cv.area * s.max_residual + cv.volume * method_error;
  return r;
}

RecoveredContact sphereContact(const RecognisedSurface& s, const Eigen::Isometry3d& X_WM,
                               const Eigen::Isometry3d& X_WH) {
  const Eigen::Isometry3d X_WS = X_WM * Eigen::Translation3d(s.point);
  return fromClosedForm(sphereHalfspace(s.radius, X_WS, X_WH), "sphere", s);
}

RecoveredContact cylinderContact(const TriangleMesh& mesh, const RecognisedSurface& c,
                                 const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH) {
  const auto [lo, hi] = axialExtent(mesh, c);
  Eigen::Isometry3d X_MC = Eigen::Isometry3d::Identity();
  X_MC.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), c.axis).toRotationMatrix();
  X_MC.translation() = c.point + c.axis * (0.5 * (lo + hi));
  return fromClosedForm(cylinderHalfspace(c.radius, hi - lo, X_WM * X_MC, X_WH), "cylinder", c);
}

RecoveredContact onMesh(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                        const Eigen::Isometry3d& X_WH, std::string reason, double gap) {
  RecoveredContact r{
      meshHalfspaceContact(mesh, X_WM, X_WH), "mesh", std::move(reason), 0.0, {}, 0, true};
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
  whole_ = closedFormSurface(all, reason);
}

const RecognisedSurface* RecoveredBody::closedFormSurface(const std::set<int>& touched,
                                                          std::string& reason) const {
  if (touched.count(-1)) {
    reason = "free-form faces reach the plane";
    return nullptr;
  }
  // One convex sphere, or one convex cylinder with the flat ends that close it.
  const RecognisedSurface* curved = nullptr;
  for (int s : touched) {
    const RecognisedSurface& surface = recognition_.surfaces[s];
    if (surface.kind == SurfaceKind::kPlane) continue;
    if (curved || !surface.convex ||
        (surface.kind != SurfaceKind::kSphere && surface.kind != SurfaceKind::kCylinder)) {
      std::ostringstream why;
      why << "the faces that reach the plane lie on";
      for (int t : touched)
        why << ' ' << (recognition_.surfaces[t].convex ? "" : "concave ")
            << geometry::surfaceKindName(recognition_.surfaces[t].kind);
      why << ", which has no closed form against a plane";
      reason = why.str();
      return nullptr;
    }
    curved = &surface;
  }
  if (!curved) {
    reason = "only planes reach the plane (exact already)";
    return nullptr;
  }
  if (curved->kind == SurfaceKind::kSphere && touched.size() == 1) return curved;
  if (curved->kind == SurfaceKind::kCylinder) {
    const auto ends = axialExtent(mesh_, *curved);
    const bool capped = std::all_of(touched.begin(), touched.end(), [&](int s) {
      const RecognisedSurface& t = recognition_.surfaces[s];
      return &t == curved || isEndCap(t, *curved, ends, recognition_.tolerance);
    });
    if (capped) return curved;
  }
  reason = "a curved surface and planes that do not close it reach the plane";
  return nullptr;
}

RecoveredContact RecoveredBody::onSurface(const RecognisedSurface& s, const Eigen::Isometry3d& X_WM,
                                          const Eigen::Isometry3d& X_WH) const {
  return s.kind == SurfaceKind::kSphere ? sphereContact(s, X_WM, X_WH)
                                        : cylinderContact(mesh_, s, X_WM, X_WH);
}

std::optional<RecoveredContact> RecoveredBody::closedFormContact(const Eigen::Isometry3d& X_WM,
                                                                 const Eigen::Isometry3d& X_WH,
                                                                 std::string& reason) const {
  if (whole_) return onSurface(*whole_, X_WM, X_WH);  // the body is one closed form
  const std::set<int> touched = reachingSurfaces(X_WH.inverse() * X_WM);
  if (touched.empty()) {
    reason = "no face reaches the plane";
    return std::nullopt;
  }
  if (const RecognisedSurface* s = closedFormSurface(touched, reason))
    return onSurface(*s, X_WM, X_WH);
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

std::shared_ptr<const RecoveredSurface> recoverSurface(
    std::shared_ptr<const geometry::TriangleMesh> mesh) {
  auto r = std::make_shared<RecoveredSurface>();
  r->mesh = std::move(mesh);
  const auto start = std::chrono::steady_clock::now();
  r->recognition = geometry::recogniseSurfaces(*r->mesh);
  r->recognition_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // r is not moved from here on, so the body's references to its mesh and recognition hold
  r->body = std::make_unique<RecoveredBody>(*r->mesh, r->recognition);
  return r;
}

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
