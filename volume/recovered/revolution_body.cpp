#include "volume/recovered/revolution_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace vcontact::volume {
namespace {

using Eigen::Vector3d;
using geometry::RecognisedSurface;
using geometry::SurfaceKind;
using geometry::TriangleMesh;
using Kind = ProfilePiece::Kind;

// Axes agree when |cos| of their angle is within this of 1 (4.5e-5 rad, as the capped
// cylinder's end caps were checked): recognition fixes an axis to ~1e-9 of the part's size.
constexpr double kParallel = 1e-9;
// Points lie on the axis, and pieces meet, within this many vertex tolerances.
constexpr double kTolerances = 10.0;

struct Axis {
  Vector3d point, dir;
  double along(const Vector3d& p) const { return dir.dot(p - point); }
  Vector3d radial(const Vector3d& p) const { return (p - point) - dir * along(p); }
};

bool parallel(const Vector3d& a, const Vector3d& b) {
  return std::abs(std::abs(a.dot(b)) - 1.0) <= kParallel;
}

// The bands [lo, hi] of a surface's faces along the axis, ascending: the extents of its faces
// merged where they overlap or meet within tol. One band, the extent of its vertices, for a
// surface in one piece; several for one whose faces lie apart along the axis (the two collars
// of a spool on one cylinder, the flanges of a pulley), each a piece of the profile.
std::vector<std::pair<double, double>> bands(const TriangleMesh& mesh, const RecognisedSurface& s,
                                             const Axis& axis, double tol) {
  std::vector<std::pair<double, double>> faces;
  for (int f : s.faces) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k = 0; k < 3; ++k) {
      const double t = axis.along(mesh.corner(f, k));
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    faces.emplace_back(lo, hi);
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::pair<double, double>> out;
  for (const auto& [lo, hi] : faces) {
    if (!out.empty() && lo <= out.back().second + tol) {
      out.back().second = std::max(out.back().second, hi);
    } else {
      out.emplace_back(lo, hi);
    }
  }
  return out;
}

// True when every face of s turns away from the axis (the solid lies inside r(ζ)).
bool facesOutward(const TriangleMesh& mesh, const RecognisedSurface& s, const Axis& axis) {
  return std::all_of(s.faces.begin(), s.faces.end(), [&](int f) {
    const Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    return (b - a).cross(c - a).dot(axis.radial((a + b + c) / 3.0)) > 0.0;
  });
}

// The piece of curved surface s over the band [lo, hi] of the axis.
ProfilePiece pieceOf(const TriangleMesh& mesh, const RecognisedSurface& s, const Axis& axis,
                     double lo, double hi) {
  ProfilePiece p;
  p.z0 = lo;
  p.z1 = hi;
  const double zc = axis.along(s.point);
  switch (s.kind) {
    case SurfaceKind::kCylinder:
      p.r0 = p.r1 = s.radius;
      break;
    case SurfaceKind::kCone: {  // r = tan(angle)·(distance from the apex along its axis)
      const double k = std::tan(s.angle) * (s.axis.dot(axis.dir) > 0.0 ? 1.0 : -1.0);
      p.kind = Kind::kLinear;
      p.r0 = k * (lo - zc);
      p.r1 = k * (hi - zc);
      break;
    }
    default: {  // sphere, torus: an arc about (ρ_c, z_c); a torus' inner half has sign −1
      p.kind = Kind::kArc;
      p.z_c = zc;
      p.rho_c = s.kind == SurfaceKind::kTorus ? s.radius : 0.0;
      p.a = s.kind == SurfaceKind::kTorus ? s.minor_radius : s.radius;
      double mean = 0.0;
      for (int f : s.faces) mean += axis.radial(mesh.corner(f, 0)).norm() / s.faces.size();
      p.sign = mean >= p.rho_c ? 1.0 : -1.0;
      p.z0 = std::max(lo, zc - p.a);
      p.z1 = std::min(hi, zc + p.a);
    }
  }
  return p;
}

// The pieces a curved surface contributes (one per band), ζ from the axis point; none when s is
// off the axis (reason set).
std::optional<std::vector<ProfilePiece>> piecesOf(const TriangleMesh& mesh,
                                                  const RecognisedSurface& s, const Axis& axis,
                                                  double tol, std::string& reason) {
  const bool hasAxis = s.kind != SurfaceKind::kSphere;
  if ((hasAxis && !parallel(s.axis, axis.dir)) || axis.radial(s.point).norm() > tol) {
    reason = std::string("a ") + geometry::surfaceKindName(s.kind) + " off the common axis";
    return std::nullopt;
  }
  if (!facesOutward(mesh, s, axis)) {
    reason = std::string("a ") + geometry::surfaceKindName(s.kind) + " facing its axis (a bore)";
    return std::nullopt;
  }
  std::vector<ProfilePiece> out;
  for (const auto& [lo, hi] : bands(mesh, s, axis, tol))
    out.push_back(pieceOf(mesh, s, axis, lo, hi));
  return out;
}

// Moves a piece's ends to [z0, z1], a cone's radii along with them.
void moveEnd(ProfilePiece& p, double z0, double z1) {
  if (p.kind == Kind::kLinear) {
    const double k = (p.r1 - p.r0) / (p.z1 - p.z0);
    const double r0 = p.r0 + k * (z0 - p.z0), r1 = p.r0 + k * (z1 - p.z0);
    p.r0 = r0;
    p.r1 = r1;
  }
  p.z0 = z0;
  p.z1 = z1;
}

// The pieces in order, meeting at shared ends, every radius step closed by a plane.
bool assemble(std::vector<ProfilePiece>& pieces, const std::vector<double>& planes, double tol,
              std::string& reason) {
  std::sort(pieces.begin(), pieces.end(),
            [](const ProfilePiece& a, const ProfilePiece& b) { return a.z0 < b.z0; });
  std::vector<double> breaks = {pieces.front().z0};
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    if (std::abs(pieces[i].z1 - pieces[i + 1].z0) > tol) {
      reason = "the surfaces of revolution do not follow one another along their axis";
      return false;
    }
    const double z = 0.5 * (pieces[i].z1 + pieces[i + 1].z0);
    moveEnd(pieces[i], pieces[i].z0, z);
    moveEnd(pieces[i + 1], z, pieces[i + 1].z1);
    const double below = pieces[i].kind == Kind::kArc ? profileRadius(pieces[i], z) : pieces[i].r1;
    const double above =
        pieces[i + 1].kind == Kind::kArc ? profileRadius(pieces[i + 1], z) : pieces[i + 1].r0;
    breaks.push_back(z);
    const bool closed =
        std::any_of(planes.begin(), planes.end(), [&](double p) { return std::abs(p - z) <= tol; });
    if (std::abs(below - above) > tol && !closed) {
      reason = "a step in the radius that no plane closes";
      return false;
    }
  }
  breaks.push_back(pieces.back().z1);
  for (double p : planes)
    if (std::none_of(breaks.begin(), breaks.end(),
                     [&](double z) { return std::abs(p - z) <= tol; })) {
      reason = "a plane across the axis away from the ends of the surfaces of revolution";
      return false;
    }
  return true;
}

}  // namespace

