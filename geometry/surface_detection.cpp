// CGAL's efficient RANSAC (Schnabel, Wahl and Klein 2007) over the sample points of a mesh:
// planes, spheres, cylinders, cones and tori, with their rough parameters.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Random.h>
#include <CGAL/Shape_detection/Efficient_RANSAC.h>
#include <CGAL/property_map.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "geometry/surface_recognition_internal.hpp"

namespace vcontact::geometry::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// A sample as RANSAC sees it: position, normal, and the sample's index, since RANSAC's octree
// reorders the range it is given and reports its shapes' points by position in that range.
using PointWithNormal = std::tuple<Kernel::Point_3, Kernel::Vector_3, int>;
using PointsWithNormals = std::vector<PointWithNormal>;
using Traits = CGAL::Shape_detection::Efficient_RANSAC_traits<
    Kernel, PointsWithNormals, CGAL::Nth_of_tuple_property_map<0, PointWithNormal>,
    CGAL::Nth_of_tuple_property_map<1, PointWithNormal>>;
using Ransac = CGAL::Shape_detection::Efficient_RANSAC<Traits>;

// The largest grid of cells the parameter-space clustering may allocate (4 bytes a cell).
constexpr double kMaxClusterCells = double(1 << 24);

// A RANSAC shape whose connected-component step is safe on any candidate. CGAL 5.5 clusters a
// candidate's points on a grid over its 2-D parameter space, sized from the parameters' range
// without checking it: a sample on a degenerate spot of a candidate (on a cylinder's axis, at
// a cone's apex, where the direction from the axis is a zero vector normalised) gives a NaN
// range, the grid's size wraps to 0 and the fill writes through a null pointer (`vcontact
// surfaces` crashed on a block with a 192-, 256- or 768-segment bore). Where the range is not
// finite, or the grid would exceed kMaxClusterCells, this falls back to CGAL's own Euclidean
// clustering of the points (the torus's method); elsewhere it is CGAL's grid, unchanged.
template <class Shape>
class GuardedShape : public Shape {
 protected:
  using FT = typename Traits::FT;
  std::size_t connected_component(std::vector<std::size_t>& indices, FT cluster_epsilon) override {
    if (!indices.empty() && this->supports_connected_component() &&
        !gridIsSafe(indices.size(), cluster_epsilon))
      return this->connected_component_kdTree(indices, cluster_epsilon);
    return Shape::connected_component(indices, cluster_epsilon);
  }

 private:
  // The parameters CGAL's grid would be built from (the same call), checked before it is.
  bool gridIsSafe(std::size_t count, FT cluster_epsilon) const {
    FT min[] = {0, 0}, max[] = {0, 0};
    FT epsilon = cluster_epsilon;
    std::vector<std::pair<FT, FT>> space(count);
    this->parameters(this->m_indices, space, epsilon, min, max);
    for (const auto& [u, v] : space)
      if (!std::isfinite(u) || !std::isfinite(v)) return false;
    const double cells_u = std::ceil((max[0] - min[0]) / epsilon) + 1.0;
    const double cells_v = std::ceil((max[1] - min[1]) / epsilon) + 1.0;
    return std::isfinite(cells_u) && std::isfinite(cells_v) &&
           cells_u * cells_v <= kMaxClusterCells;
  }
};

using Plane = GuardedShape<CGAL::Shape_detection::Plane<Traits>>;
using Sphere = GuardedShape<CGAL::Shape_detection::Sphere<Traits>>;
using Cylinder = GuardedShape<CGAL::Shape_detection::Cylinder<Traits>>;
using Cone = GuardedShape<CGAL::Shape_detection::Cone<Traits>>;
using Torus = CGAL::Shape_detection::Torus<Traits>;  // clusters by distance already

Eigen::Vector3d toEigen(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }
Eigen::Vector3d toEigen(const Kernel::Vector_3& v) { return {v.x(), v.y(), v.z()}; }

// The kind and rough parameters of one RANSAC shape; false for a kind we did not ask for.
bool roughSurface(const Ransac::Shape& shape, RecognisedSurface& s) {
  if (const auto* p = dynamic_cast<const Plane*>(&shape)) {
    s.kind = SurfaceKind::kPlane;
    s.axis = toEigen(p->plane_normal()).normalized();
  } else if (const auto* sp = dynamic_cast<const Sphere*>(&shape)) {
    s.kind = SurfaceKind::kSphere;
    s.point = toEigen(sp->center());
    s.radius = sp->radius();
  } else if (const auto* c = dynamic_cast<const Cylinder*>(&shape)) {
    s.kind = SurfaceKind::kCylinder;
    s.point = toEigen(c->axis().point());
    s.axis = toEigen(c->axis().to_vector()).normalized();
    s.radius = c->radius();
  } else if (const auto* k = dynamic_cast<const Cone*>(&shape)) {
    s.kind = SurfaceKind::kCone;
    s.point = toEigen(k->apex());
    s.axis = toEigen(k->axis()).normalized();
    s.angle = k->angle();
  } else if (const auto* t = dynamic_cast<const Torus*>(&shape)) {
    s.kind = SurfaceKind::kTorus;
    s.point = toEigen(t->center());
    s.axis = toEigen(t->axis()).normalized();
    s.radius = t->major_radius();
    s.minor_radius = t->minor_radius();
  } else {
    return false;
  }
  return true;
}

