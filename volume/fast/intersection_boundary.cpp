// Step 3 of the exact mesh–mesh intersection (fast/surface_integration.hpp): the boundary of the
// region A ∩ B as directed pieces on the faces of both meshes. The crossings of each edge, in order
// along it, give the parts of the edge inside the other body; the crossings of each face pair
// pair into the segments t_A ∩ t_B; the inside status floods over the edges that cross
// nothing, and a connected part with no crossing edge takes one exact ray-parity test.

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "volume/fast/intersector.hpp"
#include "volume/kernels/exact_predicates.hpp"

namespace vcontact::volume::internal {
namespace {

/// Crossings closer than this along their edge (as a fraction of its length) may be out of
/// order after sorting by the rounded λ; their order is then re-derived exactly
/// (orderAlongEdge). λ = d_p/(d_p − d_q) is good to a few ε unless the edge is within about
/// 1e-7 rad of the face's plane; a false alarm costs one exact parity test.
constexpr double kLambdaTie = 1e-9;

}  // namespace

void Intersector::emitAlongEdge(int side, const MeshEdge& E, const Vector3d& from,
                                const Vector3d& to, int fromNode, int toNode) {
  scratch_.pieces.push_back({side, E.tri[0], from, to, fromNode, toNode});  // owner: v0 → v1
  scratch_.pieces.push_back({side, E.tri[1], to, from, toNode, fromNode});
}

int Intersector::vertexNode(int side, int v) {
  bool fresh;
  int& node = body_[side].scratch.vertexNode.slot(v, fresh);
  if (fresh) {
    node = static_cast<int>(scratch_.nodeParent.size());
    scratch_.nodeParent.push_back(node);
  }
  return node;
}

void Intersector::markInside(int side, int v) {
  if (body_[side].scratch.inside.insert(v)) body_[side].scratch.insideList.push_back(v);
}

/// The parts of each crossing edge inside the other body; seeds the inside flood.
void Intersector::walkEdges() {
  auto& order = scratch_.order;
  order.resize(scratch_.crossings.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  scratch_.nodeParent.resize(order.size());  // crossing i is node i
  for (std::size_t i = 0; i < order.size(); ++i) scratch_.nodeParent[i] = static_cast<int>(i);
  const auto& X = scratch_.crossings;
  std::sort(order.begin(), order.end(), [&X](int i, int j) {
    const Crossing& a = X[static_cast<std::size_t>(i)];
    const Crossing& b = X[static_cast<std::size_t>(j)];
    return std::tie(a.side, a.edge, a.lambda) < std::tie(b.side, b.edge, b.lambda);
  });
  for (std::size_t i = 0; i < order.size();) {
    const Crossing& first = X[static_cast<std::size_t>(order[i])];
    std::size_t end = i + 1;
    while (end < order.size() && X[static_cast<std::size_t>(order[end])].side == first.side &&
           X[static_cast<std::size_t>(order[end])].edge == first.edge) {
      ++end;
    }
    const auto begin = order.begin() + static_cast<std::ptrdiff_t>(i);
    bool inside = orderAlongEdge(begin, order.begin() + static_cast<std::ptrdiff_t>(end));
    Body& m = body_[first.side];
    const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(first.edge)];
    m.scratch.crossingEdge.insert(first.edge);
    m.scratch.seeded[static_cast<std::size_t>(m.topo.component(E.v0))] = 1;
    if (inside) markInside(first.side, E.v0);
    Vector3d from = m.placedVertex(E.v0);
    int fromNode = inside ? vertexNode(first.side, E.v0) : -1;
    for (; i < end; ++i) {
      const Crossing& c = X[static_cast<std::size_t>(order[i])];
      if (inside) emitAlongEdge(first.side, E, from, c.x, fromNode, order[i]);
      from = c.x;
      fromNode = order[i];
      inside = c.sigma > 0;
    }
    if (inside) {
      emitAlongEdge(first.side, E, from, m.placedVertex(E.v1), fromNode,
                    vertexNode(first.side, E.v1));
      markInside(first.side, E.v1);
    }
  }
}

/// Puts one edge's crossings, sorted by λ, into their order along the perturbed edge and
/// returns whether the edge's start v0 lies inside the other body. Along an edge the
/// crossings alternate between entering and leaving. Sorted by λ they do, unless two of
/// them lie within rounding of each other or at one point (an edge through an edge or a
/// vertex of the other mesh, flush faces: the ties of the perturbed configuration), where
/// the sort may have swapped them. Then the start's status comes from the exact parity test
/// (as perturbed), and a crossing that breaks the alternation trades places with the next
/// one of the expected direction, which the true sequence puts there.
bool Intersector::orderAlongEdge(std::vector<int>::iterator first,
                                 std::vector<int>::iterator last) {
  const auto& X = scratch_.crossings;
  const auto at = [&X](int k) -> const Crossing& { return X[static_cast<std::size_t>(k)]; };
  bool clean = true;
  for (auto it = first + 1; it != last && clean; ++it) {
    clean =
        at(*it).sigma == -at(*(it - 1)).sigma && at(*it).lambda - at(*(it - 1)).lambda > kLambdaTie;
  }
  if (clean) return at(*first).sigma < 0;
  const Crossing& c = at(*first);
  const MeshEdge& E = body_[c.side].topo.edges()[static_cast<std::size_t>(c.edge)];
  const bool startsInside =
      contains(1 - c.side, body_[c.side].placedVertex(E.v0), perturbationSign(c.side));
  int expected = startsInside ? -1 : +1;
  for (auto it = first; it != last; ++it, expected = -expected) {
    if (at(*it).sigma == expected) continue;
    const auto next = std::find_if(it + 1, last, [&](int k) { return at(k).sigma == expected; });
    if (next == last) {
      throw std::logic_error(describeFailure("an edge's crossings do not alternate"));
    }
    std::rotate(it, next, next + 1);
  }
  return startsInside;
}

/// Pairs the crossings into the segments t_A ∩ t_B. With d = n_A × n_B, the region
/// t_A ∩ B lies to the left of d seen from n_A, and t_B ∩ A to the left of −d. An edge of
/// t_A that enters B ends the segment (t_A's boundary goes on along the edge, into B); an
/// edge of t_B that enters A starts it (the same rule seen from t_B, whose segment runs −d).
void Intersector::buildSegments() {
  for (std::size_t i = 0; i < scratch_.crossings.size(); ++i) {
    const Crossing& c = scratch_.crossings[i];
    const MeshEdge& E = body_[c.side].topo.edges()[static_cast<std::size_t>(c.edge)];
    for (int j = 0; j < 2; ++j) {
      const bool enters = (j == 0 ? c.sigma : -c.sigma) > 0;  // along the face's own run
      const auto t = static_cast<std::uint64_t>(E.tri[j]);
      const auto f = static_cast<std::uint64_t>(c.face);
      if (c.side == 0) {
        scratch_.endpoints.push_back({(t << 32) | f, static_cast<int>(i), !enters});
      } else {
        scratch_.endpoints.push_back({(f << 32) | t, static_cast<int>(i), enters});
      }
    }
  }
  std::sort(scratch_.endpoints.begin(), scratch_.endpoints.end(),
            [](const Endpoint& a, const Endpoint& b) { return a.key < b.key; });
  for (std::size_t i = 0; i < scratch_.endpoints.size(); i += 2) {
    const Endpoint& e0 = scratch_.endpoints[i];
    if (i + 1 >= scratch_.endpoints.size() || scratch_.endpoints[i + 1].key != e0.key ||
        scratch_.endpoints[i + 1].start == e0.start ||
        (i + 2 < scratch_.endpoints.size() && scratch_.endpoints[i + 2].key == e0.key)) {
      throw std::logic_error(describeFailure("a face pair's crossings do not form one segment"));
    }
    const Endpoint& e1 = scratch_.endpoints[i + 1];
    const int s = e0.start ? e0.crossing : e1.crossing;
    const int e = e0.start ? e1.crossing : e0.crossing;
    const Vector3d& xs = scratch_.crossings[static_cast<std::size_t>(s)].x;
    const Vector3d& xe = scratch_.crossings[static_cast<std::size_t>(e)].x;
    const int tA = static_cast<int>(e0.key >> 32);
    const int tB = static_cast<int>(e0.key & 0xffffffffu);
    scratch_.pieces.push_back({0, tA, xs, xe, s, e});
    scratch_.pieces.push_back({1, tB, xe, xs, e, s});
    if (body_[0].scratch.cut.insert(tA)) body_[0].scratch.cutList.push_back(tA);
    if (body_[1].scratch.cut.insert(tB)) body_[1].scratch.cutList.push_back(tB);
  }
}

/// Inside status spreads over the edges that cross nothing.
void Intersector::floodInside(int side) {
  Body& m = body_[side];
  auto& stack = scratch_.stack;
  stack.assign(m.scratch.insideList.begin(), m.scratch.insideList.end());
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (const int* e = m.topo.edgesBegin(v); e != m.topo.edgesEnd(v); ++e) {
      if (m.scratch.crossingEdge.contains(*e)) continue;
      const MeshEdge& E = m.topo.edges()[static_cast<std::size_t>(*e)];
      const int w = E.v0 == v ? E.v1 : E.v0;
      if (m.scratch.inside.insert(w)) {
        m.scratch.insideList.push_back(w);
        stack.push_back(w);
      }
    }
  }
}

