#include "volume/columns/columns.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <variant>

#include "geometry/error.hpp"
#include "volume/columns/columns_internal.hpp"
#include "volume/kernels/bvh_cache.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::BvhNode;
using geometry::MeshBvh;
using namespace internal;

/// Union of the world boxes of the triangles of `body` that meet `box` and (for a half-space
/// other) reach below its plane, clipped to `box`: a tight bound of the region. Triangles,
/// not leaves, so that the grid (placed on this bound) does not depend on the tree's leaf
/// size.
WorldBox tighten(const ColumnBody& body, const WorldBox& box, const ColumnBody& other) {
  if (!body.bvh) return box;
  WorldBox out{Vector3d::Constant(kInf), Vector3d::Constant(-kInf)};
  auto meets = [&](const WorldBox& wb) {
    if (wb.intersected(box).empty()) return false;
    if (other.bvh) return true;
    const Vector3d z_W = other.X_WB.linear().col(2);
    const Vector3d c = 0.5 * (wb.lo + wb.hi), h = 0.5 * (wb.hi - wb.lo);
    return z_W.dot(c - other.X_WB.translation()) - z_W.cwiseAbs().dot(h) < 0.0;
  };
  auto visit = [&](auto&& self, const BvhNode& node) -> void {
    const WorldBox wb = worldBox(node, body.X_WB);
    if (!meets(wb)) return;
    if (node.isLeaf()) {
      const geometry::TriangleMesh& mesh = body.bvh->mesh();
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int f = body.bvh->order()[static_cast<std::size_t>(i)];
        WorldBox tb{Vector3d::Constant(kInf), Vector3d::Constant(-kInf)};
        for (int k = 0; k < 3; ++k) {
          const Vector3d p_W = body.X_WB * mesh.corner(f, k);
          tb = {tb.lo.cwiseMin(p_W), tb.hi.cwiseMax(p_W)};
        }
        if (!meets(tb)) continue;
        const WorldBox clipped = tb.intersected(box);
        out = {out.lo.cwiseMin(clipped.lo), out.hi.cwiseMax(clipped.hi)};
      }
      return;
    }
    self(self, body.bvh->nodes()[node.left]);
    self(self, body.bvh->nodes()[node.right]);
  };
  visit(visit, body.bvh->root());
  return out;
}

WorldBox overlapBox(const ColumnBody& a, const ColumnBody& b) {
  WorldBox box;
  for (int pass = 0; pass < 2 && !box.empty(); ++pass) {
    box = tighten(a, box, b);
    if (!box.empty()) box = tighten(b, box, a);
  }
  return box;
}

WorldBox unite(const WorldBox& x, const WorldBox& y) {
  return {x.lo.cwiseMin(y.lo), x.hi.cwiseMax(y.hi)};
}

/// Result of the three axis passes: the normal and a tighter box.
struct AxisPasses {
  Vector3d areaDifference = Vector3d::Zero();  ///< ∫_{∂B∩A} n_B dA − ∫_{∂A∩B} n_A dA
  WorldBox region{Vector3d::Constant(kInf), Vector3d::Constant(-kInf)};
  bool found = false;
};

/// One pass along each world axis. A line along e_k crossing ∂A inside B with normal n_A
/// adds sign(n_A·e_k) dS to (∫_{∂A∩B} n_A dA)_k, and likewise for ∂B2, so component k
/// of the MODEL.md §1 normal needs only crossing signs. The wet segments, widened by two cells
/// all round, bound the region as sampled. The three passes' bounds are united, not
/// intersected: a thin region that one pass resolves and another misses (two ribs pressed
/// unequally) must stay inside the box. A pass that sees no wet line at all (a layer a few µm
/// thick lying in a coordinate plane slips between the lines of the two passes across it)
/// adds nothing to the normal: its component comes from the boundary's thin side walls, whose
/// area vectors cancel to the order of the layer's thickness over its width.
/// With `only`, the passes see region only->id alone; with `segments`, they append their wet
/// pieces to it.
AxisPasses axisPasses(const ColumnBody& a, const ColumnBody& b, const WorldBox& box, int resolution,
                      const RegionFilter* only = nullptr,
                      std::vector<WetSegment>* segments = nullptr) {
  AxisPasses out;
  for (int k = 0; k < 3; ++k) {
    const Grid g(box, Vector3d::Unit(k), resolution);
    const GridSums s = integrate(a, b, g, nullptr, nullptr, only, segments);
    out.areaDifference[k] = s.surfaceB - s.surfaceA;
    if (s.wetLines == 0) continue;
    // Two cells of margin on every axis: a thin rim between sampled lines, or a line just
    // missed, lies within a cell of a wet one for any region the grid resolves.
    const Vector3d margin = Vector3d::Constant(2.0 * (box.hi - box.lo).maxCoeff() / resolution);
    const WorldBox wet{g.o + s.wet.lo - margin, g.o + s.wet.hi + margin};
    out.region = unite(out.region, wet);
  }
  out.region = out.region.intersected(box);
  out.found = !out.region.empty();
  return out;
}

