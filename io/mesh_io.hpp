#pragma once
// Mesh files in and out.
//
// Reading: STL, OBJ, OFF and PLY through CGAL's polygon-soup readers, which keep the
// precision the file has: ASCII STL, OBJ, OFF and PLY with double properties arrive in double
// precision; binary STL is single precision on disk, and so is PLY with float properties.
// A file of these formats that CGAL's reader refuses is refused (it is never handed to
// assimp, which can abort the process on a crafted file), and so is a PLY file whose header
// does not end within 64 KiB. Every other format (glTF 2 .gltf/.glb, COLLADA .dae, 3MF, ...)
// goes through assimp, which as packaged by Debian stores coordinates in single precision
// (about 7 significant digits). Polygons are split into triangles, coordinates are checked
// finite before anything else, vertices at equal positions are welded, the coordinates scaled
// into metres and the part's extent checked against io/input_ranges.hpp (1e-6 to 1e3 m),
// optionally repaired (geometry/mesh_repair.hpp), and the result checked
// (geometry/mesh_check.hpp).

#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh_repair.hpp"
#include "geometry/triangle_mesh.hpp"

namespace vcontact::io {

/// Above this extent (m) a part read as metres is most likely in millimetres.
inline constexpr double kLargestPlausibleSize = 10.0;
/// Below this mass (kg, a milligram) a part read as metres is most likely scaled twice.
inline constexpr double kLightestPlausibleMass = 1e-6;

struct MeshReadOptions {
  bool repair = false;  ///< run geometry::repairMesh before the checks
  geometry::RepairOptions repairOptions;
};

/// What reading a mesh found, beside the mesh.
struct MeshReadReport {
  std::vector<std::string> repairs;  ///< what the repair and the check changed, unprefixed
  std::vector<std::string> doubts;   ///< other warnings (units, precision), unprefixed
  std::size_t shells = 1;            ///< closed shells of the surface
  std::string precision;             ///< "double" or "single": how the coordinates were read
};

struct MeshReadResult {
  geometry::TriangleMesh mesh;
  std::vector<std::string> warnings;  ///< repairs and doubts, each prefixed with the file name
  MeshReadReport report;
};

/// @param path  the file
/// @param scale multiplies the file's coordinates into metres (0.001 for millimetres)
/// @throws InputError naming the file and the defect; without the repair, a defect that a
///   repair would fix is named with that repair
MeshReadResult readMesh(const std::string& path, double scale = 1.0,
                        const MeshReadOptions& options = {});

/// The factor into metres of a unit name: m, cm, mm, um, in, ft; nullopt for another text.
std::optional<double> unitScale(const std::string& name);

/// A warning when a part of this mesh and density (kg/m^3) weighs less than a milligram,
/// naming the likely scale; nullopt when its mass is plausible or the density not positive.
std::optional<std::string> lightPartWarning(const geometry::TriangleMesh& mesh, double density);

/// Writes a binary STL (the format every CAD tool reads); coordinates in metres.
/// @throws InputError when the file cannot be written
void writeStl(const geometry::TriangleMesh& mesh, const std::string& path);

/// Writes a Wavefront OBJ with full double precision.
void writeObj(const geometry::TriangleMesh& mesh, const std::string& path);

/// Writes `path` in the format its extension names, in any case: ".obj" (".OBJ") an OBJ,
/// ".stl" a binary STL; a device or pipe (/dev/stdout) with another name a binary STL too.
/// @throws InputError naming `path` for another extension (a file the reader would then refuse
///   or misread, issue 36) or when the file cannot be written
void writeMesh(const geometry::TriangleMesh& mesh, const std::string& path);

}  // namespace vcontact::io
