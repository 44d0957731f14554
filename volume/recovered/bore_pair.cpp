#include "volume/recovered/bore_pair.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "volume/recovered/pin_in_bore.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using geometry::RecognisedSurface;
using geometry::SurfaceKind;

// Axes (and a plane's normal and the pin's axis) count as parallel when |cos| of their angle
// is within this of 1, as the pieces of one profile (recovered/revolution_body.cpp): β ≤ 4.5e-5
// rad, so the bore's ellipse departs from its circle by R(1/cos β − 1) ≤ 1e-9 R (5e-12 m for
// the bundled 5.1 mm bore, 1e-5 of a 0.5 µm crescent), and the error bound carries it.
constexpr double kParallel = 1e-9;
// The bore's ends and the pin's range are compared within this many vertex tolerances.
constexpr double kTolerances = 10.0;

// The surfaces of `block` holding a face whose box overlaps `box` (in the block's frame).
std::set<int> surfacesWithin(const RecoveredBody& block, const geometry::Aabb& box) {
  std::set<int> touched;
  geometry::visitTrianglesNear(block.bvh(), box, [&](int f) {
    Vector3d lo = block.mesh().corner(f, 0), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(block.mesh().corner(f, c));
      hi = hi.cwiseMax(block.mesh().corner(f, c));
    }
    if ((lo.array() <= box.max.array()).all() && (hi.array() >= box.min.array()).all())
      touched.insert(block.recognition().face_surface[f]);
    return false;
  });
  return touched;
}

