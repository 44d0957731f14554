#include "volume/halfspace_clip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vcontact::volume {
namespace {

using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;

/// Point where the edge from a (inside, z < 0) to b (outside, z ≥ 0) crosses z = 0.
Vector3d crossing(const Vector3d& a, const Vector3d& b) {
  const double t = a.z() / (a.z() - b.z());
  Vector3d p = a + t * (b - a);
  p.z() = 0.0;  // exactly on the plane, so the cap contributes nothing
  return p;
}

/// Running sums over the fan pieces (o, a, b, c), corners relative to o: with
/// D = a·(b × c) and s = a + b + c, the moments about o are m0 = ΣD/6, m1 = Σ D s/24 and
/// m2 = Σ D (a aᵀ + b bᵀ + c cᵀ + s sᵀ)/120 (as tetrahedronMoments, kept as plain sums
/// because this is the inner loop of the clip).
struct FanSum {
  double D = 0.0;
  Vector3d Ds = Vector3d::Zero();
  Eigen::Matrix3d DQ = Eigen::Matrix3d::Zero();
  double area = 0.0;  ///< projected area of the downward-facing pieces

  /// Adds the tetrahedron (o, a, b, c) and the shadow of the face (a, b, c) if it faces down.
  void add(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    const Vector3d bc = b.cross(c);
    const double d = a.dot(bc);
    const Vector3d sum = a + b + c;
    D += d;
    Ds += d * sum;
    DQ.noalias() +=
        d * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
    const double nz2 = (b - a).cross(c - a).z();  // 2 × signed projected area
    if (nz2 < 0.0) area -= 0.5 * nz2;
  }

  void addTo(ClippedMoments& out) const {
    out.moments.m0 += D / 6.0;
    out.moments.m1 += Ds / 24.0;
    out.moments.m2 += DQ / 120.0;
    out.area += area;
  }
};

/// Adds the part of the triangle v (corners relative to o, H axes) below z = 0 as fan pieces
/// with apex o (MODEL.md §1: the region is mesh ∩ {z_H ≤ 0}).
void clipTriangle(const Vector3d (&v)[3], FanSum& out) {
  const int inside = (v[0].z() < 0.0) + (v[1].z() < 0.0) + (v[2].z() < 0.0);
  if (inside == 0) return;
  if (inside == 3) {
    out.add(v[0], v[1], v[2]);
    return;
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
    out.add(a, crossing(a, b), crossing(a, c));
  } else {
    const Vector3d pb = crossing(b, a), pc = crossing(c, a);
    out.add(pb, b, c);
    out.add(pb, c, pc);
  }
}

// A box is treated as wholly on one side only when its z-range clears the plane by more than
// the rounding of the range itself (a few ulps of the coordinates); closer boxes are opened
// and their triangles clipped one by one exactly as the reference does.
constexpr double kBoxRoundingUlps = 16.0;

/// Traversal state of the accelerated clip.
class BvhClip {
 public:
  BvhClip(const MeshBvh& bvh, const Eigen::Isometry3d& X_HM)
      : bvh_(bvh), X_HM_(X_HM), R_HM_(X_HM.linear()), z_M_(R_HM_.row(2).transpose()) {}

  ClippedMoments run() {
    ClippedMoments out;
    collect(bvh_.root());
    // The lowest vertex lies in a collected node (it is below the plane when there is
    // contact); search only those, the lowest-reaching first.
    double best = std::numeric_limits<double>::infinity();
    for (const BvhNode* node : below_) best = deepestZ(*node, best);
    for (const BvhNode* node : straddling_) best = deepestZ(*node, best);
    if (!(best < 0.0)) return out;
    out.depth = -best;
    out.origin = Vector3d(deepest_.x(), deepest_.y(), 0.0);
    o_H_ = out.origin;
    for (const BvhNode* node : below_) addWholeNode(*node, out);
    FanSum clipped;
    for (const BvhNode* node : straddling_) clipLeaf(*node, clipped);
    clipped.addTo(out);
    // Wholly-below subtrees were summed about o in M axes; rotate them into H once.
    const Vector3d m1_H = R_HM_ * belowInM_.m1;
    out.moments.m0 += belowInM_.m0;
    out.moments.m1 += m1_H;
    out.moments.m2 += R_HM_ * belowInM_.m2 * R_HM_.transpose();
    return out;
  }

  struct ZRange {
    double lo, hi;
  };

  /// Bounds of z_H over the node's vertices: the tighter of its box and its normal slab.
  /// With z_M = the plane normal in M, split into a part along the slab axis a and the rest:
  /// (p − c)·z_M = (z_M·a) s + (p − c)·z_⊥ with s ∈ [axialLo, axialHi], |…| ≤ |z_⊥| ρ.
  ZRange zRange(const BvhNode& node) const {
    const double cz = (X_HM_ * node.center).z();
    const double boxExtent = z_M_.cwiseAbs().dot(node.halfExtent);
    const double za = z_M_.dot(node.normalAxis);
    const double perp = std::sqrt(std::max(0.0, 1.0 - za * za)) * node.radialExtent;
    const double slabLo = std::min(za * node.axialLo, za * node.axialHi) - perp;
    const double slabHi = std::max(za * node.axialLo, za * node.axialHi) + perp;
    const double slack = kBoxRoundingUlps * std::numeric_limits<double>::epsilon() *
                         (std::abs(cz) + boxExtent + X_HM_.translation().cwiseAbs().sum());
    return {cz + std::max(-boxExtent, slabLo) - slack, cz + std::min(boxExtent, slabHi) + slack};
  }

  Vector3d corner_H(int f, int k) const { return X_HM_ * bvh_.mesh().corner(f, k); }

