#pragma once
// The state of one query of the exact mesh–mesh intersection (fast/surface_integration.hpp) and the
// class that runs its steps: 1–2 (candidate face pairs, crossings) and 4 (integration) in
// fast/surface_integration.cpp, 3 (boundary pieces, inside flood, ray parity) in
// fast/intersection_boundary.cpp. Internal to those files.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/moments.hpp"
#include "volume/contact_volume.hpp"
#include "volume/depth/deepest_column.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/fast/tree_pair_descent.hpp"
#include "volume/fast/triangle_pair.hpp"
#include "volume/kernels/stamp_set.hpp"

namespace vcontact::volume::internal {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;
using geometry::MeshEdge;
using geometry::MeshTopology;

/// A face's plane as the integration uses it.
struct FaceFoot {
  Vector3d n_W;   ///< unit, outward, W
  Vector3d foot;  ///< the fan apex o projected onto the plane, W
};

/// Per-mesh memory reused by the queries of one thread, so a query costs what it touches.
struct SideScratch {
  StampedValues<Vector3d> p_W;      ///< vertices placed in W
  StampedValues<PlacedFace> faces;  ///< faces placed in W
  StampedValues<FaceFoot> feet;     ///< faces' planes for the integration
  StampSet inside;                  ///< vertices inside the other body
  std::vector<int> insideList;
  StampSet cut;  ///< faces with at least one intersection segment
  std::vector<int> cutList;
  StampSet crossingEdge;          ///< edges that cross the other surface
  StampSet coplanarSame;          ///< faces in the plane of a face of the other mesh, same way
  StampSet coplanarOpposite;      ///< ... facing it
  std::vector<char> seeded;       ///< per component: has a crossing edge
  StampedValues<int> vertexNode;  ///< boundary node of an inside vertex (Intersector::vertexNode)
};

/// One edge of one mesh through one face of the other.
struct Crossing {
  int side;       ///< mesh of the edge: 0 = A, 1 = B
  int edge;       ///< edge index in that mesh
  int face;       ///< face of the other mesh
  int sigma;      ///< +1: the edge, run v0 → v1, enters the other body here; −1: leaves
  double lambda;  ///< position along v0 → v1, in [0, 1]
  Vector3d x;     ///< W
};

/// An end of the segment t_A ∩ t_B, oriented as the boundary of t_A ∩ B.
struct Endpoint {
  std::uint64_t key;  ///< (t_A << 32) | t_B
  int crossing;
  bool start;
};

/// A directed boundary edge (p → q) of the region t ∩ (other body), t a face of mesh `side`,
/// and the boundary nodes at its ends (Intersector::vertexNode; a crossing's node is its
/// index), through which the pieces of one patch connect.
struct Piece {
  int side;
  int face;
  Vector3d p, q;
  int from, to;
};

/// A boundary patch as the area and depth passes see it.
struct Patch {
  std::uint64_t face;  ///< (side << 32) | face index: the depth pass groups edges by face
  Vector3d n_W;        ///< unit normal of its face
  double area;         ///< signed area (a piece's share of its face's region)
  Vector3d p, q;       ///< a boundary edge of the face's region, for the depth
};

/// The key of face `face` of mesh `side` in Patch::face.
inline std::uint64_t faceKey(int side, int face) {
  return (static_cast<std::uint64_t>(side) << 32) | static_cast<std::uint32_t>(face);
}

/// The integration's running sums over one region's boundary (step 4): its fan about the apex
/// o, the sizes its noise test needs, n's area vector and the patches for area and depth.
struct RegionSum {
  explicit RegionSum(const Vector3d& apex) : o(apex), scale3(apex.cwiseAbs()) {}

