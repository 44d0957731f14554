#include "volume/cgal/corefinement.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <variant>
#include <vector>

#include "geometry/moments.hpp"
#include "geometry/tessellate.hpp"
#include "volume/depth/deepest_column.hpp"

namespace vcontact::volume {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Eigen::Vector3d;

/// The mesh placed in W (p_W = X_WM p_M, rounded to double as every backend does).
Mesh toCgal(const geometry::TriangleMesh& m, const Eigen::Isometry3d& X_WM) {
  Mesh out;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(static_cast<std::size_t>(m.vertexCount()));
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) {
    const Vector3d p = X_WM * m.vertex(i);
    v.push_back(out.add_vertex(Point(p.x(), p.y(), p.z())));
  }
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    out.add_face(v[m.triangles(f, 0)], v[m.triangles(f, 1)], v[m.triangles(f, 2)]);
  }
  return out;
}

Vector3d toEigen(const Point& p) {
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

/// One face of the intersection polyhedron, in double, whether it lies on ∂A, and which
/// connected component of the polyhedron it bounds.
struct RegionFace {
  Vector3d p[3];
  bool onA;
  std::size_t component;
};

/// The faces of `region` (A ∩ B), labelled by PMP::connected_components (faces joined through
/// shared edges; with no cavities in A or B, A ∩ B has none, so each component of its surface
/// bounds one component of the solid).
/// @param[out] components  how many components the region has
std::vector<RegionFace> regionFaces(Mesh& region, const Mesh& a, std::size_t& components) {
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> sideOfA(a);
  auto label = region.add_property_map<Mesh::Face_index, std::size_t>("f:component", 0).first;
  components = CGAL::Polygon_mesh_processing::connected_components(region, label);
  std::vector<RegionFace> faces;
  faces.reserve(region.number_of_faces());
  for (const auto f : region.faces()) {
    Point q[3];
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(region.halfedge(f), region))
      q[k++] = region.point(v);
    // The exact centroid is on ∂A iff the face came from A (faces of B inside A are strictly
    // inside, or on ∂A only where the two surfaces coincide, where either label is right).
    const bool onA = sideOfA(CGAL::centroid(q[0], q[1], q[2])) == CGAL::ON_BOUNDARY;
    faces.push_back({{toEigen(q[0]), toEigen(q[1]), toEigen(q[2])}, onA, label[f]});
  }
  return faces;
}

/// MODEL.md §1 quantities of the region bounded by `faces`.
ContactVolume contactFromFaces(const std::vector<RegionFace>& faces) {
  if (faces.empty()) return ContactVolume{.method = Method::kCgal};
  // Fan about a vertex of the region, so that the terms are of the region's size.
  const Vector3d o = faces.front().p[0];
  geometry::Moments M;
  Vector3d areaOnA = Vector3d::Zero();  // ∫_{∂A∩B} n_A dA
  for (const RegionFace& f : faces) {
    M += geometry::tetrahedronMoments(Vector3d::Zero(), f.p[0] - o, f.p[1] - o, f.p[2] - o);
    if (f.onA) areaOnA += 0.5 * (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]);
  }
  if (!(M.m0 > 0.0) || areaOnA.norm() == 0.0) return ContactVolume{.method = Method::kCgal};
  const Vector3d n = -areaOnA.normalized();
  double area2 = 0.0, scale = 0.0;
  ColumnDepth depth;
  std::uint64_t key = 0;
  for (const RegionFace& f : faces) {
    const Vector3d N = (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]);
    area2 += std::abs(n.dot(N));
    for (const Vector3d& p : f.p) scale = std::max(scale, p.cwiseAbs().maxCoeff());
    if (!(N.norm() > 0.0)) continue;  // a face of no area bounds no column
    const Vector3d n_f = N.normalized();
    for (int k = 0; k < 3; ++k) depth.add(key, n_f, f.p[k], f.p[(k + 1) % 3]);
    ++key;
  }
  return contactFromMoments(M, o, n, 0.25 * area2, depth.deepest(n, o, scale), Method::kCgal);
}

/// The whole region as the aggregate and each connected component as a patch, each with the
/// normal of its own ∂B1 faces (MODEL.md §1).
ContactPatches patchesFromFaces(const std::vector<RegionFace>& faces, std::size_t components) {
  ContactPatches out = singlePatch(contactFromFaces(faces));
  if (!out.inContact() || components == 1) return out;
  std::vector<std::vector<RegionFace>> byComponent(components);
  for (const RegionFace& f : faces) byComponent[f.component].push_back(f);
  out.patches.clear();
  for (const std::vector<RegionFace>& component : byComponent) {
    const ContactVolume cv = contactFromFaces(component);
    if (cv.inContact()) out.patches.push_back(cv);
  }
  sortPatches(out.patches);
  return out;
}

