#pragma once
// Text forms of shapes and poses, shared by the command line and the JSON readers.
//
//   shape:  sphere:R | cylinder:R,L | box:X,Y,Z | halfspace | PATH[@SCALE]
//           (lengths in metres; PATH is a mesh file, SCALE multiplies its coordinates into
//            metres and is a number or a unit name: m, cm, mm, um, in, ft. The text after the
//            last '@' is a scale only when it reads as one: a path like a@b/part.stl stays a
//            path)
//   pose:   x,y,z | x,y,z,roll,pitch,yaw | x,y,z,qw,qx,qy,qz
//           (metres; roll, pitch, yaw in degrees about the fixed x, y, z axes, applied in
//            that order: R = Rz(yaw) Ry(pitch) Rx(roll); a quaternion is normalised after a
//            check that it is within 1e-6 of unit length)

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"
#include "io/mesh_io.hpp"

namespace vcontact::io {

struct ParsedShape {
  geometry::Shape shape;
  std::vector<std::string> warnings;  ///< mesh repairs and doubts
  MeshReadReport mesh;                ///< for a mesh file: repairs, shells, precision
};

/// @param source names the input in messages ("--pose-a", "scene.json: bodies[2].shape")
/// @param mesh   how a mesh file is read (repair or not)
/// @throws InputError naming `source` and what was expected
ParsedShape parseShape(const std::string& text, const std::string& source,
                       const MeshReadOptions& mesh = {});

/// Refuses a sphere, cylinder or box with a length outside io::kLengthRange (1e-6 to 1e3 m).
/// @throws InputError naming `source`, the length and the range
void checkShapeLengths(const geometry::Shape& shape, const std::string& source);

/// A mesh file's text PATH[@SCALE] split into the path and the scale into metres.
std::pair<std::string, double> splitMeshScale(const std::string& text);
Eigen::Isometry3d parsePose(const std::string& text, const std::string& source);

/// Pose from a translation and a quaternion (w, x, y, z), checked as parsePose does.
Eigen::Isometry3d poseFromQuaternion(const Eigen::Vector3d& t, const Eigen::Vector4d& wxyz,
                                     const std::string& source);
/// Pose from a translation and roll, pitch, yaw in degrees.
Eigen::Isometry3d poseFromRpyDegrees(const Eigen::Vector3d& t, const Eigen::Vector3d& rpy);

/// Splits "a,b,c" into numbers; throws InputError naming `source` on a non-number.
std::vector<double> parseNumberList(const std::string& text, const std::string& source);

}  // namespace vcontact::io