// The normal passes run this many times finer than the first volume grid: the normal's error
// comes from the rim cells of three passes, and it tilts every column of the final grid.
constexpr int kNormalPassFactor = 4;

/// The first axis passes, from the options' first resolution up, that see the region at all.
std::optional<AxisPasses> firstSeen(const ColumnBody& a, const ColumnBody& b, const WorldBox& box,
                                    const ColumnOptions& options, const RegionFilter* only) {
  for (int res = options.initialResolution; res <= options.maxResolution; res *= 2) {
    AxisPasses passes = axisPasses(a, b, box, res, only);
    if (passes.found) return passes;
  }
  return std::nullopt;
}

/// The normal passes' result: the normal and the box to integrate over.
struct NormalAndBox {
  Vector3d n = Vector3d::Zero();               ///< zero when no pass saw the region
  Vector3d areaDifference = Vector3d::Zero();  ///< of the passes that gave n
  WorldBox box;
};

/// The contact normal and the box to integrate over: axis passes on `box`, refined until they
/// see the region, then repeated, finer, on the region's box so that a small region is
/// resolved. For a half-space the normal is its own (out of B into A). `seen` (if given) are
/// the first passes that saw it, already made; with `only`, of that region alone.
NormalAndBox normalAndBox(const ColumnBody& a, const ColumnBody& b, const WorldBox& box,
                          const ColumnOptions& options, const RegionFilter* only = nullptr,
                          std::optional<AxisPasses> seen = std::nullopt) {
  NormalAndBox out;
  out.box = box;
  if (!seen) seen = firstSeen(a, b, box, options, only);
  if (!seen) return out;
  const AxisPasses fine =
      axisPasses(a, b, seen->region, kNormalPassFactor * options.initialResolution, only);
  const AxisPasses& use = fine.found ? fine : *seen;
  out.box = use.region;
  out.areaDifference = use.areaDifference;
  if (!b.bvh) {
    out.n = b.X_WB.linear().col(2);
  } else if (!a.bvh) {
    out.n = -a.X_WB.linear().col(2);
  } else if (!use.areaDifference.isZero()) {
    out.n = use.areaDifference.normalized();
  }
  return out;
}

struct Refined {
  GridSums sums;                     ///< of the finest level
  int resolution = 0;                ///< its lines per side
  double error = kInf;               ///< the reported estimate
  std::vector<double> depth;         ///< δ per line of the finest level, when asked for
  std::vector<LineIntegrals> lines;  ///< line integrals of the finest level, when asked for
};

/// Refines the grid ×2 per level until two successive level-to-level changes of V are within
/// the tolerance; the larger of them is the estimate (one change alone can vanish by chance).
Refined refine(const ColumnBody& a, const ColumnBody& b, const WorldBox& box, const Vector3d& n,
               const ColumnOptions& options, bool wantDepth, bool wantLines,
               const RegionFilter* only = nullptr) {
  Refined r;
  r.resolution = options.initialResolution;
  r.sums = integrate(a, b, Grid(box, n, r.resolution), wantDepth ? &r.depth : nullptr,
                     wantLines ? &r.lines : nullptr, only);
  double previousChange = kInf;
  while (r.resolution < options.maxResolution) {
    r.resolution *= 2;
    const GridSums next =
        integrate(a, b, Grid(box, n, r.resolution), wantDepth ? &r.depth : nullptr,
                  wantLines ? &r.lines : nullptr, only);
    const double change = std::abs(next.M.m0 - r.sums.M.m0) / next.M.m0;
    r.error = std::max(change, previousChange);
    previousChange = change;
    r.sums = next;
    if (r.error <= options.relativeTolerance) break;
  }
  return r;
}