std::optional<RevolutionBody> revolutionOf(const TriangleMesh& mesh,
                                           const geometry::SurfaceRecognition& recognition,
                                           const std::set<int>& surfaces, std::string& reason) {
  if (surfaces.count(-1)) {
    reason = "free-form faces reach the plane";
    return std::nullopt;
  }
  const RecognisedSurface* first = nullptr;  // the first surface with an axis gives it
  for (int s : surfaces) {
    const SurfaceKind k = recognition.surfaces[s].kind;
    if (!first && k != SurfaceKind::kPlane && k != SurfaceKind::kSphere)
      first = &recognition.surfaces[s];
  }
  if (!first) {
    reason = "no cylinder, cone or torus gives an axis";
    return std::nullopt;
  }
  const Axis axis{first->point, first->axis};  // unit, as recognition gives it
  const double tol = kTolerances * recognition.tolerance;
  RevolutionBody body;
  std::vector<ProfilePiece> pieces;
  std::vector<double> planes;
  for (int index : surfaces) {
    const RecognisedSurface& s = recognition.surfaces[index];
    body.max_residual = std::max(body.max_residual, s.max_residual);
    if (s.kind == SurfaceKind::kPlane) {
      if (!parallel(s.axis, axis.dir)) {
        reason = "a plane not perpendicular to the axis of the surfaces of revolution";
        return std::nullopt;
      }
      planes.push_back(axis.along(s.point));
      continue;
    }
    const std::optional<std::vector<ProfilePiece>> p = piecesOf(mesh, s, axis, tol, reason);
    if (!p) return std::nullopt;
    pieces.insert(pieces.end(), p->begin(), p->end());
  }
  if (!assemble(pieces, planes, tol, reason)) return std::nullopt;
  // The frame: origin on the axis at the middle of the extent, as the capped cylinder had it.
  const double lo = pieces.front().z0, hi = pieces.back().z1, mid = 0.5 * (lo + hi);
  body.X_MR.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), first->axis).toRotationMatrix();
  body.X_MR.translation() = first->point + first->axis * mid;
  body.capped_cylinder = pieces.size() == 1 && pieces[0].kind == Kind::kConstant;
  if (body.capped_cylinder) {
    body.profile = cylinderProfile(pieces[0].r0, hi - lo);
    return body;
  }
  for (ProfilePiece& p : pieces) {
    p.z0 -= mid;
    p.z1 -= mid;
    p.z_c -= mid;
  }
  body.profile = std::move(pieces);
  return body;
}

}  // namespace vcontact::volume
