#include "io/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>

#include "geometry/error.hpp"
#include "geometry/mesh_check.hpp"

namespace vcontact::io {
namespace {

geometry::TriangleMesh weld(const aiScene& scene, double scale) {
  // Exact-position welding: STL stores every triangle's corners separately, and assimp's
  // own JoinIdenticalVertices keeps corners apart whose normals differ.
  std::map<std::array<float, 3>, int> index;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    std::vector<int> local(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const auto [it, added] =
          index.emplace(std::array<float, 3>{p.x, p.y, p.z}, static_cast<int>(vertices.size()));
      if (added) vertices.emplace_back(scale * p.x, scale * p.y, scale * p.z);
      local[v] = it->second;
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no volume
      faces.emplace_back(local[face.mIndices[0]], local[face.mIndices[1]], local[face.mIndices[2]]);
    }
  }
  geometry::TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  out.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    out.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i];
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    out.triangles.row(static_cast<Eigen::Index>(i)) = faces[i];
  }
  return out;
}

}  // namespace

MeshReadResult readMesh(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw InputError(path, "scale must be a finite positive number, got " + std::to_string(scale));
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path, "no such file");
  }
  Assimp::Importer importer;
  // Keep assimp from inventing geometry: no normal generation, no smoothing; bake node
  // transforms (glTF) and split polygons into triangles.
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                  aiProcess_ValidateDataStructure | aiProcess_SortByPType);
  if (scene == nullptr) {
    throw InputError(path, std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  MeshReadResult result;
  result.mesh = weld(*scene, scale);
  if (result.mesh.triangleCount() == 0) throw InputError(path, "file holds no triangles");
  try {
    for (auto& w : geometry::checkAndRepair(result.mesh).warnings) {
      result.warnings.push_back(path + ": " + w);
    }
  } catch (const InputError& e) {
    throw e.withSource(path);
  }
  return result;
}

void writeStl(const geometry::TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path, "cannot open for writing");
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
  if (!out) throw InputError(path, "write failed");
}

void writeObj(const geometry::TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "cannot open for writing");
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
  if (!out) throw InputError(path, "write failed");
}

}  // namespace vcontact::io
