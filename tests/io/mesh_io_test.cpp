// Mesh files of every supported format read into the same solid; bad files are rejected
// with one message naming the file and the defect. One invalid-input test file per reader.

#include "io/mesh_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/tessellate.hpp"

namespace vcontact::io {
namespace {

namespace fs = std::filesystem;
using geometry::TriangleMesh;

// assimp stores coordinates as float: 24-bit mantissa, so a volume (three coordinates
// multiplied) is good to a few 1e-7.
constexpr double kFloatVolumeTolerance = 1e-6;

class MeshFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("vcontact_mesh_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  fs::path dir_;
  const TriangleMesh box_ = geometry::tessellateBox({0.03, 0.05, 0.07});
  const double boxVolume_ = 0.03 * 0.05 * 0.07;
};

std::string asciiStl(const TriangleMesh& m) {
  std::ostringstream os;
  os.precision(9);
  os << "solid box\n";
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    os << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) os << "   vertex " << m.corner(f, k).transpose() << "\n";
    os << "  endloop\n endfacet\n";
  }
  os << "endsolid box\n";
  return os.str();
}

std::string ply(const TriangleMesh& m) {
  std::ostringstream os;
  os.precision(9);
  os << "ply\nformat ascii 1.0\nelement vertex " << m.vertexCount()
     << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangleCount()
     << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) os << m.vertex(i).transpose() << "\n";
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) os << "3 " << m.triangles.row(f) << "\n";
  return os.str();
}

std::string off(const TriangleMesh& m) {
  std::ostringstream os;
  os.precision(9);
  os << "OFF\n" << m.vertexCount() << " " << m.triangleCount() << " 0\n";
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) os << m.vertex(i).transpose() << "\n";
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) os << "3 " << m.triangles.row(f) << "\n";
  return os.str();
}

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    unsigned n = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

// A glTF 2 file with one triangle mesh in an embedded buffer (float32 positions, uint32
// indices), as exporters write it.
std::string gltf(const TriangleMesh& m) {
  std::string bytes;
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = -lo;
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) {
    const Eigen::Vector3f p = m.vertex(i).cast<float>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    bytes.append(reinterpret_cast<const char*>(p.data()), 12);
  }
  const std::size_t positions = bytes.size();
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = static_cast<std::uint32_t>(m.triangles(f, k));
      bytes.append(reinterpret_cast<const char*>(&v), 4);
    }
  }
  std::ostringstream os;
  os << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
     << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
     << R"("buffers":[{"byteLength":)" << bytes.size()
     << R"(,"uri":"data:application/octet-stream;base64,)" << base64(bytes) << R"("}],)"
     << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" << positions
     << R"(},{"buffer":0,"byteOffset":)" << positions << R"(,"byteLength":)"
     << bytes.size() - positions << R"(}],)"
     << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << m.vertexCount()
     << R"(,"type":"VEC3","min":[)" << lo.x() << "," << lo.y() << "," << lo.z() << R"(],"max":[)"
     << hi.x() << "," << hi.y() << "," << hi.z() << R"(]},)"
     << R"({"bufferView":1,"componentType":5125,"count":)" << 3 * m.triangleCount()
     << R"(,"type":"SCALAR"}]})";
  return os.str();
}

TEST_F(MeshFiles, EveryFormatReadsTheSameSolid) {
  writeStl(box_, path("box_binary.stl"));
  writeObj(box_, path("box.obj"));
  const std::vector<std::string> files = {path("box_binary.stl"),
                                          write("box_ascii.stl", asciiStl(box_)),
                                          path("box.obj"),
                                          write("box.ply", ply(box_)),
                                          write("box.off", off(box_)),
                                          write("box.gltf", gltf(box_))};
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const MeshReadResult r = readMesh(file);
    EXPECT_EQ(r.mesh.vertexCount(), 8) << "corners must be welded";
    EXPECT_EQ(r.mesh.triangleCount(), 12);
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_NEAR(geometry::meshMoments(r.mesh).m0 / boxVolume_, 1.0, kFloatVolumeTolerance);
  }
}

TEST_F(MeshFiles, ScaleConvertsUnits) {
  TriangleMesh mm = box_;
  mm.vertices *= 1000.0;  // the same box in millimetres
  writeStl(mm, path("box_mm.stl"));
  const MeshReadResult r = readMesh(path("box_mm.stl"), 0.001);
  EXPECT_NEAR(geometry::meshMoments(r.mesh).m0 / boxVolume_, 1.0, kFloatVolumeTolerance);
}

TEST_F(MeshFiles, InvertedFileIsFlippedWithAWarningNamingTheFile) {
  TriangleMesh inverted = box_;
  inverted.triangles.col(1).swap(inverted.triangles.col(2));
  writeObj(inverted, path("inside_out.obj"));
  const MeshReadResult r = readMesh(path("inside_out.obj"));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].rfind(path("inside_out.obj") + ": faces were oriented inward", 0), 0u)
      << r.warnings[0];
  EXPECT_GT(geometry::meshMoments(r.mesh).m0, 0.0);
}

std::string rejection(const std::string& file, double scale = 1.0) {
  try {
    readMesh(file, scale);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(MeshFiles, OpenMeshIsRejectedNamingFileAndDefect) {
  TriangleMesh open = box_;
  open.triangles.conservativeResize(11, 3);
  writeObj(open, path("part.obj"));
  const std::string msg = rejection(path("part.obj"));
  EXPECT_EQ(
      msg.rfind(path("part.obj") + ": 3 boundary edges, mesh is not closed; first at vertex (", 0),
      0u)
      << msg;
}

TEST_F(MeshFiles, MissingFile) {
  EXPECT_EQ(rejection(path("nowhere.stl")), path("nowhere.stl") + ": no such file");
}

TEST_F(MeshFiles, GarbageFile) {
  const std::string msg = rejection(write("junk.stl", "this is not a mesh\n"));
  EXPECT_EQ(msg.rfind(path("junk.stl") + ": ", 0), 0u) << msg;
}

TEST_F(MeshFiles, NonPositiveScale) {
  writeStl(box_, path("box.stl"));
  EXPECT_NE(rejection(path("box.stl"), 0.0).find("scale must be a finite positive number"),
            std::string::npos);
}

TEST_F(MeshFiles, DegenerateFaceInFile) {
  TriangleMesh bad = box_;
  bad.triangles(0, 1) = bad.triangles(0, 0);
  writeObj(bad, path("flat.obj"));
  const std::string msg = rejection(path("flat.obj"));
  EXPECT_NE(msg.find(path("flat.obj") + ": "), std::string::npos) << msg;
  EXPECT_NE(msg.find("degenerate"), std::string::npos) << msg;
}

}  // namespace
}  // namespace vcontact::io