/// The δ map: the plate point and δ of every wet line.
DepthField fieldOf(const Grid& g, const std::vector<double>& depth) {
  DepthField field;
  field.cell_area = g.cellArea();
  for (int i = 0; i < g.n; ++i) {
    for (int j = 0; j < g.n; ++j) {
      const double d = depth[static_cast<std::size_t>(i) * g.n + j];
      if (d <= 0.0) continue;
      field.points_W.push_back(g.o + g.offset(i, j));
      field.depth.push_back(d);
    }
  }
  return field;
}

/// The fixed grid of a mesh M against a half-space H (ColumnOptions::fixed), laid in M's own
/// frame so that it moves with the body: e1 is M's x axis projected onto the plate (its y axis
/// when x is within 30° of n), and the rectangle bounds, along e1 and e2, the triangles of M
/// that reach below the plane (triangles, not leaves, so that the grid does not depend on the
/// tree's leaf size). The bound is therefore the same in any world
/// frame, tight for a face lying in M's axes, and constant while a face slides or spins on the
/// plate: no rim column enters or leaves, and V and the δ map are smooth in the pose. The
/// grid's origin lies in the plane.
/// @return the grid, or one with n = 0 when no triangle reaches below the plane
Grid fixedHalfspaceGrid(const MeshBvh& bvh, const Isometry3d& X_WM, const Isometry3d& X_WH,
                        const Vector3d& n, int resolution) {
  const Matrix3d& R_WM = X_WM.linear();
  const Vector3d z_H = X_WH.linear().col(2);
  const Matrix3d P = Matrix3d::Identity() - n * n.transpose();
  const Vector3d x = P * R_WM.col(0);
  // |P x| = sin∠(x, n) > 1/2: x more than 30° from n. The switch to y happens only for a
  // body turned far from lying on its x-y face, never in the small rocking of a face.
  constexpr double kInPlate = 0.5;
  const Vector3d e1 = (x.norm() > kInPlate ? x : Vector3d(P * R_WM.col(1))).normalized();
  const Vector3d e2 = n.cross(e1);
  // Axes in M, and the plane's height z_H(p_M) = z_M · p_M + z0 for a point of M.
  const Vector3d e1_M = R_WM.transpose() * e1, e2_M = R_WM.transpose() * e2;
  const Vector3d z_M = R_WM.transpose() * z_H;
  const double z0 = z_H.dot(X_WM.translation() - X_WH.translation());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInf), hi = Eigen::Vector2d::Constant(-kInf);
  auto visit = [&](auto&& self, const BvhNode& node) -> void {
    if (z_M.dot(node.center) + z0 - z_M.cwiseAbs().dot(node.halfExtent) >= 0.0) return;
    if (!node.isLeaf()) {
      self(self, bvh.nodes()[node.left]);
      self(self, bvh.nodes()[node.right]);
      return;
    }
    const geometry::TriangleMesh& mesh = bvh.mesh();
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int f = bvh.order()[static_cast<std::size_t>(i)];
      double lowest = kInf;
      for (int k = 0; k < 3; ++k) lowest = std::min(lowest, z_M.dot(mesh.corner(f, k)) + z0);
      if (lowest >= 0.0) continue;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d p(e1_M.dot(mesh.corner(f, k)), e2_M.dot(mesh.corner(f, k)));
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
  };
  visit(visit, bvh.root());
  if (!(lo.array() < hi.array()).all()) return Grid(Vector3d::Zero(), n, e1, 0.0, 0.0, 0);
  // Centre of the rectangle in W: M's origin plus the offsets along e1, e2, moved along n
  // into the plane.
  const Eigen::Vector2d mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  Vector3d o = X_WM.translation() + mid.x() * e1 + mid.y() * e2;
  o -= n * (n.dot(o - X_WH.translation()));
  return Grid(o, n, e1, half.x(), half.y(), resolution);
}

