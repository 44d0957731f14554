#pragma once
// The adjacency of a closed, consistently oriented triangle mesh: its undirected edges with
// the two faces on them, the faces and edges around each vertex, and its connected
// components. Built once per mesh in O(n log n); the exact mesh–mesh method walks it to
// follow the intersection curve and to flood the faces that lie wholly inside the other body.

#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

struct MeshEdge {
  int v0 = 0, v1 = 0;  ///< vertex indices, v0 < v1
  /// tri[0] runs along the edge as v0 → v1 (the edge's owner), tri[1] as v1 → v0.
  int tri[2] = {-1, -1};
};

struct MeshComponent {
  std::vector<int> vertices;  ///< the vertices of one connected part
  Aabb bounds;                ///< of those vertices, body frame M, m
};

class MeshTopology {
 public:
  /// @throws InputError (empty source) unless every edge is shared by exactly two faces that
  ///   run along it in opposite directions (closed, consistently oriented, manifold edges)
  explicit MeshTopology(const TriangleMesh& mesh);

  const std::vector<MeshEdge>& edges() const { return edges_; }
  /// Edge of face f from corner k to corner (k + 1) mod 3.
  int cornerEdge(int f, int k) const { return cornerEdge_[3 * f + k]; }
  /// Faces around vertex v: facesBegin(v) .. facesEnd(v) index into vertexFaces().
  const int* facesBegin(int v) const { return vertexFaces_.data() + faceStart_[v]; }
  const int* facesEnd(int v) const { return vertexFaces_.data() + faceStart_[v + 1]; }
  /// Edges at vertex v.
  const int* edgesBegin(int v) const { return vertexEdges_.data() + edgeStart_[v]; }
  const int* edgesEnd(int v) const { return vertexEdges_.data() + edgeStart_[v + 1]; }
  /// Connected component of vertex v.
  int component(int v) const { return component_[v]; }
  const std::vector<MeshComponent>& components() const { return components_; }

 private:
  /// Edges from the faces' half-edges, two opposite ones per edge; throws InputError otherwise.
  void pairEdges(const TriangleMesh& mesh);
  /// Vertex → faces and vertex → edges lists.
  void buildAdjacency(const TriangleMesh& mesh);
  /// Connected components by flood over the edges.
  void floodComponents(const TriangleMesh& mesh);

  std::vector<MeshEdge> edges_;
  std::vector<int> cornerEdge_;
  std::vector<int> faceStart_, vertexFaces_;
  std::vector<int> edgeStart_, vertexEdges_;
  std::vector<int> component_;
  std::vector<MeshComponent> components_;
};

}  // namespace vcontact::geometry
