#include "deepest_column_reference.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace vcontact::volume::test {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

/// τ as a fraction of the largest coordinate: two boundary points on one column (a vertex of
/// one body straight above a crossing on the other) differ in projection by their rounding, a
/// few ε of that size (≈ 1e-15); 1e-12 covers it a thousand times (as the box margin of
/// fast/surface_integration.cpp does). The column's span is taken over this reach, which adds at
/// most τ times the boundary's slope to the depth (a 1 m part at the origin, slope 1: 1e-12 m).
constexpr double kReach = 1e-12;
/// |n_f·n| at or below this: the face is a wall (parallel to the columns), seen only through
/// its edges. Above it the plane's height is evaluated and clamped to the face's own range,
/// so a steep face's large slope does no harm.
constexpr double kWall = 1e-12;

double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

void ReferenceColumnDepth::clear() { input_.clear(); }

void ReferenceColumnDepth::add(std::uint64_t faceKey, const Vector3d& n_f, const Vector3d& p,
                               const Vector3d& q) {
  input_.push_back({faceKey, n_f, p, q});
}

int ReferenceColumnDepth::Grid::col(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - x0) / hx)), 0, nx - 1);
}

int ReferenceColumnDepth::Grid::row(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - y0) / hy)), 0, ny - 1);
}

/// Segments on the plate (u, v ⊥ n, about o) with their heights along n, grouped by face.
void ReferenceColumnDepth::project(const Vector3d& n, const Vector3d& o) {
  const Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  order_.resize(input_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  std::sort(order_.begin(), order_.end(), [this](int i, int j) {
    const auto ki = input_[static_cast<std::size_t>(i)].key;
    const auto kj = input_[static_cast<std::size_t>(j)].key;
    return ki != kj ? ki < kj : i < j;
  });
  segs_.clear();
  faces_.clear();
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const Input& in = input_[static_cast<std::size_t>(order_[k])];
    const Vector3d p = in.p - o, q = in.q - o;
    const Seg s{{u.dot(p), v.dot(p)}, {u.dot(q), v.dot(q)}, n.dot(p), n.dot(q), 0};
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
}

/// About one cell per segment over the projections' bounding box (τ added around it).
void ReferenceColumnDepth::buildGrid() {
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
}

/// Files segment s, row by row, in the cells its projection passes within τ of.
void ReferenceColumnDepth::fileSegment(int index) {
  const Seg& s = segs_[static_cast<std::size_t>(index)];
  const double ylo = std::min(s.a.y(), s.b.y()), yhi = std::max(s.a.y(), s.b.y());
  const double dy = s.b.y() - s.a.y();
  const int r0 = grid_.row(ylo - tau_), r1 = grid_.row(yhi + tau_);
  for (int r = r0; r <= r1; ++r) {
    double xlo = std::min(s.a.x(), s.b.x()), xhi = std::max(s.a.x(), s.b.x());
    if (dy != 0.0) {  // the x range of the segment within this row's slab
      const double y0 = std::clamp(grid_.y0 + r * grid_.hy - tau_, ylo, yhi);
      const double y1 = std::clamp(grid_.y0 + (r + 1) * grid_.hy + tau_, ylo, yhi);
      const double x0 = s.a.x() + (y0 - s.a.y()) * (s.b.x() - s.a.x()) / dy;
      const double x1 = s.a.x() + (y1 - s.a.y()) * (s.b.x() - s.a.x()) / dy;
      xlo = std::max(xlo, std::min(x0, x1));
      xhi = std::min(xhi, std::max(x0, x1));
    }
    const int c0 = grid_.col(xlo - tau_), c1 = grid_.col(xhi + tau_);
    for (int c = c0; c <= c1; ++c) segPairs_.emplace_back(r * grid_.nx + c, index);
  }
}

/// Files a top or bottom face in the cells its projection's bounding box covers (a point of
/// the face lies in one of them; a wall holds no column's inside and is not filed).
void ReferenceColumnDepth::fileFace(int index) {
  const Face& f = faces_[static_cast<std::size_t>(index)];
  if (f.side == 0) return;
  const int r0 = grid_.row(f.bmin.y()), r1 = grid_.row(f.bmax.y());
  const int c0 = grid_.col(f.bmin.x()), c1 = grid_.col(f.bmax.x());
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) facePairs_.emplace_back(r * grid_.nx + c, index);
  }
}