/// The contact of the sums over grid g: moments about g.o moved to the centroid.
ContactVolume assemble(const Grid& g, const GridSums& s, const Vector3d& n) {
  return contactFromMoments(s.M, g.o, n, s.wetLines * g.cellArea(), s.maxDepth, Method::kColumns);
}

/// The slope (along n, per unit across the plate) up to which a thin region's neighbouring
/// lines stay joined: tan 76°. A peg pressed sideways into its hole's wall overlaps it in a
/// crescent, 5 µm thick where its wings reach 70° from the pair's normal; regions apart along
/// n by more than 4 line spacings (opposite walls of a hole, millimetres against tens of µm)
/// stay apart.
constexpr double kJoinSlope = 4.0;

/// Do the wet parts of two neighbouring lines, h apart, belong to one region? Their spans
/// [tFirst, tLast] along n overlap once grown by kJoinSlope·h: between the two lines, a
/// boundary sloped up to kJoinSlope moves by at most that along n.
bool spansTouch(const LineIntegrals& x, const LineIntegrals& y, double h) {
  const double reach = kJoinSlope * h;
  return y.L > 0.0 && x.tFirst <= y.tLast + reach && y.tFirst <= x.tLast + reach;
}

/// The wet lines of grid g grouped into patches: lines joined to their four neighbours whose
/// spans along n touch (spansTouch), each group summed alone (row by row) with the pair's
/// normal n and estimate `error`. Two regions stacked on one line are one patch.
std::vector<ContactVolume> columnPatches(const Grid& g, const std::vector<LineIntegrals>& lines,
                                         const Vector3d& n, double error) {
  const auto at = [&g](int i, int j) { return static_cast<std::size_t>(i) * g.n + j; };
  const double h1 = 2.0 * g.r1 / g.n, h2 = 2.0 * g.r2 / g.n;  // line spacing along e1, e2
  std::vector<int> label(lines.size(), -1);
  std::vector<std::pair<int, int>> stack;
  int groups = 0;
  for (int i = 0; i < g.n; ++i) {
    for (int j = 0; j < g.n; ++j) {
      if (lines[at(i, j)].L <= 0.0 || label[at(i, j)] >= 0) continue;
      label[at(i, j)] = groups;
      stack.assign(1, {i, j});
      while (!stack.empty()) {
        const auto [k, l] = stack.back();
        stack.pop_back();
        for (const auto& [dk, dl] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int k2 = k + dk, l2 = l + dl;
          if (k2 < 0 || l2 < 0 || k2 >= g.n || l2 >= g.n || label[at(k2, l2)] >= 0 ||
              !spansTouch(lines[at(k, l)], lines[at(k2, l2)], dk != 0 ? h1 : h2)) {
            continue;
          }
          label[at(k2, l2)] = groups;
          stack.push_back({k2, l2});
        }
      }
      ++groups;
    }
  }
  std::vector<GridSums> sums(static_cast<std::size_t>(groups));
  for (int i = 0; i < g.n; ++i) {
    for (int j = 0; j < g.n; ++j) {
      if (label[at(i, j)] < 0) continue;
      sums[static_cast<std::size_t>(label[at(i, j)])].add(lines[at(i, j)], g.offset(i, j), g.u,
                                                          g.cellArea());
    }
  }
  std::vector<ContactVolume> patches;
  for (const GridSums& s : sums) {
    patches.push_back(assemble(g, s, n));
    patches.back().relative_error = error;
  }
  return patches;
}

