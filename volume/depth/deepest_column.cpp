#include "volume/depth/deepest_column.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace vcontact::volume {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

/// |n_f·n| at or below this: the face is a wall (parallel to the columns), seen only through
/// its edges. Above it the plane's height is evaluated and clamped to the face's own range,
/// so a steep face's large slope does no harm.
constexpr double kWall = 1e-12;
/// The boxes of the quick rejections are grown by this many τ: a segment beyond 2τ of a point
/// (or of another segment) is beyond τ by far more than the rounding of the exact formulas
/// (a few ε of the coordinates, against τ = 1e-12 of them), which would reject it as well.
constexpr double kBoxGrowth = 2.0;
/// The test |den| > τ·√m of crossingDepth decided on squares where they differ by more than
/// this fraction (a few ulps of rounding either way), by the square root in the band between.
constexpr double kSquareBand = 1e-9;
/// The heights the pass computes on a segment, h_a + t (h_b − h_a) with t in [0, 1], lie within
/// [min, max] of its ends up to about 7 ulps of max(|h_a|, |h_b|) (three roundings); its bounds
/// are widened by this fraction of that size (about 90 ulps), so that they hold for the
/// computed values, not only for the exact ones.
constexpr double kSlack = 1e-14;

double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

void ColumnDepth::clear() { input_.clear(); }

void ColumnDepth::add(std::uint64_t faceKey, const Vector3d& n_f, const Vector3d& p,
                      const Vector3d& q) {
  input_.push_back({faceKey, n_f, p, q});
}

/// Face block (r, c) of kBlock × kBlock cells as a bin index; with `count`, the number of
/// blocks.
int ColumnDepth::blockOf(int r, int c, bool count) const {
  const int bx = (grid_.nx + kBlock - 1) / kBlock, by = (grid_.ny + kBlock - 1) / kBlock;
  return count ? bx * by : r * bx + c;
}

/// order_: the indices of input_ sorted by face key, those of one key in the order added. A
/// least-significant-digit radix sort by bytes, each pass stable, skipping the bytes in which
/// all keys agree (a face key varies in its two low bytes and in the side's): linear in the
/// segments, where a comparison sort of one run per segment (the pieces of a face are seldom
/// added one after the other) took a fifth of the pass.
void ColumnDepth::groupByFace() {
  const std::size_t n = input_.size();
  keyed_.resize(n);
  keyedSpare_.resize(n);
  std::uint64_t differ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    keyed_[i] = {input_[i].key, static_cast<int>(i)};
    differ |= input_[i].key ^ input_[0].key;
  }
  for (int shift = 0; shift < 64; shift += 8) {
    if (((differ >> shift) & 0xffu) == 0) continue;
    int start[257] = {};
    for (const auto& e : keyed_) ++start[((e.first >> shift) & 0xffu) + 1];
    for (int b = 1; b < 257; ++b) start[b] += start[b - 1];
    for (const auto& e : keyed_) keyedSpare_[start[(e.first >> shift) & 0xffu]++] = e;
    keyed_.swap(keyedSpare_);
  }
  order_.resize(n);
  for (std::size_t i = 0; i < n; ++i) order_[i] = keyed_[i].second;
}

/// Segments on the plate (u, v ⊥ n, about o) with their heights along n, grouped by face.
void ColumnDepth::project(const Vector3d& n, const Vector3d& o) {
  const Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  groupByFace();
  segs_.clear();
  faces_.clear();
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const Input& in = input_[static_cast<std::size_t>(order_[k])];
    const Vector3d p = in.p - o, q = in.q - o;
    const Vector2d a(u.dot(p), v.dot(p)), b(u.dot(q), v.dot(q));
    const double ha = n.dot(p), hb = n.dot(q);
    const double slack = kSlack * std::max(std::abs(ha), std::abs(hb)) +
                         4 * std::numeric_limits<double>::denorm_min();
    const Seg s{a,
                b,
                ha,
                hb,
                0,
                0,
                a.cwiseMin(b),
                a.cwiseMax(b),
                (b - a).norm(),
                std::min(ha, hb) - slack,
                std::max(ha, hb) + slack,
                slack};
    if (k == 0 || in.key != input_[static_cast<std::size_t>(order_[k - 1])].key) {
      const double c = in.n_f.dot(n);
      const int seg = static_cast<int>(segs_.size());
      Face f{0.0, 0.0, 0.0, s.ha, s.ha, s.a, s.a, 0, seg, seg};
      if (std::abs(c) > kWall) {
        // n_f·(x u + y v + h n) = n_f·p  ⇒  h = n_f·p / c − (n_f·u / c) x − (n_f·v / c) y
        f.slope_u = in.n_f.dot(u) / c;
        f.slope_v = in.n_f.dot(v) / c;
        f.h0 = in.n_f.dot(p) / c;
        f.side = c > 0 ? 1 : -1;
      }
      faces_.push_back(f);
    }
    Face& f = faces_.back();
    f.lo = std::min({f.lo, s.ha, s.hb});
    f.hi = std::max({f.hi, s.ha, s.hb});
    f.bmin = f.bmin.cwiseMin(s.a).cwiseMin(s.b);
    f.bmax = f.bmax.cwiseMax(s.a).cwiseMax(s.b);
    ++f.s1;
    segs_.push_back(s);
    segs_.back().face = static_cast<int>(faces_.size()) - 1;
  }
  for (Seg& s : segs_) s.side = faces_[static_cast<std::size_t>(s.face)].side;
}

