#include "geometry/surface_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace vcontact::geometry {
namespace {

std::uint64_t edgeKey(int u, int w) {
  const auto lo = static_cast<std::uint32_t>(std::min(u, w));
  const auto hi = static_cast<std::uint32_t>(std::max(u, w));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

bool isCurved(const SurfaceRecognition& r, int f) {
  const int s = r.face_surface[static_cast<std::size_t>(f)];
  return s >= 0 && r.surfaces[static_cast<std::size_t>(s)].kind != SurfaceKind::kPlane;
}

// Alternating projections onto the two surfaces of a crease: at most this many rounds, until
// the point lies on both within kAgreement of the recognition tolerance (two surfaces crossing
// at angle θ converge by cos²θ a round: a 45° chamfer on its plane by 1/2, so 60 rounds take a
// chord gap of 1e-3 m to 1e-21 m; a crease that never gets there keeps the chord).
constexpr int kProjections = 60;
constexpr double kAgreement = 1e-3;

// Builds the refinement: owns the growing vertex list and the points made on split edges.
class Refiner {
 public:
  Refiner(const TriangleMesh& mesh, const SurfaceRecognition& r, int k)
      : mesh_(mesh), rec_(r), k_(k), split_(static_cast<std::size_t>(mesh.triangleCount()), 0) {
    for (Eigen::Index v = 0; v < mesh.vertexCount(); ++v) points_.push_back(mesh.vertex(v));
    for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f)
      for (int c = 0; c < 3; ++c)
        edgeFaces_[edgeKey(mesh.triangles(f, c), mesh.triangles(f, (c + 1) % 3))].push_back(
            static_cast<int>(f));
  }

  void markSplit(int f) { split_[static_cast<std::size_t>(f)] = 1; }

  SurfaceRefinement run() {
    SurfaceRefinement out;
    out.level = k_;
    for (int f = 0; f < static_cast<int>(mesh_.triangleCount()); ++f) {
      const std::size_t before = faces_.size();
      if (split_[static_cast<std::size_t>(f)]) {
        splitFace(f);
        ++out.split_faces;
      } else if (hasSplitEdge(f)) {
        fanFace(f);
        ++out.fanned_faces;
      } else {
        faces_.push_back({mesh_.triangles(f, 0), mesh_.triangles(f, 1), mesh_.triangles(f, 2)});
      }
      out.origin.insert(out.origin.end(), faces_.size() - before, f);
    }
    out.mesh.vertices.resize(static_cast<Eigen::Index>(points_.size()), 3);
    for (std::size_t v = 0; v < points_.size(); ++v)
      out.mesh.vertices.row(static_cast<Eigen::Index>(v)) = points_[v].transpose();
    out.mesh.triangles.resize(static_cast<Eigen::Index>(faces_.size()), 3);
    for (std::size_t f = 0; f < faces_.size(); ++f)
      out.mesh.triangles.row(static_cast<Eigen::Index>(f)) << faces_[f][0], faces_[f][1],
          faces_[f][2];
    return out;
  }

 private:
  bool edgeIsSplit(int u, int w) const {
    const auto it = edgeFaces_.find(edgeKey(u, w));
    return std::any_of(it->second.begin(), it->second.end(),
                       [&](int g) { return split_[static_cast<std::size_t>(g)] != 0; });
  }

  bool hasSplitEdge(int f) const {
    for (int c = 0; c < 3; ++c)
      if (edgeIsSplit(mesh_.triangles(f, c), mesh_.triangles(f, (c + 1) % 3))) return true;
    return false;
  }

  // Where a point of edge (u, w) goes: onto the surface of both faces, or onto the curve where
  // their two surfaces meet (alternating projections, which converge to the intersection near
  // p when the surfaces cross; a cylinder's rim on its cap plane in one step), else the chord.
  Eigen::Vector3d placeOnEdge(int u, int w, const Eigen::Vector3d& p) const {
    const std::vector<int>& faces = edgeFaces_.at(edgeKey(u, w));
    std::vector<const RecognisedSurface*> on;
    for (int g : faces) {
      const int s = rec_.face_surface[static_cast<std::size_t>(g)];
      if (s < 0) return p;  // a free-form face keeps its edges
      const RecognisedSurface* S = &rec_.surfaces[static_cast<std::size_t>(s)];
      if (std::find(on.begin(), on.end(), S) == on.end()) on.push_back(S);
    }
    if (on.size() == 1) return closestPoint(*on.front(), p);
    Eigen::Vector3d q = p;
    for (int step = 0; step < kProjections; ++step) {
      for (const RecognisedSurface* S : on) q = closestPoint(*S, q);
      const bool agreed = std::all_of(on.begin(), on.end(), [&](const RecognisedSurface* S) {
        return std::abs(signedDistance(*S, q)) <= kAgreement * rec_.tolerance;
      });
      if (agreed) return q;
    }
    return p;
  }

  // The vertex at step t (0 < t < k) from u along edge (u, w); made once per edge.
  int edgePoint(int u, int w, int t) {
    const std::uint64_t key = edgeKey(u, w);
    auto it = edgePoints_.find(key);
    if (it == edgePoints_.end()) {
      const int lo = std::min(u, w), hi = std::max(u, w);
      std::vector<int> ids;
      for (int s = 1; s < k_; ++s) {
        const Eigen::Vector3d p =
            points_[static_cast<std::size_t>(lo)] +
            (points_[static_cast<std::size_t>(hi)] - points_[static_cast<std::size_t>(lo)]) *
                (static_cast<double>(s) / k_);
        ids.push_back(addPoint(placeOnEdge(lo, hi, p)));
      }
      it = edgePoints_.emplace(key, std::move(ids)).first;
    }
    return u < w ? it->second[static_cast<std::size_t>(t - 1)]
                 : it->second[static_cast<std::size_t>(k_ - t - 1)];
  }

  int addPoint(const Eigen::Vector3d& p) {
    points_.push_back(p);
    return static_cast<int>(points_.size()) - 1;
  }

  // The k×k grid of face f: point (i, j) = a + (i/k)(b − a) + (j/k)(c − a), i + j ≤ k.
  void splitFace(int f) {
    const int a = mesh_.triangles(f, 0), b = mesh_.triangles(f, 1), c = mesh_.triangles(f, 2);
    const RecognisedSurface& S =
        rec_.surfaces[static_cast<std::size_t>(rec_.face_surface[static_cast<std::size_t>(f)])];
    const Eigen::Vector3d pa = mesh_.vertex(a), pb = mesh_.vertex(b), pc = mesh_.vertex(c);
    std::vector<int> grid(static_cast<std::size_t>((k_ + 1) * (k_ + 1)), -1);
    const auto at = [&](int i, int j) -> int& {
      return grid[static_cast<std::size_t>(i * (k_ + 1) + j)];
    };
    for (int i = 0; i <= k_; ++i)
      for (int j = 0; i + j <= k_; ++j) {
        if (i == 0 && j == 0)
          at(i, j) = a;
        else if (i == k_)
          at(i, j) = b;
        else if (j == k_)
          at(i, j) = c;
        else if (j == 0)
          at(i, j) = edgePoint(a, b, i);
        else if (i == 0)
          at(i, j) = edgePoint(a, c, j);
        else if (i + j == k_)
          at(i, j) = edgePoint(b, c, j);
        else {
          const Eigen::Vector3d p = pa + (pb - pa) * (static_cast<double>(i) / k_) +
                                    (pc - pa) * (static_cast<double>(j) / k_);
          at(i, j) = addPoint(closestPoint(S, p));
        }
      }
    for (int i = 0; i < k_; ++i)
      for (int j = 0; i + j < k_; ++j) {
        faces_.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j < k_ - 1) faces_.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }

  // Face f's boundary through the points of its split edges, fanned about its centroid.
  void fanFace(int f) {
    std::vector<int> loop;
    for (int c = 0; c < 3; ++c) {
      const int u = mesh_.triangles(f, c), w = mesh_.triangles(f, (c + 1) % 3);
      loop.push_back(u);
      if (edgeIsSplit(u, w))
        for (int t = 1; t < k_; ++t) loop.push_back(edgePoint(u, w, t));
    }
    const int centre =
        addPoint((mesh_.corner(f, 0) + mesh_.corner(f, 1) + mesh_.corner(f, 2)) / 3.0);
    for (std::size_t i = 0; i < loop.size(); ++i)
      faces_.push_back({centre, loop[i], loop[(i + 1) % loop.size()]});
  }

  const TriangleMesh& mesh_;
  const SurfaceRecognition& rec_;
  const int k_;
  std::vector<char> split_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> faces_;
  std::unordered_map<std::uint64_t, std::vector<int>> edgeFaces_;
  std::unordered_map<std::uint64_t, std::vector<int>> edgePoints_;  ///< from the lower index
};

}  // namespace