/// ColumnOptions::fixed against a half-space: one grid (fixedHalfspaceGrid), the plane's normal
/// (out of B into A), no axis passes, no estimate.
ContactVolume fixedHalfspaceContact(const ColumnBody& a, const ColumnBody& b, int resolution,
                                    DepthField* field, std::vector<ContactVolume>* patches) {
  const ColumnBody& mesh = a.bvh ? a : b;
  const ColumnBody& plane = a.bvh ? b : a;
  const Vector3d n = a.bvh ? Vector3d(b.X_WB.linear().col(2)) : Vector3d(-a.X_WB.linear().col(2));
  const Grid g = fixedHalfspaceGrid(*mesh.bvh, mesh.X_WB, plane.X_WB, n, resolution);
  if (g.n == 0) return {.method = Method::kColumns};
  std::vector<double> depth;
  std::vector<LineIntegrals> lines;
  const GridSums sums = integrate(a, b, g, field ? &depth : nullptr, patches ? &lines : nullptr);
  if (!(sums.M.m0 > 0.0)) return {.method = Method::kColumns};
  if (field) *field = fieldOf(g, depth);
  if (patches) *patches = columnPatches(g, lines, n, kInf);
  ContactVolume cv = assemble(g, sums, n);
  cv.relative_error = kInf;
  return cv;
}

/// The regions of two meshes, and the pair's normal and box. The fine lines laid over the
/// whole overlap box meet any region one of their spacings across (a second, thinner region
/// that no coarse line met among them) and their pieces, on voxels of that spacing, show how
/// many regions there are (VoxelRegions). One region: the passes of normalAndBox over the
/// coarse and wide bounds, and no patch list (the pair's contact is the region's). Several:
/// each region alone (RegionFilter) with its own normal from its own axis passes, over its own
/// box, refined to the options' tolerance; the pair's normal is that of the sum of their
/// boundary area vectors (MODEL.md §1 over the whole of A ∩ B), its box their union.
NormalAndBox meshPairRegions(const ColumnBody& a, const ColumnBody& b, const WorldBox& overlap,
                             const ColumnOptions& options, std::vector<ContactVolume>& patches) {
  NormalAndBox pair;
  std::optional<AxisPasses> seen = firstSeen(a, b, overlap, options, nullptr);
  if (!seen) return pair;
  const int fineResolution = kNormalPassFactor * options.initialResolution;
  std::vector<WetSegment> pieces;
  const AxisPasses wide = axisPasses(a, b, overlap, fineResolution, nullptr, &pieces);
  const double size = (overlap.hi - overlap.lo).maxCoeff() / fineResolution;
  const VoxelRegions regions = voxelRegions(pieces, overlap, size);
  if (regions.count <= 1) {
    // The fine passes over the coarse bound, grown by what the wide lines saw beyond it: where
    // the coarse bound held it all, the passes columnsContact made before it looked for
    // regions, and so the same normal and box.
    if (wide.found) seen->region = unite(seen->region, wide.region);
    return normalAndBox(a, b, overlap, options, nullptr, seen);
  }
  pair.box = {Vector3d::Constant(kInf), Vector3d::Constant(-kInf)};
  for (int id = 0; id < regions.count; ++id) {
    const RegionFilter only{&regions, id};
    const WorldBox box = regions.boxes[static_cast<std::size_t>(id)].intersected(overlap);
    const NormalAndBox own = normalAndBox(a, b, box, options, &only);
    if (own.n.isZero()) continue;
    const Refined r = refine(a, b, own.box, own.n, options, false, false, &only);
    if (!(r.sums.M.m0 > 0.0)) continue;
    patches.push_back(assemble(Grid(own.box, own.n, r.resolution), r.sums, own.n));
    patches.back().relative_error = r.error;
    pair.areaDifference += own.areaDifference;
    pair.box = unite(pair.box, own.box);
  }
  if (!pair.areaDifference.isZero()) pair.n = pair.areaDifference.normalized();
  return pair;
}