/// (bin, item) pairs to compressed rows: bin b's items are items[start[b] .. start[b + 1]).
void ReferenceColumnDepth::toCsr(std::vector<std::pair<int, int>>& pairs, int bins,
                                 std::vector<int>& start, std::vector<int>& items) {
  start.assign(static_cast<std::size_t>(bins) + 1, 0);
  for (const auto& [bin, item] : pairs) ++start[static_cast<std::size_t>(bin) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  items.resize(pairs.size());
  std::vector<int>& next = next_;
  next.assign(start.begin(), start.end() - 1);
  for (const auto& [bin, item] : pairs) items[static_cast<std::size_t>(next[bin]++)] = item;
  pairs.clear();
}

/// Whether x lies inside the projection of face f: the crossing number along +u over the
/// face's own boundary loops (each edge meets the line v = x.v once at most).
bool ReferenceColumnDepth::holds(const Face& f, const Vector2d& x) const {
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

/// The span along n of the closed boundary on the column through x (a vertex at height h).
double ReferenceColumnDepth::columnSpanAt(const Vector2d& x, double h) const {
  double lo = h, hi = h;
  const auto reach = [&](double z) {
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  };
  const int cell = grid_.row(x.y()) * grid_.nx + grid_.col(x.x());
  // Edges within τ: the heights over the part of each that lies within τ of the column.
  for (int k = segStart_[cell]; k < segStart_[cell + 1]; ++k) {
    const Seg& s = segs_[static_cast<std::size_t>(cellSegs_[k])];
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
  for (int k = faceStart_[cell]; k < faceStart_[cell + 1]; ++k) {
    const Face& F = faces_[static_cast<std::size_t>(cellFaces_[k])];
    if (holds(F, x)) reach(std::clamp(F.h0 - F.slope_u * x.x() - F.slope_v * x.y(), F.lo, F.hi));
  }
  return hi - lo;
}

/// The largest height difference of a top edge over a bottom edge where their projections
/// cross within the cell.
double ReferenceColumnDepth::crossingsIn(int cell) const {
  double best = 0.0;
  for (int i = segStart_[cell]; i < segStart_[cell + 1]; ++i) {
    const Seg& s = segs_[static_cast<std::size_t>(cellSegs_[i])];
    const int side = faces_[static_cast<std::size_t>(s.face)].side;
    if (side == 0) continue;
    for (int j = i + 1; j < segStart_[cell + 1]; ++j) {
      const Seg& t = segs_[static_cast<std::size_t>(cellSegs_[j])];
      if (faces_[static_cast<std::size_t>(t.face)].side != -side) continue;
      const Vector2d ds = s.b - s.a, dt = t.b - t.a, w = t.a - s.a;
      const double den = cross2(ds, dt), dt2 = dt.squaredNorm();
      // Edges that stay within τ of each other's line over their length (sin α · length ≤ τ):
      // δ is linear along their overlap, whose ends are vertex columns, which see the other
      // edge within τ. Skipped here, where their crossing would be ill-conditioned.
      if (!(std::abs(den) > tau_ * std::sqrt(std::min(ds.squaredNorm(), dt2)))) continue;
      const double a = cross2(w, dt) / den;
      if (a < 0.0 || a > 1.0) continue;
      // t's height at the foot of s's crossing point on t: both at one column (to τ) even
      // where the rounding moves the crossing along the edges
      const Vector2d x = s.a + a * ds;
      const double b = (x - t.a).dot(dt) / dt2;
      if (b < 0.0 || b > 1.0 || (t.a + b * dt - x).norm() > tau_) continue;
      const double hs = s.ha + a * (s.hb - s.ha), ht = t.ha + b * (t.hb - t.ha);
      best = std::max(best, side > 0 ? hs - ht : ht - hs);
    }
  }
  return best;
}

double ReferenceColumnDepth::deepest(const Vector3d& n, const Vector3d& o, double scale) {
  if (input_.empty()) return 0.0;
  tau_ = kReach * scale;
  project(n, o);
  buildGrid();
  for (int s = 0; s < static_cast<int>(segs_.size()); ++s) fileSegment(s);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) fileFace(f);
  toCsr(segPairs_, grid_.nx * grid_.ny, segStart_, cellSegs_);
  toCsr(facePairs_, grid_.nx * grid_.ny, faceStart_, cellFaces_);
  double best = 0.0;
  for (const Seg& s : segs_) best = std::max(best, columnSpanAt(s.a, s.ha));
  for (int c = 0; c < grid_.nx * grid_.ny; ++c) best = std::max(best, crossingsIn(c));
  return best;
}

}  // namespace vcontact::volume::test
