// The detrended bounds of the depth pass (depth/deepest_column.hpp): a cell about to be evaluated
// is bounded once more with every height less a linear trend g·x, and so is each of its vertex
// columns.
//
// Why. Every candidate value of the pass is a difference of two heights h₁ − h₂ at points y₁,
// y₂ within 2τ of each other (a vertex column's items lie within τ of the vertex; a crossing's
// bottom edge is taken within τ of its top edge's point), so for any g
//   h₁ − h₂ = (h₁ − g·y₁) − (h₂ − g·y₂) + g·(y₁ − y₂) ≤ max(h − g·y) − min(h − g·y) + 2τ|g|₁.
// Where the region is a thin shell that is steep along n (a pin pressed into a chamfer), the
// heights over one cell vary by the slope times the cell's width, several times the depth; the
// heights less the local slope vary by little more than the depth. With g the mean gradient of
// the planes of the cell's top and bottom faces, most cells that the first bound (branch and
// bound, depth/deepest_column_bounds.cpp) lets through stop here, and so do most vertex columns of
// the cells that do not. Nothing is skipped whose value could exceed the deepest found so far, so
// the depth is the same to the bit (deepest_column_test).
//
// The detrended ranges are taken over
// - each segment filed in the cell: h − g·y is linear along it, so its ends bound it;
// - each vertex of the cell (its own height);
// - each face of the cell's block at the points of the cell's box (grown by kClipGrowth τ)
//   inside the face's box, the only points where a vertex column of the cell evaluates it: the
//   plane less g·x is linear over that rectangle, so two corners bound it. height() clamps the
//   plane to the face's range [lo, hi]; the clamp acts only where a column that the
//   crossing-number test puts inside the face lies beyond the plane's range, by the rounding
//   of the points (a few ε of the coordinates, times the slope), which (1 + |slope|₁) τ covers.
// The margins add the rounding allowed for on each height (Seg::slack, the plane's terms) and
// that of the products and differences here (4ε of their operands), all far below τ, itself
// far below any depth the pass reports (τ = 1e-12 of the coordinates).

#include <algorithm>
#include <cmath>
#include <limits>

#include "volume/depth/deepest_column.hpp"

