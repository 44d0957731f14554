#pragma once
// The shapes a body can have. Each is defined in its own frame:
//   Sphere   centred at the origin;
//   Cylinder axis z, centred (z ∈ [−L/2, L/2]);
//   Box      centred, edges along the axes;
//   HalfSpace the solid z ≤ 0, outward normal +z;
//   Mesh     a closed, outward-oriented triangle mesh in its body frame.
// A shape is placed in the world by an Eigen::Isometry3d X_WS (pose of shape S in world W).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <variant>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::geometry {

struct Sphere {
  double radius;  ///< m
};
struct Cylinder {
  double radius;  ///< m
  double length;  ///< m, along the frame's z axis
};
struct Box {
  Eigen::Vector3d size;  ///< full edge lengths along x, y, z (m)
};
struct HalfSpace {};
struct Mesh {
  std::shared_ptr<const TriangleMesh> mesh;
  std::string name;  ///< where it came from (file name), for messages
};

using Shape = std::variant<Sphere, Cylinder, Box, HalfSpace, Mesh>;

/// "sphere", "cylinder", "box", "halfspace" or "mesh".
std::string shapeKind(const Shape& shape);
/// One-line description with dimensions, for tables and messages.
std::string describe(const Shape& shape);

/// Throws InputError (source = `source`) unless every dimension is finite and positive.
void validate(const Shape& shape, const std::string& source);

}  // namespace vcontact::geometry
