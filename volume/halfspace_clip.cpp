#include "volume/halfspace_clip.hpp"

#include <algorithm>
#include <limits>

namespace vcontact::volume {
namespace {

using Eigen::Vector3d;

/// Point where the edge from a (inside, z < 0) to b (outside, z ≥ 0) crosses z = 0.
Vector3d crossing(const Vector3d& a, const Vector3d& b) {
  const double t = a.z() / (a.z() - b.z());
  Vector3d p = a + t * (b - a);
  p.z() = 0.0;  // exactly on the plane, so the cap contributes nothing
  return p;
}

/// Adds the tetrahedron (o, a, b, c) and the shadow of the face (a, b, c) if it faces down.
void addPiece(const Vector3d& o, const Vector3d& a, const Vector3d& b, const Vector3d& c,
              ClippedMoments& out) {
  out.moments += geometry::tetrahedronMoments(o, a, b, c);
  const double nz2 = (b - a).cross(c - a).z();  // 2 × signed projected area
  if (nz2 < 0.0) out.area -= 0.5 * nz2;
}

}  // namespace

ClippedMoments clipMeshByHalfspace(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_HM) {
  const Eigen::Index n = mesh.vertexCount();
  geometry::Vertices p_H(n, 3);
  Eigen::Index deepest = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    p_H.row(i) = (X_HM * mesh.vertex(i)).transpose();
    if (p_H(i, 2) < p_H(deepest, 2)) deepest = i;
  }
  ClippedMoments out;
  if (n == 0) return out;
  out.depth = -p_H(deepest, 2);
  if (out.depth <= 0.0) return out;
  const Vector3d o(p_H(deepest, 0), p_H(deepest, 1), 0.0);
  out.origin = o;
  const Vector3d zero = Vector3d::Zero();

  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    Vector3d v[3];
    int inside = 0;
    for (int k = 0; k < 3; ++k) {
      v[k] = p_H.row(mesh.triangles(f, k)).transpose() - o;
      inside += v[k].z() < 0.0;
    }
    if (inside == 0) continue;
    if (inside == 3) {
      addPiece(zero, v[0], v[1], v[2], out);
      continue;
    }
    // Rotate so that the lone vertex (inside when inside == 1, outside when 2) comes first;
    // the cyclic order, and with it the orientation, is kept.
    const bool loneInside = inside == 1;
    int k0 = 0;
    while ((v[k0].z() < 0.0) != loneInside) ++k0;
    const Vector3d& a = v[k0];
    const Vector3d& b = v[(k0 + 1) % 3];
    const Vector3d& c = v[(k0 + 2) % 3];
    if (loneInside) {
      addPiece(zero, a, crossing(a, b), crossing(a, c), out);
    } else {
      const Vector3d pb = crossing(b, a), pc = crossing(c, a);
      addPiece(zero, pb, b, c, out);
      addPiece(zero, pb, c, pc, out);
    }
  }
  return out;
}

ContactVolume contactFromClippedMoments(const ClippedMoments& clipped,
                                        const Eigen::Isometry3d& X_WH, Method method) {
  const geometry::Moments& M = clipped.moments;
  if (!(M.m0 > 0.0)) return ContactVolume{.method = method};
  const Vector3d c_o = M.m1 / M.m0;  // centroid relative to o, H axes
  const Eigen::Matrix3d Sigma_H = M.m2 - M.m0 * c_o * c_o.transpose();
  const Eigen::Matrix3d R_WH = X_WH.linear();
  ContactVolume cv = assembleContactVolume(M.m0, X_WH * clipped.origin + R_WH * c_o,
                                           R_WH * Sigma_H * R_WH.transpose(),
                                           R_WH.col(2), clipped.area, clipped.depth, method);
  return cv;
}

ContactVolume meshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_WM,
                                   const Eigen::Isometry3d& X_WH) {
  return contactFromClippedMoments(clipMeshByHalfspace(mesh, X_WH.inverse() * X_WM), X_WH,
                                   Method::kHalfspace);
}

}  // namespace vcontact::volume
