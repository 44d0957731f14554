#include "io/mesh_io.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/STL.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/mesh_check.hpp"
#include "io/file_names.hpp"
#include "io/input_ranges.hpp"
#include "io/output_file.hpp"

namespace vcontact::io {
namespace {

// The faces of a file as read, before any welding: coordinates in the file's unit.
struct FileMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::string precision;
  std::vector<std::string> notes;
};

// A point as CGAL's STL reader merges them (a std::map keyed on the point): ordered so that
// a coordinate that is NaN never compares equal to a number, hence no vertex with a NaN
// vanishes into another before the finiteness check (issue 20). -0 and +0 are equal.
struct StlPoint {
  std::array<double, 3> x{};
  double& operator[](std::size_t i) { return x[i]; }
  double operator[](std::size_t i) const { return x[i]; }
  std::size_t size() const { return 3; }
  friend bool operator<(const StlPoint& a, const StlPoint& b) {
    const auto key = [](double v) { return std::pair(std::isnan(v), std::isnan(v) ? 0.0 : v); };
    for (std::size_t k = 0; k < 3; ++k) {
      if (key(a[k]) != key(b[k])) return key(a[k]) < key(b[k]);
    }
    return false;
  }
};

bool readStl(const std::string& path, FileMesh& out) {
  std::vector<StlPoint> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  if (!CGAL::IO::read_STL(path, points, triangles)) return false;
  for (const auto& p : points) out.points.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : triangles) out.polygons.push_back({t[0], t[1], t[2]});
  // Binary STL stores float32; an ASCII file holds the digits it was written with.
  std::ifstream in(path, std::ios::binary);
  std::string first;
  in >> first;
  const bool ascii = first == "solid" && out.polygons.size() > 0 &&
                     std::filesystem::file_size(path) != 84 + 50 * out.polygons.size();
  out.precision = ascii ? "double" : "single";
  return true;
}

bool readSoup(const std::string& path, const std::string& extension, FileMesh& out) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> points;
  if (!CGAL::IO::read_polygon_soup(path, points, out.polygons)) return false;
  for (const auto& p : points) out.points.emplace_back(p.x(), p.y(), p.z());
  // A PLY file declares its coordinate type; CGAL reads float properties as float.
  std::ifstream in(path);
  std::string header, line;
  while (extension == ".ply" && std::getline(in, line) && line != "end_header") header += line;
  out.precision = header.find("property float x") != std::string::npos ? "single" : "double";
  return true;
}

FileMesh readAssimp(const std::string& path) {
  Assimp::Importer importer;
  // Keep assimp from inventing geometry: no normal generation, no smoothing; bake node
  // transforms (glTF) and split polygons into triangles.
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                  aiProcess_ValidateDataStructure | aiProcess_SortByPType);
  if (scene == nullptr) {
    throw InputError(path, std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  FileMesh out;
  out.precision = "single";
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const std::size_t offset = out.points.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      out.points.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      out.polygons.emplace_back();
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        out.polygons.back().push_back(offset + face.mIndices[k]);
      }
    }
  }
  return out;
}

// A PLY header ends with an "end_header" line within its first kPlyHeaderLimit bytes; CGAL's
// reader is handed only a file whose header does (one that never ends hung a reader, issue
// 20), and whose every "property" follows an "element" (CGAL 5.5 reads the last element of
// an empty list otherwise: undefined behaviour, found by tests/fuzz). 64 KiB holds thousands
// of comment and property lines.
constexpr std::size_t kPlyHeaderLimit = 1 << 16;

bool isOneOf(const std::string& word, std::initializer_list<const char*> words) {
  return std::any_of(words.begin(), words.end(), [&](const char* w) { return word == w; });
}