// Orients the rough surface by its samples: a plane's normal and a cone's axis point the way
// the samples say, and a curved surface is convex when the samples' normals point away from
// its centre, axis or tube centre line.
void orient(RecognisedSurface& s, const SamplePoints& samples, const std::vector<int>& taken) {
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
  for (int i : taken) {
    mean_normal += samples.normal[i];
    centroid += samples.position[i];
  }
  centroid /= static_cast<double>(taken.size());
  if (s.kind == SurfaceKind::kPlane) {
    if (s.axis.dot(mean_normal) < 0.0) s.axis = -s.axis;
    s.point = centroid;
    return;
  }
  if (s.kind == SurfaceKind::kCone && s.axis.dot(centroid - s.point) < 0.0) s.axis = -s.axis;
  if (s.kind == SurfaceKind::kCylinder)  // the axis point nearest the samples' centroid
    s.point += s.axis * s.axis.dot(centroid - s.point);
  s.convex = true;  // outwardNormal is then the direction away from the solid's inside
  double agree = 0.0;
  for (int i : taken) agree += samples.normal[i].dot(outwardNormal(s, samples.position[i]));
  s.convex = agree >= 0.0;
}

}  // namespace

std::vector<Candidate> detectCandidates(const SamplePoints& samples, const std::vector<char>& use,
                                        const DetectionSettings& set) {
  // CGAL's plane construction refuses three points whose edge vectors' cross product is below
  // 1e-4 in the input's units (Plane.h), so a part measured in metres would lose every plane
  // smaller than 1 cm. RANSAC therefore sees the samples centred and scaled to a diagonal of
  // kFrame; the shapes are mapped back below.
  constexpr double kFrame = 100.0;
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < samples.position.size(); ++i)
    if (use[i]) box.extend(samples.position[i]);
  const Eigen::Vector3d centre = box.center();
  const double k = box.diagonal().norm() > 0.0 ? kFrame / box.diagonal().norm() : 1.0;
  PointsWithNormals points;
  points.reserve(samples.position.size());
  for (std::size_t i = 0; i < samples.position.size(); ++i) {
    if (!use[i]) continue;
    const Eigen::Vector3d p = (samples.position[i] - centre) * k;
    const Eigen::Vector3d& n = samples.normal[i];
    points.emplace_back(Kernel::Point_3(p.x(), p.y(), p.z()), Kernel::Vector_3(n.x(), n.y(), n.z()),
                        static_cast<int>(i));
  }
  // RANSAC draws from CGAL's default generator: seeding it makes the result reproducible.
  CGAL::get_default_random() = CGAL::Random(set.seed);
  Ransac ransac;
  ransac.set_input(points);
  const auto wanted = [&](SurfaceKind k) { return (set.kinds >> static_cast<int>(k)) & 1u; };
  if (wanted(SurfaceKind::kPlane)) ransac.add_shape_factory<Plane>();
  if (wanted(SurfaceKind::kSphere)) ransac.add_shape_factory<Sphere>();
  if (wanted(SurfaceKind::kCylinder)) ransac.add_shape_factory<Cylinder>();
  if (wanted(SurfaceKind::kCone)) ransac.add_shape_factory<Cone>();
  if (wanted(SurfaceKind::kTorus)) ransac.add_shape_factory<Torus>();
  Ransac::Parameters parameters;
  parameters.probability = 0.001;  // chance of missing the best candidate in a round
  parameters.min_points = 4;  // a box face has 4 corner samples; smaller shapes are not worth it
  parameters.epsilon = set.epsilon * k;
  parameters.cluster_epsilon = set.cluster_epsilon * k;
  parameters.normal_threshold = set.normal_threshold;
  std::vector<Candidate> out;
  if (points.size() < parameters.min_points || !ransac.detect(parameters)) return out;
  for (const auto& shape : ransac.shapes()) {
    Candidate c;
    if (!roughSurface(*shape, c.surface)) continue;
    c.surface.point = c.surface.point / k + centre;  // back to the mesh frame
    c.surface.radius /= k;
    c.surface.minor_radius /= k;
    for (std::size_t i : shape->indices_of_assigned_points())
      c.samples.push_back(std::get<2>(points[i]));
    if (c.samples.empty()) continue;
    orient(c.surface, samples, c.samples);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace vcontact::geometry::detail