/// About one cell per segment over the projections' bounding box (τ added around it).
void ColumnDepth::buildGrid() {
  Vector2d lo = segs_.front().a, hi = lo;
  for (const Seg& s : segs_) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const double W = hi.x() - lo.x() + 2 * tau_, H = hi.y() - lo.y() + 2 * tau_;
  const double n = static_cast<double>(segs_.size());
  const double cap = 4.0 * n + 1.0;  // cells per axis for a region thin along one of them
  double h = std::sqrt(W * H / n);
  if (!(h > 0.0)) h = std::max(W, H) / n;
  grid_.nx = static_cast<int>(std::clamp(std::ceil(W / h), 1.0, cap));
  grid_.ny = static_cast<int>(std::clamp(std::ceil(H / h), 1.0, cap));
  grid_.x0 = lo.x() - tau_;
  grid_.y0 = lo.y() - tau_;
  grid_.hx = W > 0.0 ? W / grid_.nx : 1.0;
  grid_.hy = H > 0.0 ? H / grid_.ny : 1.0;
  grid_.inv_hx = 1.0 / grid_.hx;
  grid_.inv_hy = 1.0 / grid_.hy;
  // The blocks of kBlock × kBlock cells as a grid of their own (the rounding of its cells'
  // edges against those of the cells is covered by the filing's reach, deepest()).
  blocks_ = grid_;
  blocks_.nx = (grid_.nx + kBlock - 1) / kBlock;
  blocks_.ny = (grid_.ny + kBlock - 1) / kBlock;
  blocks_.hx = kBlock * grid_.hx;
  blocks_.hy = kBlock * grid_.hy;
  blocks_.inv_hx = 1.0 / blocks_.hx;
  blocks_.inv_hy = 1.0 / blocks_.hy;
}

/// Whether x lies inside the projection of face f: the crossing number along +u over the
/// face's own boundary loops (each edge meets the line v = x.v once at most).
bool ColumnDepth::holds(const Face& f, const Vector2d& x) const {
  if (x.x() < f.bmin.x() || x.x() > f.bmax.x() || x.y() < f.bmin.y() || x.y() > f.bmax.y()) {
    return false;
  }
  bool inside = false;
  for (int k = f.s0; k < f.s1; ++k) {
    const Seg& s = segs_[static_cast<std::size_t>(k)];
    if ((s.a.y() > x.y()) == (s.b.y() > x.y())) continue;
    const double xc = s.a.x() + (x.y() - s.a.y()) * (s.b.x() - s.a.x()) / (s.b.y() - s.a.y());
    if (xc > x.x()) inside = !inside;
  }
  return inside;
}

/// Is x beyond g of segment s's bounding box?
bool ColumnDepth::misses(const Seg& s, const Vector2d& x, double g) {
  return (x.x() < s.lo.x() - g) | (x.x() > s.hi.x() + g) | (x.y() < s.lo.y() - g) |
         (x.y() > s.hi.y() + g);
}

bool ColumnDepth::inBox(const Face& F, const Vector2d& x) {
  return x.x() >= F.bmin.x() && x.x() <= F.bmax.x() && x.y() >= F.bmin.y() && x.y() <= F.bmax.y();
}

/// The height of face F's plane over x, clamped to the face's range.
double ColumnDepth::height(const Face& F, const Vector2d& x) {
  return std::clamp(F.h0 - F.slope_u * x.x() - F.slope_v * x.y(), F.lo, F.hi);
}