  /// Branch and bound for the lowest vertex; returns the best z so far.
  double deepestZ(const BvhNode& node, double best) {
    return deepestZ(node, zRange(node).lo, best);
  }

  /// The same with the node's lower bound `lo` already known (each bound computed once).
  double deepestZ(const BvhNode& node, double lo, double best) {
    if (lo >= best) return best;
    if (node.isLeaf()) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        for (int k = 0; k < 3; ++k) {
          const Vector3d p = corner_H(bvh_.order()[i], k);
          if (p.z() < best) {
            best = p.z();
            deepest_ = p;
          }
        }
      }
      return best;
    }
    const BvhNode& l = bvh_.nodes()[node.left];
    const BvhNode& r = bvh_.nodes()[node.right];
    const double loL = zRange(l).lo, loR = zRange(r).lo;
    if (loL <= loR) return deepestZ(r, loR, deepestZ(l, loL, best));
    return deepestZ(l, loL, deepestZ(r, loR, best));
  }

  /// Sorts the tree into subtrees wholly below the plane and leaves that straddle it;
  /// subtrees wholly above are dropped.
  void collect(const BvhNode& node) {
    const ZRange z = zRange(node);
    if (z.lo >= 0.0) return;
    if (z.hi < 0.0) {
      below_.push_back(&node);
    } else if (node.isLeaf()) {
      straddling_.push_back(&node);
    } else {
      collect(bvh_.nodes()[node.left]);
      collect(bvh_.nodes()[node.right]);
    }
  }

  void clipLeaf(const BvhNode& node, FanSum& out) const {
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int f = bvh_.order()[i];
      const Vector3d v[3] = {corner_H(f, 0) - o_H_, corner_H(f, 1) - o_H_, corner_H(f, 2) - o_H_};
      clipTriangle(v, out);
    }
  }

  /// Fan moments about o of a subtree wholly below the plane, in M axes:
  /// δ_M = R_HMᵀ (X_HM r − o) (fan_integrals.hpp).
  void addWholeNode(const BvhNode& node, ClippedMoments& out) {
    const Vector3d delta_M = R_HM_.transpose() * (X_HM_ * node.center - o_H_);
    belowInM_ += geometry::fanMoments(node.integrals, delta_M);
    out.area += downwardArea(node);
  }

  /// Projected area onto z_H = 0 of the node's faces with n_z < 0: −(R_HM ∫n dA)_z when the
  /// normal cone lies wholly below the horizontal, 0 when wholly above, else per child.
  double downwardArea(const BvhNode& node) const {
    const double axisZ = R_HM_.row(2).dot(node.normalAxis);
    if (axisZ <= -node.normalSinHalfAngle) return -R_HM_.row(2).dot(node.integrals.F);
    if (axisZ >= node.normalSinHalfAngle) return 0.0;
    if (!node.isLeaf()) {
      return downwardArea(bvh_.nodes()[node.left]) + downwardArea(bvh_.nodes()[node.right]);
    }
    double area = 0.0;
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int f = bvh_.order()[i];
      const Vector3d a = corner_H(f, 0);
      const double nz2 = (corner_H(f, 1) - a).cross(corner_H(f, 2) - a).z();
      if (nz2 < 0.0) area -= 0.5 * nz2;
    }
    return area;
  }

  const MeshBvh& bvh_;
  const Eigen::Isometry3d X_HM_;
  const Eigen::Matrix3d R_HM_;
  const Vector3d z_M_;  ///< the plane's normal z_H in M
  Vector3d deepest_ = Vector3d::Zero();
  Vector3d o_H_ = Vector3d::Zero();
  geometry::Moments belowInM_;
  std::vector<const BvhNode*> below_, straddling_;
};

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
  FanSum sum;
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    Vector3d v[3];
    for (int k = 0; k < 3; ++k) v[k] = p_H.row(mesh.triangles(f, k)).transpose() - o;
    clipTriangle(v, sum);
  }
  sum.addTo(out);
  return out;
}

ClippedMoments clipMeshByHalfspace(const MeshBvh& bvh, const Eigen::Isometry3d& X_HM) {
  return BvhClip(bvh, X_HM).run();
}

ContactVolume contactFromClippedMoments(const ClippedMoments& clipped,
                                        const Eigen::Isometry3d& X_WH, Method method) {
  const geometry::Moments& M = clipped.moments;
  if (!(M.m0 > 0.0)) return ContactVolume{.method = method};
  const Vector3d c_o = M.m1 / M.m0;  // centroid relative to o, H axes
  const Eigen::Matrix3d Sigma_H = M.m2 - M.m0 * c_o * c_o.transpose();
  const Eigen::Matrix3d R_WH = X_WH.linear();
  ContactVolume cv = assembleContactVolume(M.m0, X_WH * clipped.origin + R_WH * c_o,
                                           R_WH * Sigma_H * R_WH.transpose(), R_WH.col(2),
                                           clipped.area, clipped.depth, method);
  return cv;
}

ContactVolume meshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                   const Eigen::Isometry3d& X_WM, const Eigen::Isometry3d& X_WH) {
  return contactFromClippedMoments(clipMeshByHalfspace(mesh, X_WH.inverse() * X_WM), X_WH,
                                   Method::kHalfspace);
}

ContactVolume meshHalfspaceContact(const MeshBvh& bvh, const Eigen::Isometry3d& X_WM,
                                   const Eigen::Isometry3d& X_WH) {
  return contactFromClippedMoments(clipMeshByHalfspace(bvh, X_WH.inverse() * X_WM), X_WH,
                                   Method::kHalfspace);
}

}  // namespace vcontact::volume
