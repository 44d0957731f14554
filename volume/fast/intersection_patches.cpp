// Step 5 of the exact mesh–mesh intersection (fast/surface_integration.hpp): the boundary pieces of
// A ∩ B grouped into the connected components of the region, and each component integrated as a
// patch of its own. The pieces connect through their end nodes (crossings and inside
// vertices); a face whose region has a hole bounded by another group (a ring pressed into a
// plate face) joins the hole to the loop around it on that face.

#include <algorithm>
#include <numeric>
#include <vector>

#include "volume/fast/intersector.hpp"

namespace vcontact::volume::internal {
/// The two coordinates of a face's plane kept when its dominant normal axis is dropped.
struct PlaneAxes {
  explicit PlaneAxes(const Vector3d& n) {
    int drop;
    n.cwiseAbs().maxCoeff(&drop);
    u = (drop + 1) % 3;
    v = (drop + 2) % 3;
  }
  int u, v;
};

/// One group's loops on one face: its pieces and their signed area about the face's normal
/// (> 0: an outer boundary of the face's region, < 0: a hole in it).
struct FaceLoops {
  int root;
  std::vector<const Piece*> pieces;
  double area = 0.0;
};

namespace {

/// Does the closed set of directed segments `loop` (pieces of one face) wind around the
/// point x of the face's plane? Crossing-number test on the projection (Haines, "Point in
/// Polygon Strategies", Graphics Gems IV); the segments' order does not matter.
bool encloses(const std::vector<const Piece*>& loop, const Vector3d& x, const PlaneAxes& ax) {
  bool in = false;
  for (const Piece* pc : loop) {
    const double au = pc->p[ax.u], av = pc->p[ax.v], bu = pc->q[ax.u], bv = pc->q[ax.v];
    if ((av > x[ax.v]) != (bv > x[ax.v]) && x[ax.u] < (bu - au) * (x[ax.v] - av) / (bv - av) + au) {
      in = !in;
    }
  }
  return in;
}

}  // namespace

int Intersector::findNode(int node) {
  auto& parent = scratch_.nodeParent;
  while (parent[static_cast<std::size_t>(node)] != node) {
    int& up = parent[static_cast<std::size_t>(node)];
    up = parent[static_cast<std::size_t>(up)];  // path halving
    node = up;
  }
  return node;
}

void Intersector::joinNodes(int a, int b) {
  a = findNode(a);
  b = findNode(b);
  if (a != b) scratch_.nodeParent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

/// Joins the ends of every piece; returns the number of groups of the pieces' nodes. Each
/// piece's ends are joined once: a segment and a part of an edge come as a pair of opposite
/// pieces (one per face), and a whole edge of a cut face without its opposite lies on a whole
/// face. Whole faces are not joined here: each connected set of them borders a cut face along
/// a whole edge (a face with two inside corners is whole or cut), so it adds no group unless
/// it is a shell wholly inside the other body (wholeShellInside_).
int Intersector::groupPieces() {
  for (const Piece& pc : scratch_.pieces) {
    if (pc.from < pc.to) joinNodes(pc.from, pc.to);
  }
  return countGroups();
}

/// Joins the corners of every whole face (for integratePatches, which finds a whole face's
/// group from its first corner).
void Intersector::joinWholeFaces() {
  for (const WholeFace& wf : scratch_.wholes) {
    const auto& tri = body_[wf.side].mesh().triangles;
    const int a = vertexNode(wf.side, tri(wf.face, 0));
    joinNodes(a, vertexNode(wf.side, tri(wf.face, 1)));
    joinNodes(a, vertexNode(wf.side, tri(wf.face, 2)));
  }
}

int Intersector::countGroups() const {
  int groups = 0;
  for (std::size_t i = 0; i < scratch_.nodeParent.size(); ++i) {
    groups += scratch_.nodeParent[i] == static_cast<int>(i);
  }
  return groups;
}

/// On each face that carries pieces of several groups, joins each hole loop to the smallest
/// outer loop around it; returns the number of groups left.
int Intersector::joinHolesWithinFaces() {
  const auto& pieces = scratch_.pieces;
  std::vector<int> byFace(pieces.size());
  std::iota(byFace.begin(), byFace.end(), 0);
  std::sort(byFace.begin(), byFace.end(), [&pieces](int i, int j) {
    const Piece& a = pieces[static_cast<std::size_t>(i)];
    const Piece& b = pieces[static_cast<std::size_t>(j)];
    return a.side != b.side ? a.side < b.side : a.face < b.face;
  });
  std::vector<FaceLoops> loops;
  for (std::size_t i = 0; i < byFace.size();) {
    const Piece& first = pieces[static_cast<std::size_t>(byFace[i])];
    const Vector3d& n = body_[first.side].scratch.feet[first.face].n_W;
    loops.clear();
    for (; i < byFace.size(); ++i) {
      const Piece& pc = pieces[static_cast<std::size_t>(byFace[i])];
      if (pc.side != first.side || pc.face != first.face) break;
      const int root = findNode(pc.from);
      auto it = std::find_if(loops.begin(), loops.end(),
                             [root](const FaceLoops& l) { return l.root == root; });
      if (it == loops.end()) it = loops.insert(loops.end(), FaceLoops{root, {}, 0.0});
      it->pieces.push_back(&pc);
      it->area += 0.5 * n.dot((pc.p - first.p).cross(pc.q - first.p));
    }
    if (loops.size() > 1) joinHoles(loops, PlaneAxes(n));
  }
  return countGroups();
}

/// Joins each hole loop of one face to the smallest outer loop that encloses it.
void Intersector::joinHoles(const std::vector<FaceLoops>& loops, const PlaneAxes& axes) {
  for (const FaceLoops& hole : loops) {
    if (hole.area >= 0.0) continue;
    const FaceLoops* around = nullptr;
    for (const FaceLoops& outer : loops) {
      if (outer.area > 0.0 && (!around || outer.area < around->area) &&
          encloses(outer.pieces, hole.pieces.front()->p, axes)) {
        around = &outer;
      }
    }
    if (around) joinNodes(hole.root, around->root);
  }
}

/// Integrates each group as its own region (step 4 per group), about its own apex: the first
/// point of its first piece (or first whole face), so that its terms are of its own size.
std::vector<ContactVolume> Intersector::integratePatches() {
  std::vector<int> groupOf(scratch_.nodeParent.size(), -1);
  std::vector<RegionSum> sums;
  std::vector<std::vector<Patch>> parts;
  const auto sumOf = [&](int node, const Vector3d& apex) -> int {
    int& g = groupOf[static_cast<std::size_t>(findNode(node))];
    if (g < 0) {
      g = static_cast<int>(sums.size());
      sums.emplace_back(apex);
      parts.emplace_back();
    }
    return g;
  };
  for (const Piece& pc : scratch_.pieces) {
    const auto g = static_cast<std::size_t>(sumOf(pc.from, pc.p));
    const FaceFoot& F = body_[pc.side].scratch.feet[pc.face];
    // the group's apex dropped onto the face's plane (F.foot is a point of that plane)
    const Vector3d c = sums[g].o - F.n_W * F.n_W.dot(sums[g].o - F.foot);
    sums[g].add(pc.side, pc.face, c, pc.p, pc.q, F.n_W, 0.5 * F.n_W.dot((pc.p - c).cross(pc.q - c)),
                inNormal(pc.side, pc.face), inArea(pc.side, pc.face), parts[g]);
  }
  for (const WholeFace& wf : scratch_.wholes) {
    Body& m = body_[wf.side];
    const Vector3d &a = m.corner(wf.face, 0), &b = m.corner(wf.face, 1), &c = m.corner(wf.face, 2);
    const auto g =
        static_cast<std::size_t>(sumOf(vertexNode(wf.side, m.mesh().triangles(wf.face, 0)), a));
    const Vector3d N = (b - a).cross(c - a);
    const double twiceArea = N.norm();
    const Vector3d nrm = N * (1.0 / twiceArea);
    const bool area = inArea(wf.side, wf.face);
    sums[g].add(wf.side, wf.face, a, b, c, nrm, 0.5 * twiceArea, inNormal(wf.side, wf.face), area,
                parts[g]);
    if (area) addOtherEdges(wf, nrm, parts[g]);
  }
  std::vector<ContactVolume> patches;
  for (std::size_t g = 0; g < sums.size(); ++g) {
    const ContactVolume cv = contactOf(sums[g], parts[g]);
    if (cv.inContact()) patches.push_back(cv);
  }
  return patches;
}

}  // namespace vcontact::volume::internal
