#include "geometry/mesh_topology.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <tuple>

#include "geometry/error.hpp"

namespace vcontact::geometry {
namespace {

/// CSR lists: for each key in [0, n), the values pushed for it, in input order.
void buildCsr(int n, const std::vector<std::pair<int, int>>& keyValue, std::vector<int>& start,
              std::vector<int>& values) {
  start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& [k, v] : keyValue) ++start[k + 1];
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  values.resize(keyValue.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& [k, v] : keyValue) values[fill[k]++] = v;
}

[[noreturn]] void badEdge(int v0, int v1, const std::string& what) {
  std::ostringstream s;
  s << "edge (" << v0 << ", " << v1 << ") " << what
    << "; expected a closed mesh whose faces run along each shared edge in opposite directions";
  throw InputError("", s.str());
}

}  // namespace

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  pairEdges(mesh);
  buildAdjacency(mesh);
  floodComponents(mesh);
}

void MeshTopology::pairEdges(const TriangleMesh& mesh) {
  const int nf = static_cast<int>(mesh.triangleCount());
  // Directed half-edges keyed by their undirected edge; sorting pairs up the two faces.
  struct HalfEdge {
    int lo, hi, face, corner;
    bool forward;  // runs lo → hi
  };
  std::vector<HalfEdge> half;
  half.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      half.push_back({std::min(a, b), std::max(a, b), f, k, a < b});
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.forward) < std::tie(y.lo, y.hi, y.forward);
  });
  cornerEdge_.assign(3 * static_cast<std::size_t>(nf), -1);
  for (std::size_t i = 0; i < half.size(); i += 2) {
    const HalfEdge& r = half[i];  // backward (forward = false sorts first)
    if (i + 1 >= half.size() || half[i + 1].lo != r.lo || half[i + 1].hi != r.hi) {
      badEdge(r.lo, r.hi, "is used by one face only");
    }
    const HalfEdge& f = half[i + 1];
    if (r.forward == f.forward) badEdge(r.lo, r.hi, "is run in the same direction by two faces");
    if (i + 2 < half.size() && half[i + 2].lo == r.lo && half[i + 2].hi == r.hi) {
      badEdge(r.lo, r.hi, "is used by more than two faces");
    }
    const int e = static_cast<int>(edges_.size());
    edges_.push_back({r.lo, r.hi, {f.face, r.face}});
    cornerEdge_[3 * f.face + f.corner] = e;
    cornerEdge_[3 * r.face + r.corner] = e;
  }
}

void MeshTopology::buildAdjacency(const TriangleMesh& mesh) {
  const int nv = static_cast<int>(mesh.vertexCount());
  const int nf = static_cast<int>(mesh.triangleCount());
  std::vector<std::pair<int, int>> vf, ve;
  vf.reserve(3 * static_cast<std::size_t>(nf));
  ve.reserve(2 * edges_.size());
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) vf.emplace_back(mesh.triangles(f, k), f);
  }
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    ve.emplace_back(edges_[e].v0, e);
    ve.emplace_back(edges_[e].v1, e);
  }
  buildCsr(nv, vf, faceStart_, vertexFaces_);
  buildCsr(nv, ve, edgeStart_, vertexEdges_);
}

void MeshTopology::floodComponents(const TriangleMesh& mesh) {
  const int nv = static_cast<int>(mesh.vertexCount());
  component_.assign(static_cast<std::size_t>(nv), -1);
  std::vector<int> stack;
  for (int seed = 0; seed < nv; ++seed) {
    if (component_[seed] >= 0 || faceStart_[seed] == faceStart_[seed + 1]) continue;
    const int c = static_cast<int>(components_.size());
    MeshComponent comp;
    comp.bounds = {mesh.vertex(seed), mesh.vertex(seed)};
    component_[seed] = c;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      comp.vertices.push_back(v);
      comp.bounds.min = comp.bounds.min.cwiseMin(mesh.vertex(v));
      comp.bounds.max = comp.bounds.max.cwiseMax(mesh.vertex(v));
      for (const int* e = edgesBegin(v); e != edgesEnd(v); ++e) {
        const int w = edges_[*e].v0 == v ? edges_[*e].v1 : edges_[*e].v0;
        if (component_[w] < 0) {
          component_[w] = c;
          stack.push_back(w);
        }
      }
    }
    components_.push_back(std::move(comp));
  }
}

}  // namespace vcontact::geometry
