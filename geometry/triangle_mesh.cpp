#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

Aabb bounds(const TriangleMesh& mesh) {
  if (mesh.vertexCount() == 0) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  return {mesh.vertices.colwise().minCoeff().transpose(),
          mesh.vertices.colwise().maxCoeff().transpose()};
}

}  // namespace vcontact::geometry