/// columnsContact, and with `patches`, its patches: for two meshes (refined grids) the regions
/// of meshPairRegions, otherwise the finest grid's columnPatches.
ContactVolume columnsWithPatches(const ColumnBody& a, const ColumnBody& b,
                                 const ColumnOptions& options, DepthField* field,
                                 std::vector<ContactVolume>* patches) {
  if (!a.bvh && !b.bvh) throw std::invalid_argument("columnsContact: two half-spaces");
  if (options.isFixed() && (!a.bvh || !b.bvh)) {
    return fixedHalfspaceContact(a, b, options.initialResolution, field, patches);
  }
  const ContactVolume none{.method = Method::kColumns};
  const WorldBox overlap = overlapBox(a, b);
  if (overlap.empty()) return none;
  // A mesh on a half-space has the plane's normal for every region, and the volume grid's
  // lines group them; so does a fixed grid, which keeps its cost.
  const bool byRegion = a.bvh && b.bvh && !options.isFixed();
  std::vector<ContactVolume> regionPatches;
  const NormalAndBox nb = byRegion ? meshPairRegions(a, b, overlap, options, regionPatches)
                                   : normalAndBox(a, b, overlap, options);
  if (nb.n.isZero()) return none;
  const Refined r =
      refine(a, b, nb.box, nb.n, options, field != nullptr, patches != nullptr && !byRegion);
  if (!(r.sums.M.m0 > 0.0)) return none;
  const Grid g(nb.box, nb.n, r.resolution);
  if (field) *field = fieldOf(g, r.depth);
  if (patches)
    *patches = byRegion ? std::move(regionPatches) : columnPatches(g, r.lines, nb.n, r.error);
  ContactVolume cv = assemble(g, r.sums, nb.n);
  cv.relative_error = r.error;
  return cv;
}

/// A mesh (with its cached tree) or a half-space as a column-method body; null otherwise.
std::optional<ColumnBody> columnBody(const geometry::Shape& s, const Isometry3d& X_WS,
                                     std::shared_ptr<const MeshBvh>& keepAlive) {
  if (std::holds_alternative<geometry::HalfSpace>(s)) return ColumnBody{nullptr, X_WS};
  const auto* mesh = std::get_if<geometry::Mesh>(&s);
  if (!mesh) return std::nullopt;
  keepAlive = bvhOf(mesh->mesh);
  return ColumnBody{keepAlive.get(), X_WS};
}

/// Two shapes as column-method bodies, with the trees they use.
struct ColumnPair {
  std::shared_ptr<const MeshBvh> bvhA, bvhB;
  ColumnBody a, b;
};

/// @throws InputError when the pair is not handled, naming both shapes
ColumnPair columnPair(const geometry::Shape& a, const Isometry3d& X_WA, const geometry::Shape& b,
                      const Isometry3d& X_WB) {
  ColumnPair pair;
  const std::optional<ColumnBody> bodyA = columnBody(a, X_WA, pair.bvhA);
  const std::optional<ColumnBody> bodyB = columnBody(b, X_WB, pair.bvhB);
  if (!bodyA || !bodyB || (!bodyA->bvh && !bodyB->bvh)) {
    throw InputError("volume method columns",
                     "cannot compute " + geometry::describe(a) + " against " +
                         geometry::describe(b) +
                         " with this method; it integrates columns through two meshes, or a mesh "
                         "and a half-space");
  }
  pair.a = *bodyA;
  pair.b = *bodyB;
  return pair;
}

}  // namespace

ContactVolume columnsContact(const geometry::Shape& a, const Isometry3d& X_WA,
                             const geometry::Shape& b, const Isometry3d& X_WB, DepthField* field,
                             const ColumnOptions& options) {
  const ColumnPair pair = columnPair(a, X_WA, b, X_WB);
  return columnsContact(pair.a, pair.b, options, field);
}

ContactVolume columnsContact(const ColumnBody& a, const ColumnBody& b, const ColumnOptions& options,
                             DepthField* field) {
  return columnsWithPatches(a, b, options, field, nullptr);
}

ContactPatches columnsPatches(const geometry::Shape& a, const Isometry3d& X_WA,
                              const geometry::Shape& b, const Isometry3d& X_WB, DepthField* field,
                              const ColumnOptions& options) {
  const ColumnPair pair = columnPair(a, X_WA, b, X_WB);
  std::vector<ContactVolume> patches;
  ContactPatches out = singlePatch(columnsWithPatches(pair.a, pair.b, options, field, &patches));
  if (!out.inContact() || patches.size() <= 1) return out;
  sortPatches(patches);
  out.patches = std::move(patches);
  return out;
}

}  // namespace vcontact::volume