// CGAL 5.5's PLY reader takes vertex coordinates of a floating-point type only (an integer one
// dereferences a null pointer: a crash, issue 36) and face indices of a 32-bit integer type
// only (it refuses others without saying why). Either is refused here with the line and type.
void checkPlyPropertyType(const std::string& element, std::istringstream& words, std::size_t n) {
  std::string type, indexType, name;
  words >> type;
  if (type == "list") words >> indexType >> indexType;  // the count's type, then the index's
  words >> name;
  const std::string at = "cannot read mesh: PLY header line " + std::to_string(n) + ": ";
  const bool vertex = element == "vertex" || element == "vertices";
  const bool face = element == "face" || element == "faces";
  if (vertex && type != "list" && isOneOf(name, {"x", "y", "z"}) &&
      !isOneOf(type, {"float", "double", "float32", "float64"})) {
    throw InputError("", at + "vertex coordinate '" + name + "' is of type '" + type +
                             "'; expected float or double (float32, float64): vcontact reads "
                             "no integer coordinates from PLY; export the mesh with "
                             "floating-point coordinates, or as STL or OBJ");
  }
  if (face && type == "list" && isOneOf(name, {"vertex_indices", "vertex_index"}) &&
      !isOneOf(indexType, {"int", "uint", "int32", "uint32"})) {
    throw InputError("", at + "face indices '" + name + "' are of type '" + indexType +
                             "'; expected int or uint (int32, uint32)");
  }
}

void checkPlyHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t read = 0;
  std::string element;  // the name of the element the properties belong to; empty before one
  bool any = false;
  for (std::size_t n = 1; read < kPlyHeaderLimit && std::getline(in, line); ++n) {
    read += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "end_header") return;
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (n == 1 && keyword != "ply") {
      throw InputError("", "cannot read mesh: line 1 is not \"ply\"; expected a PLY file");
    }
    if (keyword == "element") {
      any = true;
      words >> element;
    }
    if (keyword == "property" && !any) {
      throw InputError("", "cannot read mesh: PLY header line " + std::to_string(n) +
                               ": a property before any element; expected \"element NAME "
                               "COUNT\" first");
    }
    if (keyword == "property") checkPlyPropertyType(element, words, n);
  }
  throw InputError("", "cannot read mesh: the PLY header has no \"end_header\" line in its first " +
                           std::to_string(kPlyHeaderLimit) + " bytes");
}

// CGAL's text readers refuse "nan" and "inf" without saying so; a file they refused is
// searched for such a word, so that the message names the line (binary files hold none).
void refuseNonFiniteToken(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, word;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    std::istringstream words(line);
    while (words >> word) {
      std::string w;
      for (const char c : word) w += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (!w.empty() && (w[0] == '-' || w[0] == '+')) w.erase(0, 1);
      if (w == "nan" || w == "inf" || w == "infinity") {
        throw InputError(
            "", "line " + std::to_string(n) + ": '" + word +
                    "': a vertex with a NaN or infinite coordinate; expected a finite number");
      }
    }
  }
}

// STL, OBJ, OFF and PLY are read by CGAL, which fails cleanly on a broken file; only the
// formats CGAL does not read go to assimp (which aborted the process on a crafted PLY file).
FileMesh readFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  const bool cgalFormat = ext == ".stl" || ext == ".obj" || ext == ".off" || ext == ".ply";
  if (!cgalFormat) return readAssimp(path);
  if (ext == ".ply") checkPlyHeader(path);
  FileMesh out;
  if (ext == ".stl" ? readStl(path, out) : readSoup(path, ext, out)) return out;
  refuseNonFiniteToken(path);
  throw InputError("", "cannot read mesh: not a valid " + ext.substr(1) +
                           " file (CGAL's reader refused it; is it truncated or of another "
                           "format?)");
}

void checkPolygonIndices(const FileMesh& file) {
  for (std::size_t f = 0; f < file.polygons.size(); ++f) {
    for (const std::size_t v : file.polygons[f]) {
      if (v >= file.points.size()) {
        throw InputError("", "face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + ", but the file has " +
                                 std::to_string(file.points.size()) + " vertices");
      }
    }
  }
}

