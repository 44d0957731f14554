#include "geometry/mass_properties.hpp"

#include <cmath>
#include <variant>

#include "geometry/error.hpp"

namespace vcontact::geometry {

Moments meshMoments(const TriangleMesh& mesh) {
  const Aabb box = bounds(mesh);
  const Eigen::Vector3d o = 0.5 * (box.min + box.max);
  Moments sum;
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    sum += tetrahedronMoments(o, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
  }
  return sum;
}

namespace {

// Diagonal moments ∫x², ∫y², ∫z² of a centred solid with volume m0.
Moments centredDiagonal(double m0, double xx, double yy, double zz) {
  Moments M;
  M.m0 = m0;
  M.m2 = Eigen::Vector3d(xx, yy, zz).asDiagonal();
  return M;
}

}  // namespace

Moments solidMoments(const Shape& shape) {
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    const double R = s->radius;
    const double r2 = 4.0 * M_PI * std::pow(R, 5) / 15.0;  // ∫x² dV over the ball
    return centredDiagonal(4.0 * M_PI * R * R * R / 3.0, r2, r2, r2);
  }
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    const double R = c->radius, L = c->length;
    const double m0 = M_PI * R * R * L;
    return centredDiagonal(m0, m0 * R * R / 4.0, m0 * R * R / 4.0, m0 * L * L / 12.0);
  }
  if (const auto* b = std::get_if<Box>(&shape)) {
    const Eigen::Vector3d s = b->size;
    const double m0 = s.prod();
    return centredDiagonal(m0, m0 * s.x() * s.x() / 12.0, m0 * s.y() * s.y() / 12.0,
                           m0 * s.z() * s.z() / 12.0);
  }
  if (const auto* m = std::get_if<Mesh>(&shape)) return meshMoments(*m->mesh);
  throw InputError("", "a half-space has no finite volume or inertia");
}

MassProperties massProperties(const Moments& moments, double density) {
  MassProperties p;
  p.mass = density * moments.m0;
  p.com = moments.centroid();
  p.inertia = density * moments.centralInertia();
  return p;
}

}  // namespace vcontact::geometry
