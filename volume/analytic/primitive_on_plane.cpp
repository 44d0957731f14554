#include "volume/analytic/primitive_on_plane.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "volume/analytic/revolution_on_plane.hpp"
#include "volume/halfspace/clip.hpp"

namespace vcontact::volume {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

// ---------------------------------------------------------------------------------------
// Sphere (MODEL.md §5). u is the height above the sphere's lowest point, u ∈ [0, d]; the
// slice at u is a disc of area π(2Ru − u²). All moments are polynomials in d.

ContactVolume sphereInHalfspaceFrame(double R, const Vector3d& c_H, const Isometry3d& X_WH) {
  const double d = std::min(R - c_H.z(), 2.0 * R);  // penetration of the lowest point
  if (!(d > 0.0)) return ContactVolume{.method = Method::kAnalytic};
  const double d2 = d * d, d3 = d2 * d;
  const double V = M_PI * d2 * (3.0 * R - d) / 3.0;
  const double uBar = d * (8.0 * R - 3.0 * d) / (4.0 * (3.0 * R - d));  // centroid height
  // ∫u² dV − V ū², with ∫u² dV = π(R d⁴/2 − d⁵/5).
  const double Suu = M_PI * d2 * d2 * (R / 2.0 - d / 5.0) - V * uBar * uBar;
  const double Jnn = M_PI * d3 * (20.0 * R * R - 15.0 * R * d + 3.0 * d2) / 30.0;  // polar
  Matrix3d Sigma_H = Vector3d(Jnn / 2.0, Jnn / 2.0, Suu).asDiagonal();
  const Vector3d p_H(c_H.x(), c_H.y(), c_H.z() - R + uBar);
  const double area = d <= R ? M_PI * d * (2.0 * R - d) : M_PI * R * R;
  const Matrix3d R_WH = X_WH.linear();
  return assembleContactVolume(V, X_WH * p_H, R_WH * Sigma_H * R_WH.transpose(), R_WH.col(2), area,
                               d, Method::kAnalytic);
}

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

bool isBoundedPrimitive(const geometry::Shape& s) {
  return std::holds_alternative<geometry::Sphere>(s) ||
         std::holds_alternative<geometry::Cylinder>(s) || std::holds_alternative<geometry::Box>(s);
}

ContactVolume primitiveHalfspace(const geometry::Shape& body, const Isometry3d& X_WB,
                                 const Isometry3d& X_WH) {
  return std::visit(
      Overloaded{[&](const geometry::Sphere& s) { return sphereHalfspace(s.radius, X_WB, X_WH); },
                 [&](const geometry::Cylinder& c) {
                   return cylinderHalfspace(c.radius, c.length, X_WB, X_WH);
                 },
                 [&](const geometry::Box& b) { return boxHalfspace(b.size, X_WB, X_WH); },
                 [&](const auto&) -> ContactVolume {
                   throw InputError("volume method analytic", "not a bounded primitive");
                 }},
      body);
}

}  // namespace

ContactVolume sphereHalfspace(double radius, const Isometry3d& X_WS, const Isometry3d& X_WH) {
  const Vector3d c_H = X_WH.inverse() * X_WS.translation();
  return sphereInHalfspaceFrame(radius, c_H, X_WH);
}

ContactVolume cylinderHalfspace(double radius, double length, const Isometry3d& X_WC,
                                const Isometry3d& X_WH) {
  return revolutionHalfspace(cylinderProfile(radius, length), X_WC, X_WH);
}

ContactVolume boxHalfspace(const Vector3d& size, const Isometry3d& X_WB, const Isometry3d& X_WH) {
  // A box is a polyhedron: its exact clip is its closed form.
  static thread_local geometry::TriangleMesh mesh;
  static thread_local Vector3d meshSize = Vector3d::Zero();
  if (meshSize != size) {
    mesh = geometry::tessellateBox(size);
    meshSize = size;
  }
  ContactVolume cv = meshHalfspaceContact(mesh, X_WB, X_WH);
  cv.method = Method::kAnalytic;
  return cv;
}

bool analyticSupports(const geometry::Shape& a, const geometry::Shape& b) {
  return (isBoundedPrimitive(a) && std::holds_alternative<geometry::HalfSpace>(b)) ||
         (isBoundedPrimitive(b) && std::holds_alternative<geometry::HalfSpace>(a));
}

ContactVolume analyticContact(const geometry::Shape& a, const Isometry3d& X_WA,
                              const geometry::Shape& b, const Isometry3d& X_WB) {
  if (!analyticSupports(a, b)) {
    throw InputError("volume method analytic",
                     "the analytic method handles a sphere, cylinder or box against a "
                     "half-space; got " +
                         geometry::shapeKind(a) + " and " + geometry::shapeKind(b));
  }
  if (std::holds_alternative<geometry::HalfSpace>(b)) return primitiveHalfspace(a, X_WA, X_WB);
  return swapped(primitiveHalfspace(b, X_WB, X_WA));
}

}  // namespace vcontact::volume