/// A bound of columnSpanAt(x, h) without its exact tests: the ranges of the edges whose box
/// holds x (each the least of its whole range and, with the cell's trend, its detrended range
/// about x, depth/deepest_column_trend.cpp) and the heights of the faces whose box does (rounding
/// is monotonic).
double ColumnDepth::columnBound(const Vector2d& x, double h, int cell, int block) const {
  const double g = kBoxGrowth * tau_;
  const bool trend = trend_.valid && cellOfTrend_ == cell;
  const double gx = trend ? trend_.g.dot(x) : 0.0, margin = trend ? trendMargin(gx) : 0.0;
  double hi = h, lo = h;
  for (int k = segBegin_[cell]; k < segEnd_[cell]; ++k) {
    const Seg& s = cellSeg(k);
    if (misses(s, x, g)) continue;
    if (trend) {
      const auto& [dlo, dhi] = trendRange_[static_cast<std::size_t>(k - segBegin_[cell])];
      hi = std::max(hi, std::min(s.hmax, dhi + gx + margin));
      lo = std::min(lo, std::max(s.hmin, dlo + gx - margin));
    } else {
      hi = std::max(hi, s.hmax);
      lo = std::min(lo, s.hmin);
    }
  }
  for (int k = faceStart_[block]; k < faceStart_[block + 1]; ++k) {
    const Face& F = faces_[static_cast<std::size_t>(cellFaces_[k])];
    if (!inBox(F, x)) continue;
    const double z = height(F, x);
    hi = std::max(hi, z);
    lo = std::min(lo, z);
  }
  return hi - lo;
}

/// The span along n of the closed boundary on the column through x (a vertex at height h), or
/// 0 where that span cannot exceed `best` (≥ 0).
double ColumnDepth::columnSpanAt(const Vector2d& x, double h, double best) const {
  const int cell = grid_.row(x.y()) * grid_.nx + grid_.col(x.x());
  const int block = blockOf(grid_.row(x.y()) / kBlock, grid_.col(x.x()) / kBlock);
  if (columnBound(x, h, cell, block) <= best) return 0.0;
  double lo = h, hi = h;
  const auto reach = [&](double z) {
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  };
  // Edges within τ: the heights over the part of each that lies within τ of the column.
  const double g = kBoxGrowth * tau_;
  for (int k = segBegin_[cell]; k < segEnd_[cell]; ++k) {
    const Seg& s = segs_[static_cast<std::size_t>(cellSegs_[k])];
    if (misses(s, x, g)) continue;
    const Vector2d d = s.b - s.a, w = x - s.a;
    const double L2 = d.squaredNorm();
    if (L2 == 0.0) {  // an edge along n
      if (w.norm() <= tau_) reach(s.ha), reach(s.hb);
      continue;
    }
    const double L = std::sqrt(L2), e = std::abs(cross2(d, w)) / L;
    if (e > tau_) continue;
    const double t = w.dot(d) / L2, half = std::sqrt(tau_ * tau_ - e * e) / L;
    if (t + half < 0.0 || t - half > 1.0) continue;
    const double t0 = std::max(t - half, 0.0), t1 = std::min(t + half, 1.0);
    reach(s.ha + t0 * (s.hb - s.ha));
    reach(s.ha + t1 * (s.hb - s.ha));
  }
  // The top and bottom faces whose projection holds x: the column meets their planes there.
  // A height within [lo, hi] changes neither: its face's crossing-number test is skipped.
  for (int k = faceStart_[block]; k < faceStart_[block + 1]; ++k) {
    const Face& F = faces_[static_cast<std::size_t>(cellFaces_[k])];
    if (!inBox(F, x)) continue;
    const double z = height(F, x);
    if ((z < lo || z > hi) && holds(F, x)) reach(z);
  }
  return hi - lo;
}

/// Is segment t farther than g from the line of s, all on one side (cross products against
/// s's direction, of length `len`)?
bool ColumnDepth::beyondLine(const Seg& s, const Seg& t, double g) {
  const Vector2d ds = s.b - s.a;
  const double c1 = cross2(ds, t.a - s.a), c2 = cross2(ds, t.b - s.a), limit = g * s.len;
  return ((c1 > limit) & (c2 > limit)) | ((c1 < -limit) & (c2 < -limit));
}

/// Are s and t one segment (a crossing line t_A ∩ t_B bounds a face of each body: one is a
/// top face, the other a bottom one)? Then dt = ±ds exactly, and crossingDepth's den is 0, or
/// its rounding with a fused multiply-add (ε|ds|², far below τ|ds|): it would skip them.
bool ColumnDepth::sameEnds(const Seg& s, const Seg& t) {
  return (s.a == t.b && s.b == t.a) || (s.a == t.a && s.b == t.b);
}