  /// Adds the boundary triangle (c, p, q) of face `face` of mesh `side`, with unit normal nrm
  /// and signed area `area` (p → q is an edge of the face's region); `normal`, `area`: whether
  /// it counts in n, in area and depth.
  void add(int side, int face, const Vector3d& c, const Vector3d& p, const Vector3d& q,
           const Vector3d& nrm, double area, bool inNormal, bool inArea,
           std::vector<Patch>& parts) {
    termSum6 += std::abs(fan.add(c - o, p - o, q - o));
    areaSum += std::abs(area);
    scale3 = scale3.cwiseMax(p.cwiseAbs()).cwiseMax(q.cwiseAbs());
    if (inNormal) nSum += (side == 1 ? area : -area) * nrm;
    if (inArea) parts.push_back({faceKey(side, face), nrm, area, p, q});
  }

  Vector3d o;
  geometry::TetrahedronSum fan;
  double termSum6 = 0.0;             ///< 6 Σ |fan term volumes|
  double areaSum = 0.0;              ///< Σ |patch areas|
  Vector3d scale3;                   ///< largest |coordinate| of the points, per axis
  Vector3d nSum = Vector3d::Zero();  ///< ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA (MODEL.md §1)
};

struct WholeFace {
  int side;
  int face;
};

struct Scratch {
  SideScratch sides[2];
  DescentScratch descent;
  std::vector<Crossing> crossings;
  std::vector<int> order;
  std::vector<Endpoint> endpoints;
  std::vector<Piece> pieces;
  std::vector<WholeFace> wholes;
  std::vector<int> stack;
  /// Faces of B's leaf that meet A's leaf slab (testLeaves), with their placement.
  std::vector<std::pair<int, const PlacedFace*>> columns;
  std::vector<Patch> patches;
  /// Union-find parents of the boundary nodes: crossings first, then inside vertices.
  std::vector<int> nodeParent;
  ColumnDepth depth;
};

/// This thread's scratch memory of meshMeshContact.
Scratch& threadScratch();

/// The depth pass of this thread's last meshMeshContact that ran one (its segments and
/// arguments: ColumnDepth::inputs, lastArguments), for tests that replay it.
const ColumnDepth& lastDepthPass();

/// A mesh placed in W for one query.
struct Body {
  const MeshBvh& bvh;
  const MeshTopology& topo;
  Isometry3d X_WM;
  SideScratch& scratch;

  const geometry::TriangleMesh& mesh() const { return bvh.mesh(); }
  /// p_W of vertex v, placed on first use.
  const Vector3d& placedVertex(int v) {
    bool fresh;
    Vector3d& p_W = scratch.p_W.slot(v, fresh);
    if (fresh) p_W = X_WM * mesh().vertex(v);
    return p_W;
  }
  /// Face f placed in W, on first use (the look-up inline, the placement not: the descent
  /// asks for each face many times).
  const PlacedFace& face(int f) {
    if (scratch.faces.contains(f)) return scratch.faces[f];
    return placeFace(f);
  }
  const Vector3d& corner(int f, int k) { return placedVertex(mesh().triangles(f, k)); }
  /// Face f's unit outward normal and the foot of the fan apex o on its plane (W), on first
  /// use; o is the same for the whole query.
  const FaceFoot& foot(int f, const Vector3d& o) {
    bool fresh;
    FaceFoot& F = scratch.feet.slot(f, fresh);
    if (!fresh) return F;
    const Vector3d& a = corner(f, 0);
    const Vector3d N = (corner(f, 1) - a).cross(corner(f, 2) - a);
    F.n_W = N * (1.0 / N.norm());           // one division, not three
    F.foot = o - F.n_W * F.n_W.dot(o - a);  // o projected onto the face's plane
    return F;
  }
  /// Places face f in W (face()'s first use).
  [[gnu::noinline]] const PlacedFace& placeFace(int f) {
    bool fresh;  // always: face() has looked
    PlacedFace& F = scratch.faces.slot(f, fresh);
    F = placedFace(corner(f, 0), corner(f, 1), corner(f, 2));
    return F;
  }
};

/// The symbolic translation of a segment of mesh `side` relative to the other mesh's faces:
/// A is the body moved by +τ (kernels/exact_predicates.hpp).
inline int perturbationSign(int side) { return side == 0 ? 1 : -1; }

struct FaceLoops;
struct PlaneAxes;

/// One query of meshMeshContact over two placed bodies (the steps of fast/surface_integration.hpp).
class Intersector {
 public:
  Intersector(Body a, Body b, Scratch& scratch);

