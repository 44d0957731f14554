#include "volume/kernels/mesh_convexity.hpp"

#include <Eigen/Geometry>

#include "geometry/error.hpp"
#include "geometry/mesh_topology.hpp"
#include "volume/kernels/mesh_cache.hpp"

namespace vcontact::volume {
namespace {

/// sin of the fold below which an edge counts as flat: the two triangles of a planar quad
/// (a UV sphere's) fold by rounding only, ~1e-16; a fold of 1e-9 rad moves a cut by 1e-9 of
/// the faces' size, far below any region it could split off.
constexpr double kFlatFold = 1e-9;

/// Every edge convex: the corner of tri[1] off the edge is not above tri[0]'s plane.
bool edgesConvex(const geometry::TriangleMesh& mesh, const geometry::MeshTopology& topo) {
  for (const geometry::MeshEdge& e : topo.edges()) {
    const int t0 = e.tri[0], t1 = e.tri[1];
    int far = mesh.triangles(t1, 0);
    for (int k = 1; k < 3 && (far == e.v0 || far == e.v1); ++k) far = mesh.triangles(t1, k);
    const Eigen::Vector3d a = mesh.corner(t0, 0);
    const Eigen::Vector3d N = (mesh.corner(t0, 1) - a).cross(mesh.corner(t0, 2) - a);
    const Eigen::Vector3d d = mesh.vertex(far) - a;
    if (N.dot(d) > kFlatFold * N.norm() * d.norm()) return false;
  }
  return true;
}

}  // namespace

MeshConvexity::MeshConvexity(const geometry::TriangleMesh& mesh) {
  try {
    const geometry::MeshTopology topo(mesh);
    convex = topo.components().size() == 1 && edgesConvex(mesh, topo);
  } catch (const InputError&) {
    convex = false;  // not closed: the clip's own checks report it
  }
}

bool isConvex(const std::shared_ptr<const geometry::TriangleMesh>& mesh) {
  return derivedOf<MeshConvexity>(mesh)->convex;
}

}  // namespace vcontact::volume
