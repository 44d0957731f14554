#include "volume/recovered_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "volume/analytic.hpp"
#include "volume/halfspace_clip.hpp"

namespace vcontact::volume {
namespace {

using geometry::RecognisedSurface;
using geometry::SurfaceKind;
using geometry::TriangleMesh;

// The largest distance between face f's chord and the surface it lies on, estimated at the
// centroid and the edge midpoints (for a face inscribed in a convex surface, the gap is
// largest inside the face, near its circumcentre).
double chordGap(const TriangleMesh& mesh, int f, const RecognisedSurface& s) {
  const Eigen::Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
  const Eigen::Vector3d probes[] = {(a + b + c) / 3.0, (a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0};
  double gap = 0.0;
  for (const Eigen::Vector3d& p : probes) gap = std::max(gap, std::abs(signedDistance(s, p)));
  return gap;
}

// Heights of the vertices above the half-space's boundary, m.
std::vector<double> heights(const TriangleMesh& mesh, const Eigen::Isometry3d& X_HM) {
  std::vector<double> h(static_cast<std::size_t>(mesh.vertexCount()));
  for (Eigen::Index v = 0; v < mesh.vertexCount(); ++v) h[v] = (X_HM * mesh.vertex(v)).z();
  return h;
}

// The faces that can reach the plane: the true surface lies within `margin` outside them.
std::vector<int> reachingFaces(const TriangleMesh& mesh, const std::vector<double>& h,
                               double margin) {
  std::vector<int> faces;
  for (int f = 0; f < static_cast<int>(mesh.triangleCount()); ++f) {
    const double low =
        std::min({h[mesh.triangles(f, 0)], h[mesh.triangles(f, 1)], h[mesh.triangles(f, 2)]});
    if (low <= margin) faces.push_back(f);
  }
  return faces;
}

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

RecoveredContact onSurface(ContactVolume cv, const char* kind, const RecognisedSurface& s) {
  RecoveredContact r{cv, kind, "", 0.0};
  const double method_error = std::isfinite(cv.relative_error) ? cv.relative_error : 1e-12;
  r.volume_error_bound = cv.area * s.max_residual + cv.volume * method_error;
  return r;
}

RecoveredContact sphereContact(const RecognisedSurface& s, const Eigen::Isometry3d& X_WM,
                               const Eigen::Isometry3d& X_WH) {
  const Eigen::Isometry3d X_WS = X_WM * Eigen::Translation3d(s.point);
  return onSurface(sphereHalfspace(s.radius, X_WS, X_WH), "sphere", s);
}

RecoveredContact cylinderContact(const TriangleMesh& mesh, const RecognisedSurface& c,
                                 const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH) {
  const auto [lo, hi] = axialExtent(mesh, c);
  Eigen::Isometry3d X_MC = Eigen::Isometry3d::Identity();
  X_MC.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), c.axis).toRotationMatrix();
  X_MC.translation() = c.point + c.axis * (0.5 * (lo + hi));
  return onSurface(cylinderHalfspace(c.radius, hi - lo, X_WM * X_MC, X_WH), "cylinder", c);
}

RecoveredContact onMesh(const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                        const Eigen::Isometry3d& X_WH, std::string reason, double gap) {
  RecoveredContact r{meshHalfspaceContact(mesh, X_WM, X_WH), "mesh", std::move(reason), 0.0};
  r.volume_error_bound = r.cv.area * gap;
  return r;
}

}  // namespace

RecoveredContact recoveredHalfspaceContact(const TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const Eigen::Isometry3d& X_WM,
                                           const Eigen::Isometry3d& X_WH) {
  // How far outside its faces the true surface may lie: the largest chord gap of any
  // recognised face (free-form faces are their own surface, gap 0).
  std::vector<double> gap(recognition.surfaces.size(), 0.0);
  for (int f = 0; f < static_cast<int>(mesh.triangleCount()); ++f) {
    const int s = recognition.face_surface[f];
    if (s >= 0) gap[s] = std::max(gap[s], chordGap(mesh, f, recognition.surfaces[s]));
  }
  const double margin = gap.empty() ? 0.0 : *std::max_element(gap.begin(), gap.end());
  const std::vector<int> reaching =
      reachingFaces(mesh, heights(mesh, X_WH.inverse() * X_WM), margin);
  std::set<int> touched;
  for (int f : reaching) touched.insert(recognition.face_surface[f]);
  double reach_gap = 0.0;
  for (int s : touched) reach_gap = std::max(reach_gap, s >= 0 ? gap[s] : 0.0);
  if (touched.empty()) return onMesh(mesh, X_WM, X_WH, "no face reaches the plane", 0.0);
  if (touched.count(-1))
    return onMesh(mesh, X_WM, X_WH, "free-form faces reach the plane",
                  std::numeric_limits<double>::quiet_NaN());

  // One convex sphere, or one convex cylinder with the flat ends that close it.
  const RecognisedSurface* curved = nullptr;
  for (int s : touched) {
    const RecognisedSurface& surface = recognition.surfaces[s];
    if (surface.kind == SurfaceKind::kPlane) continue;
    if (curved || !surface.convex ||
        (surface.kind != SurfaceKind::kSphere && surface.kind != SurfaceKind::kCylinder)) {
      std::ostringstream why;
      why << "the faces that reach the plane lie on";
      for (int t : touched)
        why << ' ' << (recognition.surfaces[t].convex ? "" : "concave ")
            << geometry::surfaceKindName(recognition.surfaces[t].kind);
      why << ", which has no closed form against a plane";
      return onMesh(mesh, X_WM, X_WH, why.str(), reach_gap);
    }
    curved = &surface;
  }
  if (!curved) return onMesh(mesh, X_WM, X_WH, "only planes reach the plane (exact already)", 0.0);
  if (curved->kind == SurfaceKind::kSphere && touched.size() == 1)
    return sphereContact(*curved, X_WM, X_WH);
  if (curved->kind == SurfaceKind::kCylinder) {
    const auto ends = axialExtent(mesh, *curved);
    const bool capped = std::all_of(touched.begin(), touched.end(), [&](int s) {
      const RecognisedSurface& t = recognition.surfaces[s];
      return &t == curved || isEndCap(t, *curved, ends, recognition.tolerance);
    });
    if (capped) return cylinderContact(mesh, *curved, X_WM, X_WH);
  }
  return onMesh(mesh, X_WM, X_WH,
                "a curved surface and planes that do not close it reach the plane", reach_gap);
}

}  // namespace vcontact::volume