// The file's triangles on its own vertices; polygons split (points and lines carry no volume).
geometry::TriangleMesh triangles(const FileMesh& file) {
  std::vector<Eigen::Vector3i> faces;
  for (const auto& polygon : file.polygons) {
    if (polygon.size() == 3) {
      faces.emplace_back(polygon[0], polygon[1], polygon[2]);
    } else if (polygon.size() > 3) {
      std::vector<Eigen::Vector3d> corners;
      for (const std::size_t v : polygon) corners.push_back(file.points[v]);
      for (const auto& t : geometry::triangulatePolygon(corners)) {
        faces.emplace_back(polygon[t[0]], polygon[t[1]], polygon[t[2]]);
      }
    }
  }
  geometry::TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(file.points.size()), 3);
  for (std::size_t i = 0; i < file.points.size(); ++i) {
    out.vertices.row(static_cast<Eigen::Index>(i)) = file.points[i];
  }
  out.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    out.triangles.row(static_cast<Eigen::Index>(i)) = faces[i];
  }
  return out;
}

// Exact-position welding, in the order vertices are first used: STL stores every triangle's
// corners separately, and other formats may repeat a vertex where normals differ.
geometry::TriangleMesh weld(const geometry::TriangleMesh& raw, double scale) {
  std::map<std::array<double, 3>, int> index;
  std::vector<int> welded(static_cast<std::size_t>(raw.vertexCount()), -1);
  geometry::TriangleMesh out;
  out.triangles.resize(raw.triangleCount(), 3);
  std::vector<Eigen::Vector3d> vertices;
  for (Eigen::Index f = 0; f < raw.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = raw.triangles(f, k);
      if (welded[v] < 0) {
        const Eigen::Vector3d p = raw.vertex(v);
        const auto [it, added] =
            index.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, vertices.size());
        if (added) vertices.emplace_back(scale * p.x(), scale * p.y(), scale * p.z());
        welded[v] = it->second;
      }
      out.triangles(f, k) = welded[v];
    }
  }
  out.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    out.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i];
  }
  return out;
}

std::optional<std::string> largePartWarning(const geometry::TriangleMesh& mesh) {
  const double size = geometry::bounds(mesh).size().maxCoeff();
  if (size <= kLargestPlausibleSize) return std::nullopt;
  std::ostringstream os;
  os.precision(4);
  os << "the part is " << size << " m across, implausible for a file in metres; if the file is "
     << "in millimetres, read it with scale 0.001 (PATH@mm)";
  return os.str();
}

// The part's extent in metres within kLengthRange (io/input_ranges.hpp): beyond it a scale
// or the coordinates are absurd, and the face checks would report the rounding instead.
void checkExtent(const geometry::TriangleMesh& mesh, double scale) {
  const double size = geometry::bounds(mesh).size().maxCoeff();
  const std::string why = outOfRange(size, kLengthRange, "the part's extent");
  if (why.empty()) return;
  std::ostringstream os;
  os << why << " (coordinates times the scale " << scale << ")";
  throw InputError("", os.str());
}

}  // namespace