ContactPatches intersect(Mesh a, Mesh b) {
  const Mesh aOriginal = a;
  Mesh region;
  namespace PMP = CGAL::Polygon_mesh_processing;
  if (!PMP::corefine_and_compute_intersection(a, b, region)) {
    throw std::runtime_error("cgal reference: corefinement failed (self-intersecting input?)");
  }
  std::size_t components = 0;
  const std::vector<RegionFace> faces = regionFaces(region, aOriginal, components);
  return patchesFromFaces(faces, components);
}

/// A contact computed in the half-space frame H, in W; the normal is the half-space's by
/// definition (MODEL.md §1).
ContactVolume halfspaceToWorld(const ContactVolume& cv, const Eigen::Isometry3d& X_WH) {
  const Eigen::Matrix3d R = X_WH.linear();
  const Eigen::Matrix3d Sigma_H = cv.J_v.trace() / 2.0 * Eigen::Matrix3d::Identity() - cv.J_v;
  return assembleContactVolume(cv.volume, X_WH * cv.p_WC, R * Sigma_H * R.transpose(), R.col(2),
                               cv.area, cv.depth, Method::kCgal);
}

}  // namespace

ContactPatches cgalMeshMeshContact(const geometry::TriangleMesh& a, const Eigen::Isometry3d& X_WA,
                                   const geometry::TriangleMesh& b, const Eigen::Isometry3d& X_WB) {
  return intersect(toCgal(a, X_WA), toCgal(b, X_WB));
}

ContactPatches cgalMeshHalfspaceContact(const geometry::TriangleMesh& mesh,
                                        const Eigen::Isometry3d& X_WM,
                                        const Eigen::Isometry3d& X_WH) {
  // Work in H: the box spans the mesh's footprint with a margin and reaches below its lowest
  // point; its top face is z_H = 0 exactly.
  const Eigen::Isometry3d X_HM = X_WH.inverse() * X_WM;
  geometry::TriangleMesh m_H = mesh;
  for (Eigen::Index i = 0; i < m_H.vertexCount(); ++i) {
    m_H.vertices.row(i) = (X_HM * mesh.vertex(i)).transpose();
  }
  const geometry::Aabb box = geometry::bounds(m_H);
  if (!(box.min.z() < 0.0)) return singlePatch(ContactVolume{.method = Method::kCgal});
  const Vector3d size = box.size() + Vector3d::Constant(box.size().maxCoeff());
  const Vector3d center(0.5 * (box.min.x() + box.max.x()), 0.5 * (box.min.y() + box.max.y()),
                        -0.5 * size.z());
  Eigen::Isometry3d X_HBox = Eigen::Isometry3d::Identity();
  X_HBox.translation() = center;
  ContactPatches inH = intersect(toCgal(m_H, Eigen::Isometry3d::Identity()),
                                 toCgal(geometry::tessellateBox(size), X_HBox));
  if (!inH.inContact()) return inH;
  ContactPatches inW;
  inW.aggregate = halfspaceToWorld(inH.aggregate, X_WH);
  for (const ContactVolume& patch : inH.patches)
    inW.patches.push_back(halfspaceToWorld(patch, X_WH));
  return inW;
}

ContactPatches cgalContact(const geometry::Shape& a, const Eigen::Isometry3d& X_WA,
                           const geometry::Shape& b, const Eigen::Isometry3d& X_WB) {
  const auto* meshA = std::get_if<geometry::Mesh>(&a);
  const auto* meshB = std::get_if<geometry::Mesh>(&b);
  if (meshA && meshB) return cgalMeshMeshContact(*meshA->mesh, X_WA, *meshB->mesh, X_WB);
  if (meshA) {
    assert(std::holds_alternative<geometry::HalfSpace>(b));
    return cgalMeshHalfspaceContact(*meshA->mesh, X_WA, X_WB);
  }
  assert(meshB && std::holds_alternative<geometry::HalfSpace>(a));
  return swapped(cgalMeshHalfspaceContact(*meshB->mesh, X_WB, X_WA));
}

}  // namespace vcontact::volume
