#include "validation/friction_map.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <variant>

#include "dynamics/distributed_friction.hpp"
#include "dynamics/model.hpp"
#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "io/shape_spec.hpp"
#include "volume/contact.hpp"

namespace vcontact::validation {
namespace {

// A 512-gon's area is within 2.5e-5 of the circle's, below the column grid's error (~1e-3).
constexpr int kPunchSegments = 512;
constexpr int kSphereSegments = 256, kSphereRings = 128;
constexpr int kMaxRows = 2000;
// The plate is tilted by these angles (degrees); the friction is frame-invariant. The tilt
// once hid a columns bug (a micrometre-thin slab in a coordinate plane was missed; now
// tests/volume/columns/columns_test.cpp FindsAThinAxisAlignedLayer) and stays because the map's
// numbers depend on how the grid lies: untilted, f_n moves by 9e-5 relative (grid error).
const Eigen::Vector3d kPlateRpyDeg(17.0, 29.0, 0.0);

/// The contact the sweep runs on: the columns δ map of the shape on a half-space (plate
/// z ≤ 0), the reference length R of ε, and whether the punch closed form applies.
struct SweepContact {
  Eigen::Isometry3d X_WH;  // the plate's frame, its z along n
  volume::ContactVolume cv;
  volume::DepthField field;
  double R = 0.0;  // m
  bool punch = false;
  std::string description;
};

void check(bool ok, const std::string& quantity, const std::string& expected) {
  if (!ok) throw InputError(quantity, expected);
}

geometry::TriangleMesh meshOf(const geometry::Shape& shape) {
  if (const auto* m = std::get_if<geometry::Mesh>(&shape)) return *m->mesh;
  if (const auto* c = std::get_if<geometry::Cylinder>(&shape)) {
    return geometry::tessellateCylinder(c->radius, c->length, kPunchSegments);
  }
  if (const auto* b = std::get_if<geometry::Box>(&shape)) return geometry::tessellateBox(b->size);
  if (const auto* s = std::get_if<geometry::Sphere>(&shape)) {
    return geometry::tessellateSphere(s->radius, kSphereSegments, kSphereRings);
  }
  throw InputError("shape", "expected a mesh file, cylinder, box or sphere to press on the plate");
}

/// The body pressed `depth` into the plate z_H ≤ 0 (its lowest vertex at z_H = −depth).
SweepContact press(geometry::TriangleMesh mesh, double depth) {
  const geometry::Aabb box = geometry::bounds(mesh);
  SweepContact c;
  c.X_WH = io::poseFromRpyDegrees(Eigen::Vector3d::Zero(), kPlateRpyDeg);
  const Eigen::Isometry3d X_WB = c.X_WH * Eigen::Translation3d(0.0, 0.0, -box.min.z() - depth);
  const geometry::Mesh body{std::make_shared<geometry::TriangleMesh>(std::move(mesh)), "payload"};
  volume::QueryOptions columns;
  columns.method = volume::Method::kColumns;  // the δ map the distributed friction integrates
  c.cv = volume::computeContact(body, X_WB, geometry::HalfSpace{}, c.X_WH, columns, &c.field)
             .aggregate;
  if (!c.cv.inContact()) throw InputError("depth", "the body does not reach the plate");
  return c;
}

SweepContact sweepContact(const FrictionMapOptions& o) {
  if (!o.shape) {
    // Flat punch: depth from the load, f_n = kv π R² d (MODEL.md §5).
    const double depth = o.load / (o.kv * std::numbers::pi * o.radius * o.radius);
    SweepContact c = press(geometry::tessellateCylinder(o.radius, o.radius, kPunchSegments), depth);
    c.R = o.radius;
    c.punch = true;
    std::ostringstream s;
    s << "flat punch R = " << o.radius << " m, depth " << depth << " m";
    c.description = s.str();
    return c;
  }
  SweepContact c = press(meshOf(*o.shape), o.depth);
  c.R = std::sqrt(2.0) * c.cv.r_gyr;  // the flat punch of the same r_gyr
  std::ostringstream s;
  s << geometry::describe(*o.shape) << ", depth " << o.depth << " m, R = sqrt(2) r_gyr = " << c.R
    << " m";
  c.description = s.str();
  return c;
}

/// Slip speed v and spin ω for ε with √(v² + (ωR)²) = speed, so that neither falls far below
/// the regularisation speed v_ε at the ends of the sweep.
FrictionMapRow evaluate(const SweepContact& c, const dynamics::Model& lumped,
                        const FrictionMapOptions& o, double eps) {
  FrictionMapRow r{};
  r.eps = eps;
  const double scale = std::isinf(eps) ? 0.0 : 1.0 / std::hypot(eps, 1.0);
  r.v = std::isinf(eps) ? o.speed : o.speed * eps * scale;
  r.w = o.speed * scale / c.R;
  const dynamics::RelativeMotion m{r.v * c.X_WH.linear().col(0), r.w * c.cv.n_W, 0.0};
  const dynamics::ContactResult l = lumped.evaluate(c.cv, m, dynamics::PairState{});
  const Eigen::Vector3d n = c.cv.n_W;
  r.f_lumped = (l.wrench.f_W - l.wrench.f_W.dot(n) * n).norm();
  r.m_lumped = std::abs(l.wrench.tau_W.dot(n));
  const dynamics::DistributedFriction d =
      dynamics::distributedFriction(c.cv, c.field, {o.kv, 0.0}, m, o.mu, lumped.settings.v_eps);
  r.f_dist = d.wrench.f_W.norm();
  r.m_dist = std::abs(d.wrench.tau_W.dot(n));
  if (c.punch) r.exact = flatPunchFriction(eps);
  return r;
}

std::vector<double> sweep(const FrictionMapOptions& o) {
  std::vector<double> eps = {0.0};
  const double decades = std::log10(o.eps_max / o.eps_min);
  const int steps = static_cast<int>(std::ceil(decades * o.per_decade - 1e-9));
  for (int i = 0; i <= steps; ++i) eps.push_back(o.eps_min * std::pow(10.0, decades * i / steps));
  eps.push_back(INFINITY);
  return eps;
}

void validate(const FrictionMapOptions& o) {
  check(std::isfinite(o.radius) && o.radius > 0.0, "radius", "a radius > 0 in metres");
  check(std::isfinite(o.load) && o.load > 0.0, "load", "a load > 0 in newtons");
  check(std::isfinite(o.mu) && o.mu > 0.0, "mu", "a friction coefficient > 0");
  check(std::isfinite(o.kv) && o.kv > 0.0, "kv", "a volumetric stiffness > 0 in N/m^3");
  check(std::isfinite(o.depth) && o.depth > 0.0, "depth", "a depth > 0 in metres");
  check(std::isfinite(o.speed) && o.speed > 0.0, "speed", "a speed > 0 in m/s");
  check(std::isfinite(o.eps_min) && o.eps_min > 0.0 && std::isfinite(o.eps_max) &&
            o.eps_max > o.eps_min,
        "epsilon range", "0 < eps-min < eps-max, finite");
  check(o.per_decade >= 1 && std::log10(o.eps_max / o.eps_min) * o.per_decade < kMaxRows,
        "points per decade", "at least 1, and fewer than 2000 rows in all");
}

}  // namespace

FrictionMap frictionMap(const FrictionMapOptions& o) {
  validate(o);
  const SweepContact c = sweepContact(o);
  dynamics::Model lumped =
      dynamics::Model::withEffects({"stiffness", "coulomb", "spin", "contensou"});
  lumped.setParameter("stiffness.kv", o.kv);
  lumped.setParameter("coulomb.mu", o.mu);
  FrictionMap map{c.description, o.kv * c.cv.volume,  o.mu, c.R,
                  c.cv.r_gyr,    c.cv.relative_error, {}};
  for (double eps : sweep(o)) map.rows.push_back(evaluate(c, lumped, o, eps));
  return map;
}

double lumpedOverDistributed(double a, double b) {
  return a != 0.0 && b != 0.0 ? a / b : std::nan("");
}

}  // namespace vcontact::validation