std::optional<double> unitScale(const std::string& name) {
  static const std::map<std::string, double> kUnits = {
      {"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"um", 1e-6}, {"in", 0.0254}, {"ft", 0.3048}};
  const auto it = kUnits.find(name);
  return it == kUnits.end() ? std::nullopt : std::optional<double>(it->second);
}

std::optional<std::string> lightPartWarning(const geometry::TriangleMesh& mesh, double density) {
  const double mass = density * geometry::meshMoments(mesh).m0;
  if (!(density > 0.0) || mass >= kLightestPlausibleMass) return std::nullopt;
  std::ostringstream os;
  os.precision(4);
  os << "the part weighs " << mass << " kg at " << density
     << " kg/m^3, less than a milligram; if the file is in metres, read it with scale 1 "
     << "(no @SCALE)";
  return os.str();
}

MeshReadResult readMesh(const std::string& path, double scale, const MeshReadOptions& options) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw InputError(path, "scale must be a finite positive number, got " + std::to_string(scale));
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path, "is a folder; expected a mesh file");
  }
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "no such file");
  MeshReadResult result;
  try {
    const FileMesh file = readFile(path);
    checkPolygonIndices(file);
    const geometry::TriangleMesh raw = triangles(file);
    if (raw.triangleCount() == 0) throw InputError("", "file holds no triangles");
    geometry::checkFinite(raw);
    result.report.precision = file.precision;
    result.report.doubts = file.notes;
    result.mesh = weld(raw, scale);
    checkExtent(result.mesh, scale);
    if (options.repair) {
      geometry::RepairResult repaired = geometry::repairMesh(result.mesh, options.repairOptions);
      result.mesh = std::move(repaired.mesh);
      result.report.repairs = std::move(repaired.changes);
    }
    geometry::MeshCheckResult checked = geometry::checkAndRepair(result.mesh);
    auto& repairs = result.report.repairs;
    repairs.insert(repairs.end(), checked.warnings.begin(), checked.warnings.end());
    result.report.shells = checked.shells;
  } catch (const InputError& e) {
    throw e.withSource(path);
  }
  if (auto w = largePartWarning(result.mesh)) result.report.doubts.push_back(*w);
  for (const auto* list : {&result.report.repairs, &result.report.doubts}) {
    for (const auto& w : *list) result.warnings.push_back(path + ": " + w);
  }
  return result;
}

namespace {

void putStl(const geometry::TriangleMesh& mesh, std::ostream& out) {
  std::array<char, 80> header{};
  const std::string title = "vcontact binary STL, metres";
  std::copy(title.begin(), title.end(), header.begin());
  out.write(header.data(), header.size());
  const auto count = static_cast<std::uint32_t>(mesh.triangleCount());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3d a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    std::array<float, 12> v{};
    for (int k = 0; k < 3; ++k) {
      v[k] = static_cast<float>(n[k]);
      v[3 + k] = static_cast<float>(a[k]);
      v[6 + k] = static_cast<float>(b[k]);
      v[9 + k] = static_cast<float>(c[k]);
    }
    out.write(reinterpret_cast<const char*>(v.data()), sizeof(float) * 12);
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

void putObj(const geometry::TriangleMesh& mesh, std::ostream& out) {
  out.precision(17);
  out << "# vcontact mesh, metres\n";
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    out << "v " << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' ' << mesh.vertices(i, 2)
        << '\n';
  }
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    out << "f " << mesh.triangles(f, 0) + 1 << ' ' << mesh.triangles(f, 1) + 1 << ' '
        << mesh.triangles(f, 2) + 1 << '\n';
  }
}

}  // namespace

void writeStl(const geometry::TriangleMesh& mesh, const std::string& path) {
  writeFile(
      path, [&](std::ostream& out) { putStl(mesh, out); }, std::ios::binary);
}

void writeObj(const geometry::TriangleMesh& mesh, const std::string& path) {
  writeFile(path, [&](std::ostream& out) { putObj(mesh, out); });
}

void writeMesh(const geometry::TriangleMesh& mesh, const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return writeObj(mesh, path);
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  const bool special = !ec && std::filesystem::exists(status) &&
                       !std::filesystem::is_regular_file(status) &&
                       !std::filesystem::is_directory(status);
  if (ext == ".stl" || special) return writeStl(mesh, path);  // a device or pipe takes STL
  const std::string what = ext.empty() ? "a name without an extension" : "'" + ext + "'";
  throw InputError(path, "cannot write a mesh to " + what +
                             "; expected a file name ending in .stl (binary STL) or .obj");
}

}  // namespace vcontact::io