namespace vcontact::volume {

using Eigen::Vector2d;

namespace {

/// Four roundings of a sum or product, relative to its operands.
constexpr double kEps4 = 4.0 * std::numeric_limits<double>::epsilon();
/// The points of a column's items lie within τ of it, those of a crossing's two edges within τ
/// of each other, up to the rounding of the points (far below τ): 1.5 τ covers either.
constexpr double kNear = 1.5;

}  // namespace

/// The trend of cell c (trend_): g, the mean gradient of the planes of the faces of its top
/// and bottom segments, and each segment's range of h − g·y (trendRange_, in the order of the
/// cell's list). false where the cell has no top or bottom segment.
bool ColumnDepth::detrend(int c) {
  trend_ = Trend{};
  cellOfTrend_ = c;
  Vector2d g = Vector2d::Zero();
  int count = 0;
  for (int k = segBegin_[c]; k < segEnd_[c]; ++k) {
    const Face& F = faces_[static_cast<std::size_t>(cellSeg(k).face)];
    if (F.side == 0) continue;
    g -= Vector2d(F.slope_u, F.slope_v);  // h = h0 − slope_u x − slope_v y
    ++count;
  }
  if (count == 0) return false;
  trend_.g = g / count;
  trend_.gAbs = trend_.g.cwiseAbs().sum();
  trendRange_.clear();
  for (int k = segBegin_[c]; k < segEnd_[c]; ++k) {
    const Seg& s = cellSeg(k);
    const double da = detrended(s.a, s.ha), db = detrended(s.b, s.hb);
    trend_.err = std::max(trend_.err, s.slack);
    trendRange_.emplace_back(std::min(da, db), std::max(da, db));
    trend_.dAbs = std::max({trend_.dAbs, std::abs(da), std::abs(db)});
  }
  trend_.valid = true;
  return true;
}

/// h − g·y for the trend of the cell, widening trend_.err by its rounding.
double ColumnDepth::detrended(const Vector2d& y, double h) {
  trend_.err = std::max(trend_.err, kEps4 * (std::abs(h) + trend_.gAbs * y.cwiseAbs().maxCoeff()));
  return h - trend_.g.dot(y);
}

/// Widens [lo, hi] by h − g·x of face F at the points x of the box [blo, bhi] inside F's box,
/// and trend_.err by the rounding and the clamp allowed for there.
void ColumnDepth::detrendedFace(const Face& F, const Vector2d& blo, const Vector2d& bhi, double& lo,
                                double& hi) {
  const Vector2d rlo = blo.cwiseMax(F.bmin), rhi = bhi.cwiseMin(F.bmax);
  if (rlo.x() > rhi.x() || rlo.y() > rhi.y()) return;
  const Vector2d& g = trend_.g;
  // the gradient of h − g·x over the plane: (−slope_u − g_x, −slope_v − g_y)
  const bool xUp = -F.slope_u - g.x() >= 0.0, yUp = -F.slope_v - g.y() >= 0.0;
  const Vector2d up(xUp ? rhi.x() : rlo.x(), yUp ? rhi.y() : rlo.y());
  const Vector2d down(xUp ? rlo.x() : rhi.x(), yUp ? rlo.y() : rhi.y());
  const double slope = std::abs(F.slope_u) + std::abs(F.slope_v);
  const double reach = rlo.cwiseAbs().cwiseMax(rhi.cwiseAbs()).maxCoeff();
  trend_.err = std::max(
      trend_.err, (1.0 + slope) * tau_ + kEps4 * (std::abs(F.h0) + std::abs(F.lo) + std::abs(F.hi) +
                                                  (slope + trend_.gAbs) * reach));
  hi = std::max(hi, F.h0 - F.slope_u * up.x() - F.slope_v * up.y() - g.dot(up));
  lo = std::min(lo, F.h0 - F.slope_u * down.x() - F.slope_v * down.y() - g.dot(down));
}

/// A bound of every candidate value of cell c (its crossings and vertex columns) from its
/// detrended heights; sets the cell's trend for columnBound. +∞ without a trend.
double ColumnDepth::detrendedBound(int c) {
  if (!detrend(c)) return kInf;
  double hi = -kInf, lo = kInf, topHi = -kInf, bottomLo = kInf;
  for (int k = segBegin_[c]; k < segEnd_[c]; ++k) {
    const auto& [dlo, dhi] = trendRange_[static_cast<std::size_t>(k - segBegin_[c])];
    hi = std::max(hi, dhi);
    lo = std::min(lo, dlo);
    const int side = cellSeg(k).side;
    if (side > 0) topHi = std::max(topHi, dhi);
    if (side < 0) bottomLo = std::min(bottomLo, dlo);
  }
  double value = topHi - bottomLo;  // −∞ without a top and a bottom segment
  if (vertexBegin_[c] < vertexEnd_[c]) {
    for (int k = vertexBegin_[c]; k < vertexEnd_[c]; ++k) {
      const Seg& s = segs_[static_cast<std::size_t>(cellVertices_[static_cast<std::size_t>(k)])];
      const double d = detrended(s.a, s.ha);
      hi = std::max(hi, d);
      lo = std::min(lo, d);
    }
    Vector2d blo, bhi;
    box(grid_, c, blo, bhi);
    const int block = blockOfCell(c);
    for (int k = faceStart_[block]; k < faceStart_[block + 1]; ++k) {
      detrendedFace(faces_[static_cast<std::size_t>(cellFaces_[k])], blo, bhi, lo, hi);
    }
    value = std::max(value, hi - lo);
  }
  const double rounding = kEps4 * (std::abs(hi) + std::abs(lo) + std::abs(topHi) +
                                   std::abs(bottomLo) + std::abs(value));
  return value + 2.0 * (trend_.err + kNear * trend_.gAbs * tau_) + rounding;
}

/// The margin of a segment's detrended range about a column of cell cellOfTrend_ (g·x = gx):
/// a segment's heights near the column, at points y within kNear τ of it, are h = (h − g·y) +
/// g·y ≤ its detrended high + gx + τ|g|₁, with the rounding of h (Seg::slack) and of its
/// detrended range (each within err), and of the two additions (4ε of their operands).
double ColumnDepth::trendMargin(double gx) const {
  return 2.0 * trend_.err + kNear * trend_.gAbs * tau_ + kEps4 * (trend_.dAbs + std::abs(gx));
}

}  // namespace vcontact::volume