/// A connected part with no crossing edge is wholly inside or wholly outside (it may
/// still be pierced by edges of the other mesh); one exact ray-parity test decides.
void Intersector::classifyUnseededComponents(int side) {
  Body& m = body_[side];
  Body& o = body_[1 - side];
  const auto otherBox = placedBox(o.X_WM, o.bvh.root().center, o.bvh.root().halfExtent);
  const auto& comps = m.topo.components();
  for (std::size_t c = 0; c < comps.size(); ++c) {
    if (m.scratch.seeded[c]) continue;
    const geometry::Aabb& bb = comps[c].bounds;
    const auto box = placedBox(m.X_WM, 0.5 * (bb.min + bb.max), 0.5 * bb.size());
    if (!boxesOverlap(box.first, box.second, otherBox.first, otherBox.second, margin_)) {
      continue;
    }
    if (!contains(1 - side, m.placedVertex(comps[c].vertices.front()), perturbationSign(side)))
      continue;
    wholeShellInside_ = true;
    for (const int v : comps[c].vertices) markInside(side, v);
  }
}

/// Is p_W (a point of the other mesh, moved by sign·τ) inside mesh `side`? Parity of the
/// crossings of a segment from p to beyond the mesh's box, through its tree.
bool Intersector::contains(int side, const Vector3d& p_W, int sign) {
  Body& m = body_[side];
  const BvhNode& root = m.bvh.root();
  const Isometry3d X_MW = m.X_WM.inverse();
  const Vector3d p_M = X_MW * p_W;
  if (((p_M - root.center).cwiseAbs().array() > root.halfExtent.array() + margin_).any()) {
    return false;
  }
  // A fixed direction that no mesh built on axes or simple angles lies along.
  const Vector3d dir_M = Vector3d(0.5773, 0.2113, 0.7887).normalized();
  const double length = 2.0 * ((p_M - root.center).norm() + root.halfExtent.norm());
  const Vector3d f_M = p_M + length * dir_M;
  const Vector3d f_W = m.X_WM * f_M;
  const Vector3d grow = Vector3d::Constant(margin_);
  int crossings = 0;
  auto& stack = scratch_.stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const BvhNode& n = m.bvh.nodes()[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (!segmentMeetsBox(p_M, f_M, n.center, n.halfExtent + grow)) continue;
    if (!n.isLeaf()) {
      stack.push_back(n.left);
      stack.push_back(n.right);
      continue;
    }
    for (int i = n.first; i < n.first + n.count; ++i) {
      const int f = m.bvh.order()[static_cast<std::size_t>(i)];
      if (perturbedSegmentCrossing(p_W, f_W, m.corner(f, 0), m.corner(f, 1), m.corner(f, 2),
                                   sign) != 0) {
        ++crossings;
      }
    }
  }
  return crossings % 2 == 1;
}