/// The largest height difference of a top edge over a bottom edge where their projections
/// cross within the cell (the cell's list holds its top edges first, then its bottom edges).
/// A pair is evaluated with s the edge of lower index, as every pass of the grid sees it.
/// Pairs whose boxes, grown by 2τ, miss each other, or of which one edge lies beyond 2τ of the
/// other's line, are passed over: where the formulas below accept a pair, its crossing point
/// lies on s and within τ of t, both to a rounding far below τ, so the edges come within
/// about τ of each other, and of each other's lines.
double ColumnDepth::crossingsIn(int cell, double best) const {
  const int first = segBegin_[cell], last = segEnd_[cell];
  int bottoms = first;
  while (bottoms < last && segs_[static_cast<std::size_t>(cellSegs_[bottoms])].side > 0) {
    ++bottoms;
  }
  int walls = bottoms;
  while (walls < last && segs_[static_cast<std::size_t>(cellSegs_[walls])].side < 0) ++walls;
  const double g = kBoxGrowth * tau_;
  for (int i = first; i < bottoms; ++i) {
    const Seg& top = segs_[static_cast<std::size_t>(cellSegs_[i])];
    const Vector2d lo = top.lo.array() - g, hi = top.hi.array() + g;
    for (int j = bottoms; j < walls; ++j) {
      const Seg& bottom = segs_[static_cast<std::size_t>(cellSegs_[j])];
      if (top.hmax - bottom.hmin <= best) continue;  // cannot beat best (boundCells)
      if ((bottom.hi.x() < lo.x()) | (bottom.lo.x() > hi.x()) | (bottom.hi.y() < lo.y()) |
              (bottom.lo.y() > hi.y()) ||
          sameEnds(top, bottom) || beyondLine(top, bottom, g) || beyondLine(bottom, top, g)) {
        continue;
      }
      const bool topFirst = cellSegs_[i] < cellSegs_[j];
      best = std::max(best, crossingDepth(topFirst ? top : bottom, topFirst ? bottom : top));
    }
  }
  return best;
}

/// The height of the top edge over the bottom one where the projections of s and t (one of
/// each) cross, or 0 where they do not.
double ColumnDepth::crossingDepth(const Seg& s, const Seg& t) const {
  const Vector2d ds = s.b - s.a, dt = t.b - t.a, w = t.a - s.a;
  const double den = cross2(ds, dt), dt2 = dt.squaredNorm();
  // Edges that stay within τ of each other's line over their length (sin α · length ≤ τ):
  // δ is linear along their overlap, whose ends are vertex columns, which see the other
  // edge within τ. Skipped here, where their crossing would be ill-conditioned.
  const double m = std::min(ds.squaredNorm(), dt2), den2 = den * den, tau2m = tau_ * tau_ * m;
  if (den2 <= (1.0 - kSquareBand) * tau2m) return 0.0;
  if (den2 < (1.0 + kSquareBand) * tau2m && !(std::abs(den) > tau_ * std::sqrt(m))) return 0.0;
  const double a = cross2(w, dt) / den;
  if (a < 0.0 || a > 1.0) return 0.0;
  // t's height at the foot of s's crossing point on t: both at one column (to τ) even
  // where the rounding moves the crossing along the edges
  const Vector2d x = s.a + a * ds;
  const double b = (x - t.a).dot(dt) / dt2;
  if (b < 0.0 || b > 1.0 || (t.a + b * dt - x).norm() > tau_) return 0.0;
  const double hs = s.ha + a * (s.hb - s.ha), ht = t.ha + b * (t.hb - t.ha);
  return s.side > 0 ? hs - ht : ht - hs;
}

/// The candidates of cell c (its vertex columns, its top/bottom crossings) that can raise best;
/// none where the cell's detrended bound shows that none can.
double ColumnDepth::evaluateCell(int c, double best) {
  if (detrendedBound(c) <= best) return best;  // depth/deepest_column_trend.cpp
  // Equal first ends (the same computed point, filed by several faces) are one column,
  // evaluated once.
  const auto key = [this](int i) {
    const Seg& s = segs_[static_cast<std::size_t>(i)];
    return std::tuple(s.a.x(), s.a.y(), s.ha);
  };
  cellScratch_.assign(cellVertices_.begin() + vertexBegin_[c],
                      cellVertices_.begin() + vertexEnd_[c]);
  std::sort(cellScratch_.begin(), cellScratch_.end(),
            [&](int i, int j) { return key(i) < key(j); });
  for (std::size_t k = 0; k < cellScratch_.size(); ++k) {
    if (k > 0 && key(cellScratch_[k]) == key(cellScratch_[k - 1])) continue;
    const Seg& s = segs_[static_cast<std::size_t>(cellScratch_[k])];
    best = std::max(best, columnSpanAt(s.a, s.ha, best));
  }
  return crossingsIn(c, best);
}

}  // namespace vcontact::volume