  /// @param deepest  run the depth pass (else depth is NaN)
  ContactPatches run(MeshMeshCache* cache, bool deepest);

  /// `what` went wrong, with both poses to 17 digits (a reproducible test case).
  std::string describeFailure(const std::string& what) const;

 private:
  // --- 1, 2: candidate face pairs and their crossings (fast/surface_integration.cpp)
  // -----------------------
  void findCrossings(MeshMeshCache* cache);
  /// A node's slab (bvh.hpp) placed in W, its axial range grown by the box margin.
  struct PlacedSlab {
    Vector3d center, axis;
    double lo, hi;
  };
  // The inner loop of the query, defined and used in fast/surface_integration.cpp only: inline, so
  // that it is inlined as if it were file-local (a call per face pair costs ~4 % of a query).
  inline PlacedSlab placedSlab(const Body& m, const BvhNode& n) const;
  static inline bool faceMeetsSlab(const PlacedFace& F, const PlacedSlab& S);
  inline void testLeaves(const BvhNode& na, const BvhNode& nb);
  inline void testFaces(int tA, const PlacedFace& FA, int tB, const PlacedFace& FB);
  inline void flagIfCoplanar(int tA, const Vector3d* A, int tB, const Vector3d* B);
  inline void testEdge(int side, int e, int face, int s0, int s1);

  // --- 3: boundary pieces (fast/intersection_boundary.cpp)
  // ------------------------------------------
  void emitAlongEdge(int side, const MeshEdge& E, const Vector3d& from, const Vector3d& to,
                     int fromNode, int toNode);
  /// The boundary node of inside vertex v of mesh `side`, made on first use.
  int vertexNode(int side, int v);
  void markInside(int side, int v);
  void walkEdges();
  bool orderAlongEdge(std::vector<int>::iterator first, std::vector<int>::iterator last);
  void buildSegments();
  void floodInside(int side);
  void classifyUnseededComponents(int side);
  bool contains(int side, const Vector3d& p_W, int sign);
  void addWholeEdgesOfCutFaces(int side);
  void collectWholeFaces(int side);

  // --- 4: integration (fast/surface_integration.cpp)
  // -------------------------------------------------------
  bool inNormal(int side, int face) const;
  bool inArea(int side, int face) const;
  ContactVolume integrate();
  /// The ContactVolume of a region from its sums and its area/depth patches `parts`.
  ContactVolume contactOf(const RegionSum& sum, const std::vector<Patch>& parts) const;
  void addOtherEdges(const WholeFace& wf, const Vector3d& nrm, std::vector<Patch>& parts);
  Vector3d contactNormal(const Vector3d& nSum, double areaSum, const Vector3d& p_c) const;
  // --- 5: patches (fast/intersection_patches.cpp)
  // ----------------------------------------------------
  int findNode(int node);
  void joinNodes(int a, int b);
  int groupPieces();
  void joinWholeFaces();
  int countGroups() const;
  int joinHolesWithinFaces();
  void joinHoles(const std::vector<FaceLoops>& loops, const PlaneAxes& axes);
  std::vector<ContactVolume> integratePatches();

  Body body_[2];
  Scratch& scratch_;
  double margin_ = 0.0;
  bool deepest_ = true;            ///< run()'s deepest
  bool anyCoplanar_ = false;       ///< flagIfCoplanar has flagged a face pair in this query
  bool wholeShellInside_ = false;  ///< classifyUnseededComponents found a shell inside
};

}  // namespace vcontact::volume::internal