/// The edges of a cut face that cross nothing and lie inside bound its region whole.
void Intersector::addWholeEdgesOfCutFaces(int side) {
  Body& m = body_[side];
  for (const int t : m.scratch.cutList) {
    for (int k = 0; k < 3; ++k) {
      const int e = m.topo.cornerEdge(t, k);
      if (m.scratch.crossingEdge.contains(e) ||
          !m.scratch.inside.contains(m.mesh().triangles(t, k))) {
        continue;
      }
      const int v = m.mesh().triangles(t, k), w = m.mesh().triangles(t, (k + 1) % 3);
      scratch_.pieces.push_back({side, t, m.corner(t, k), m.corner(t, (k + 1) % 3),
                                 vertexNode(side, v), vertexNode(side, w)});
    }
  }
}

/// Faces that are not cut and have an inside vertex are wholly inside.
void Intersector::collectWholeFaces(int side) {
  Body& m = body_[side];
  for (const int v : m.scratch.insideList) {
    for (const int* f = m.topo.facesBegin(v); f != m.topo.facesEnd(v); ++f) {
      if (m.mesh().triangles(*f, 0) == v && !m.scratch.cut.contains(*f))
        scratch_.wholes.push_back({side, *f});
    }
  }
}

}  // namespace vcontact::volume::internal