// The box in the block's frame B of the pin's bounding cylinder, grown by `grow`.
geometry::Aabb pinBox(const RevolutionBody& pin, const Isometry3d& X_BR, double grow) {
  const double r = largestRadius(pin.profile);
  geometry::Aabb box{Vector3d::Constant(INFINITY), Vector3d::Constant(-INFINITY)};
  for (int i = 0; i < 8; ++i) {
    const Vector3d p = X_BR * Vector3d(i & 1 ? r : -r, i & 2 ? r : -r,
                                       i & 4 ? pin.profile.back().z1 : pin.profile.front().z0);
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

// What the block offers the slices, in the pin's frame R.
struct BoreSetup {
  BoreSection section;
  const RecognisedSurface* bore = nullptr;
  double residual = 0.0;          // the largest fit residual of the block's surfaces used, m
  double planeTilt = 0.0;         // the largest tan γ of a plane taken as across the axis
  bool tilted = false;            // the bore's axis is not parallel to the pin's
  std::vector<BorePlane> planes;  // tilted: the planes across the bore's axis
};

bool parallel(double cosine) { return std::abs(cosine) >= 1.0 - kParallel; }

// A plane across the pin's axis bounds ζ on the side its outward normal points to.
bool addPlane(const RecognisedSurface& s, const Isometry3d& X_RB, BoreSetup& setup,
              std::string& reason) {
  const Vector3d n = X_RB.linear() * s.axis, p = X_RB * s.point;
  if (!parallel(n.z())) {
    reason = "a plane of the bored body that is not across the pin's axis is within reach";
    return false;
  }
  const double zeta = n.dot(p) / n.z();  // where the plane crosses the axis
  double& bound = n.z() > 0.0 ? setup.section.zeta_hi : setup.section.zeta_lo;
  if (std::isfinite(bound)) {
    reason = "two planes of the bored body bound the pin on one side (a step or a counterbore)";
    return false;
  }
  bound = zeta;
  setup.planeTilt =
      std::max(setup.planeTilt, std::sqrt(std::max(0.0, 1.0 - n.z() * n.z())) / std::abs(n.z()));
  return true;
}

// A tilted bore: a plane across the bore's axis bounds the block along it.
bool addTiltedPlane(const RecognisedSurface& s, const Isometry3d& X_RB, BoreSetup& setup,
                    std::string& reason) {
  const Vector3d n = X_RB.linear() * s.axis, axis = setup.section.axis_R;
  if (!parallel(n.dot(axis))) {
    reason = "a plane of the bored body that is not across the bore's axis is within reach";
    return false;
  }
  for (const BorePlane& q : setup.planes)
    if ((q.normal_R.dot(axis) > 0.0) == (n.dot(axis) > 0.0)) {
      reason = "two planes of the bored body bound the pin on one side (a step or a counterbore)";
      return false;
    }
  setup.planes.push_back({n, X_RB * s.point});
  return true;
}

// The bore's faces' extent along `dir` from `origin` (in R).
std::pair<double, double> boreExtent(const RecoveredBody& block, const RecognisedSurface& bore,
                                     const Isometry3d& X_RB, const Vector3d& dir,
                                     const Vector3d& origin) {
  double lo = INFINITY, hi = -INFINITY;
  for (int f : bore.faces)
    for (int c = 0; c < 3; ++c) {
      const double z = dir.dot(X_RB * block.mesh().corner(f, c) - origin);
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  return {lo, hi};
}

// The one concave cylinder among the block's surfaces within reach, and whether it is tilted.
bool findBore(const geometry::SurfaceRecognition& rec, const std::set<int>& touched,
              const Isometry3d& X_RB, BoreSetup& setup, std::string& reason) {
  for (int index : touched) {
    if (index < 0) {
      reason = "free-form faces of the bored body are within reach";
      return false;
    }
    const RecognisedSurface& s = rec.surfaces[static_cast<std::size_t>(index)];
    if (s.kind == SurfaceKind::kPlane) continue;
    if (s.kind != SurfaceKind::kCylinder || s.convex || setup.bore) {
      reason = std::string("a ") + (s.convex ? "" : "concave ") + surfaceKindName(s.kind) +
               " of the bored body is within reach besides " +
               (setup.bore ? "its bore" : "planes") + " (only one concave cylinder is sliced)";
      return false;
    }
    setup.bore = &s;
  }
  if (!setup.bore) {
    reason = "no concave cylinder (bore) of the other body is within reach";
    return false;
  }
  Vector3d axis = X_RB.linear() * setup.bore->axis;
  if (axis.z() < 0.0) axis = -axis;
  setup.tilted = !parallel(axis.z());
  setup.section.point_R = X_RB * setup.bore->point;
  setup.section.axis_R = axis;
  setup.section.radius = setup.bore->radius;
  setup.residual = setup.bore->max_residual;
  return true;
}

// The block's surfaces within reach, read as a bore and planes across the axis.
std::optional<BoreSetup> boreOf(const RecoveredBody& block, const std::set<int>& touched,
                                const Isometry3d& X_RB, std::string& reason) {
  BoreSetup setup;
  const geometry::SurfaceRecognition& rec = block.recognition();
  if (!findBore(rec, touched, X_RB, setup, reason)) return std::nullopt;
  for (int index : touched) {
    const RecognisedSurface& s = rec.surfaces[static_cast<std::size_t>(index)];
    if (s.kind != SurfaceKind::kPlane) continue;
    setup.residual = std::max(setup.residual, s.max_residual);
    if (!(setup.tilted ? addTiltedPlane : addPlane)(s, X_RB, setup, reason)) return std::nullopt;
  }
  return setup;
}

// Beyond the bore's ends the block's material is unknown unless a plane closes it there: the
// part of the pin's bounding cylinder between the planes must lie within the bore's extent,
// along the bore's axis (in R: along ζ for a parallel bore, whose planes bound ζ).
bool withinBore(const RevolutionBody& pin, const RecoveredBody& block, const BoreSetup& setup,
                const Isometry3d& X_RB) {
  const BoreSection& sec = setup.section;
  const Vector3d dir = setup.tilted ? sec.axis_R : Vector3d::UnitZ();
  const Vector3d origin = setup.tilted ? sec.point_R : Vector3d::Zero();
  const auto [lo, hi] = boreExtent(block, *setup.bore, X_RB, dir, origin);
  double pinLo = INFINITY, pinHi = -INFINITY;
  const double r = largestRadius(pin.profile);
  for (int i = 0; i < 8; ++i) {
    const double t = dir.dot(Vector3d(i & 1 ? r : -r, i & 2 ? r : -r,
                                      i & 4 ? pin.profile.back().z1 : pin.profile.front().z0) -
                             origin);
    pinLo = std::min(pinLo, t);
    pinHi = std::max(pinHi, t);
  }
  double planeLo = sec.zeta_lo, planeHi = sec.zeta_hi;
  for (const BorePlane& q : setup.planes) {
    const double t = dir.dot(q.point_R - origin);
    if (q.normal_R.dot(dir) > 0.0) {
      planeHi = t;
    } else {
      planeLo = t;
    }
  }
  const double tol = kTolerances * block.recognition().tolerance;
  return std::max(pinLo, planeLo) >= lo - tol && std::min(pinHi, planeHi) <= hi + tol;
}

}  // namespace

std::optional<RecoveredContact> boreContact(const RecoveredBody& pin, const Isometry3d& X_WP,
                                            const RecoveredBody& block, const Isometry3d& X_WB,
                                            std::string& reason) {
  const RevolutionBody* rev = pin.revolution();
  if (!rev) {
    reason = "the pin is not one solid of revolution";
    return std::nullopt;
  }
  const Isometry3d X_WR = X_WP * rev->X_MR, X_BR = X_WB.inverse() * X_WR;
  const std::set<int> touched =
      surfacesWithin(block, pinBox(*rev, X_BR, pin.margin() + block.margin()));
  std::optional<BoreSetup> setup = boreOf(block, touched, X_BR.inverse(), reason);
  if (!setup) return std::nullopt;
  if (!withinBore(*rev, block, *setup, X_BR.inverse())) {
    reason = "the pin reaches beyond the bore where no plane of the bored body closes it";
    return std::nullopt;
  }
  const BoreSection& sec = setup->section;
  const BoreContact bc = setup->tilted
                             ? revolutionInTiltedBore(rev->profile, X_WR, sec, setup->planes)
                             : revolutionInBore(rev->profile, X_WR, sec);
  const ContactVolume& cv = bc.cv;
  const double residual = std::max(rev->max_residual, setup->residual);
  const double method = std::isfinite(cv.relative_error) ? cv.relative_error : 0.0;
  RecoveredContact r{cv, Representation::kRevolutionInBore, "", 0.0, {}, 0, true, bc.patches};
  r.volume_error_bound = cv.area * residual + cv.volume * method;
  if (!setup->tilted)  // what taking the axes and the planes as parallel costs
    r.volume_error_bound += cv.area * sec.radius * (1.0 / sec.axis_R.z() - 1.0) +
                            bc.plane_area * largestRadius(rev->profile) * setup->planeTilt;
  return r;
}

}  // namespace vcontact::volume