Eigen::Vector3d closestPoint(const RecognisedSurface& s, const Eigen::Vector3d& p) {
  return p - signedDistance(s, p) * outwardNormal(s, p);
}

double chordGap(const TriangleMesh& mesh, const SurfaceRecognition& recognition, int f) {
  const int s = recognition.face_surface[static_cast<std::size_t>(f)];
  if (s < 0) return 0.0;
  const Eigen::Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
  const Eigen::Vector3d probes[] = {(a + b + c) / 3.0, (a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0};
  double gap = 0.0;
  for (const Eigen::Vector3d& p : probes)
    gap = std::max(gap,
                   std::abs(signedDistance(recognition.surfaces[static_cast<std::size_t>(s)], p)));
  return gap;
}

SurfaceRefinement refineSurfaces(const TriangleMesh& mesh, const SurfaceRecognition& recognition,
                                 const std::vector<int>& faces, int level) {
  if (level < 1) throw std::invalid_argument("refineSurfaces: level must be >= 1");
  Refiner refiner(mesh, recognition, level);
  for (int f : faces) {
    if (f < 0 || f >= mesh.triangleCount())
      throw std::invalid_argument("refineSurfaces: face " + std::to_string(f) + " out of range");
    if (level > 1 && isCurved(recognition, f)) refiner.markSplit(f);
  }
  return refiner.run();
}

}  // namespace vcontact::geometry
