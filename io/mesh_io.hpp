#pragma once
// Mesh files in and out. Reading goes through assimp (STL ASCII and binary, OBJ, PLY, OFF,
// glTF 2 .gltf/.glb and whatever else assimp knows), welds vertices at equal positions,
// scales into metres and checks the result (geometry/mesh_check.hpp).
//
// assimp as packaged by Debian stores coordinates in single precision, so a file's
// coordinates arrive with about 7 significant digits whatever the file holds.

#include <string>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace vcontact::io {

struct MeshReadResult {
  geometry::TriangleMesh mesh;
  std::vector<std::string> warnings;  ///< repairs, each prefixed with the file name
};

/// @param path  the file
/// @param scale multiplies the file's coordinates into metres (0.001 for millimetres)
/// @throws InputError naming the file and the defect
MeshReadResult readMesh(const std::string& path, double scale = 1.0);

/// Writes a binary STL (the format every CAD tool reads); coordinates in metres.
/// @throws InputError when the file cannot be written
void writeStl(const geometry::TriangleMesh& mesh, const std::string& path);

/// Writes a Wavefront OBJ with full double precision.
void writeObj(const geometry::TriangleMesh& mesh, const std::string& path);

}  // namespace vcontact::io
