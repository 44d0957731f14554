// Mesh files of every supported format read into the same solid; bad files are rejected
// with one message naming the file and the defect. One invalid-input test file per reader.

#include "io/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/defect_meshes.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/tessellate.hpp"
#include "io/file_names.hpp"
#include "io/shape_json.hpp"
#include "support/test_support.hpp"

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

std::string asciiStl(const TriangleMesh& m, int digits = 9) {
  std::ostringstream os;
  os.precision(digits);
  os << "solid box\n";
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    os << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) os << "   vertex " << m.corner(f, k).transpose() << "\n";
    os << "  endloop\n endfacet\n";
  }
  os << "endsolid box\n";
  return os.str();
}

std::string ply(const TriangleMesh& m, int digits = 9, const std::string& type = "float") {
  std::ostringstream os;
  os.precision(digits);
  os << "ply\nformat ascii 1.0\nelement vertex " << m.vertexCount() << "\nproperty " << type
     << " x\nproperty " << type << " y\nproperty " << type << " z\nelement face "
     << m.triangleCount() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) os << m.vertex(i).transpose() << "\n";
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) os << "3 " << m.triangles.row(f) << "\n";
  return os.str();
}

std::string off(const TriangleMesh& m, int digits = 9) {
  std::ostringstream os;
  os.precision(digits);
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

TEST_F(MeshFiles, TextFormatsAreReadInDoublePrecision) {
  // A part whose coordinates need 12 significant digits, away from the origin, as a flat
  // part pressed nanometres into a plate needs them.
  TriangleMesh part = geometry::tessellateBox({0.0123456789012, 0.0234567890123, 2.0345678901e-5});
  part.vertices.rowwise() += Eigen::RowVector3d(0.123456789012, -0.0456789012345, 0.0789012345678);
  const double volume = geometry::meshMoments(part).m0;
  writeObj(part, path("part.obj"));
  const std::vector<std::string> files = {write("part.stl", asciiStl(part, 17)), path("part.obj"),
                                          write("part.off", off(part, 17)),
                                          write("part.ply", ply(part, 17, "double"))};
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const MeshReadResult r = readMesh(file);
    EXPECT_EQ(r.report.precision, "double");
    // 17 digits give back every double, so only the summation order can differ: 1e-12 is the
    // issue's bound, a float coordinate would miss it by five orders.
    EXPECT_NEAR(geometry::meshMoments(r.mesh).m0 / volume, 1.0, 1e-12);
  }
}

TEST_F(MeshFiles, BinaryStlAndFloatPlyAreSinglePrecision) {
  writeStl(box_, path("box.stl"));
  EXPECT_EQ(readMesh(path("box.stl")).report.precision, "single");
  EXPECT_EQ(readMesh(write("box.ply", ply(box_))).report.precision, "single");
  EXPECT_EQ(readMesh(write("box.gltf", gltf(box_))).report.precision, "single");
}

TEST_F(MeshFiles, PolygonFacesAreSplitIntoTriangles) {
  // The box as six quads in an OFF file.
  const std::string quads =
      "OFF\n8 6 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
      "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  const MeshReadResult r = readMesh(write("quads.off", quads));
  EXPECT_EQ(r.mesh.triangleCount(), 12);
  EXPECT_DOUBLE_EQ(geometry::meshMoments(r.mesh).m0, 1.0);
}

TEST_F(MeshFiles, RepairedMeshWrittenAndReadBackIsTheSame) {
  writeObj(test::withSeam(box_, 3, 1e-10), path("seam.obj"));
  MeshReadOptions repair;
  repair.repair = true;
  const MeshReadResult first = readMesh(path("seam.obj"), 1.0, repair);
  ASSERT_FALSE(first.report.repairs.empty());
  writeObj(first.mesh, path("repaired.obj"));
  const MeshReadResult again = readMesh(path("repaired.obj"));
  EXPECT_TRUE(again.report.repairs.empty());
  EXPECT_EQ(again.mesh.vertices, first.mesh.vertices);
  EXPECT_EQ(again.mesh.triangles, first.mesh.triangles);
}

TEST_F(MeshFiles, MillimetreFileReadAsMetresIsNamedWithItsScale) {
  TriangleMesh mm = box_;
  mm.vertices *= 1000.0;
  writeStl(mm, path("box_mm.stl"));
  const MeshReadResult r = readMesh(path("box_mm.stl"));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("70 m across, implausible for a file in metres"), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("PATH@mm"), std::string::npos);
  EXPECT_TRUE(readMesh(path("box_mm.stl"), 0.001).warnings.empty());
}

TEST_F(MeshFiles, ShapeJsonTakesRepairAndAUnitName) {
  TriangleMesh mm = test::withSeam(box_, 3, 1e-10);
  mm.vertices *= 1000.0;
  writeObj(mm, path("seam_mm.obj"));
  const auto j = nlohmann::json::parse(R"({"mesh": "seam_mm.obj", "scale": "mm"})");
  EXPECT_NE(test::inputErrorMessage([&] {
              parseShapeJson(j, "rig.json: payload", dir_.string());
            }).find("boundary edges"),
            std::string::npos);
  nlohmann::json repaired = j;
  repaired["repair"] = true;
  const JsonShape s = parseShapeJson(repaired, "rig.json: payload", dir_.string());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("welded 1 vertex"), std::string::npos);
  EXPECT_NEAR(geometry::meshMoments(*std::get<geometry::Mesh>(s.shape).mesh).m0 / boxVolume_, 1.0,
              1e-12);  // a weld of 1e-10 m moves nothing of the box: summation order only
  repaired["repair"] = "yes";
  EXPECT_NE(test::inputErrorMessage([&] {
              parseShapeJson(repaired, "rig.json: payload", ".");
            }).find("\"repair\" must be true or false"),
            std::string::npos);
}

TEST(BundledMeshes, ReadWithoutWarnings) {
  for (const auto& dir : {"meshes", "scenarios/meshes", "scenarios/meshes/bin"}) {
    for (const auto& entry : fs::directory_iterator(fs::path(VCONTACT_ASSETS_DIR) / dir)) {
      if (entry.path().extension() != ".stl") continue;
      SCOPED_TRACE(entry.path().string());
      const MeshReadResult r = readMesh(entry.path().string());
      EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
      EXPECT_FALSE(lightPartWarning(r.mesh, 7900.0).has_value());
    }
  }
}

TEST(LightPart, WarnsBelowAMilligramAndNamesTheScale) {
  // A 1 mm cube of steel weighs 7.9 mg; read as millimetres from a metre file, 7.9e-9 mg.
  const TriangleMesh mm = geometry::tessellateBox({1e-3, 1e-3, 1e-3});
  EXPECT_FALSE(lightPartWarning(mm, 7900.0).has_value());
  const auto w = lightPartWarning(geometry::tessellateBox({1e-6, 1e-6, 1e-6}), 7900.0);
  ASSERT_TRUE(w.has_value());
  EXPECT_NE(w->find("less than a milligram; if the file is in metres, read it with scale 1"),
            std::string::npos)
      << *w;
}

TEST(UnitNames, AreTheirFactors) {
  EXPECT_EQ(unitScale("mm"), 0.001);
  EXPECT_EQ(unitScale("in"), 0.0254);
  EXPECT_EQ(unitScale("ft"), 0.3048);
  EXPECT_FALSE(unitScale("furlong").has_value());
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

TEST_F(MeshFiles, NanVertexIsRejectedBeforeWelding) {
  // Issue 20: a NaN corner used to vanish into a welded vertex. Vertex 5 gets a sentinel x,
  // written wherever a face uses it (as STL does), then replaced by "nan" in the text.
  TriangleMesh marked = box_;
  marked.vertices(5, 0) = 12345.0;
  std::string stl = asciiStl(marked);
  for (auto at = stl.find("12345"); at != std::string::npos; at = stl.find("12345", at)) {
    stl.replace(at, 5, "  nan");
  }
  const std::string msg = rejection(write("nan.stl", stl));
  EXPECT_NE(msg.find("with a NaN or infinite coordinate"), std::string::npos) << msg;
}

TEST_F(MeshFiles, DegenerateFaceInFile) {
  TriangleMesh bad = box_;
  bad.triangles(0, 1) = bad.triangles(0, 0);
  writeObj(bad, path("flat.obj"));
  const std::string msg = rejection(path("flat.obj"));
  EXPECT_NE(msg.find(path("flat.obj") + ": "), std::string::npos) << msg;
  EXPECT_NE(msg.find("degenerate"), std::string::npos) << msg;
}

// Issue 20: a PLY header without "end_header" hung the reader; now it is refused at once.
TEST_F(MeshFiles, PlyHeaderThatNeverEnds) {
  std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n";
  for (int i = 0; i < 5000; ++i) header += "comment no end in sight\n";
  const std::string msg = rejection(write("endless.ply", header));
  EXPECT_EQ(msg, path("endless.ply") +
                     ": cannot read mesh: the PLY header has no \"end_header\" line in its "
                     "first 65536 bytes");
}

// Found by tests/fuzz/mesh_reader_fuzz: CGAL 5.5's PLY reader took the last element of an
// empty list on a property before any element (undefined behaviour under UBSan).
TEST_F(MeshFiles, PlyPropertyBeforeAnyElement) {
  const std::string msg = rejection(write(
      "early.ply", "ply\nformat ascii 1.0\nproperty double x\nelement vertex 1\nend_header\n0\n"));
  EXPECT_EQ(msg, path("early.ply") +
                     ": cannot read mesh: PLY header line 3: a property before any element; "
                     "expected \"element NAME COUNT\" first");
}

// A PLY file of integer coordinates (a box of side 1, 2, 3 in the file's unit) in `format`:
// "ascii", or "binary_little_endian" with each coordinate stored as a 4-byte int whatever the
// declared type (the reader is to refuse it at the header, before any data is read).
std::string integerPly(const std::string& type, const std::string& format,
                       const std::string& indexType = "int", const std::string& coordType = "") {
  const TriangleMesh m = geometry::tessellateBox({1.0, 2.0, 3.0});
  const std::string t = coordType.empty() ? type : coordType;
  std::ostringstream os;
  os << "ply\nformat " << format << " 1.0\nelement vertex " << m.vertexCount() << "\nproperty " << t
     << " x\nproperty " << t << " y\nproperty " << t << " z\nelement face " << m.triangleCount()
     << "\nproperty list uchar " << indexType << " vertex_indices\nend_header\n";
  const bool ascii = format == "ascii";
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) {
    for (int k = 0; k < 3; ++k) {
      // whole numbers: the box moved by 1.5 along each axis, truncation keeps its sides
      const auto v = static_cast<std::int32_t>(m.vertices(i, k) + 1.5);
      if (ascii) os << v << (k < 2 ? " " : "\n");
      if (!ascii) os.write(reinterpret_cast<const char*>(&v), 4);
    }
  }
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f) {
    if (ascii) os << "3 " << m.triangles.row(f) << "\n";
    if (ascii) continue;
    const char three = 3;
    os.write(&three, 1);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = m.triangles(f, k);
      os.write(reinterpret_cast<const char*>(&v), 4);
    }
  }
  return os.str();
}

// Issue 36: a valid PLY file whose coordinates are of an integer type crashed CGAL 5.5's PLY
// reader (SIGSEGV: it dereferences the float property it assumes). Every integer type of the
// PLY specification, ASCII and binary, is refused with the line and the type.
TEST_F(MeshFiles, PlyIntegerCoordinatesAreRefusedNotACrash) {
  for (const char* type : {"char", "uchar", "short", "ushort", "int", "uint", "int8", "uint8",
                           "int16", "uint16", "int32", "uint32"}) {
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
      const std::string name = std::string(type) + "_" + format + ".ply";
      const std::string msg = rejection(write(name, integerPly(type, format)));
      EXPECT_EQ(msg, path(name) +
                         ": cannot read mesh: PLY header line 4: vertex coordinate 'x' "
                         "is of type '" +
                         type +
                         "'; expected float or double (float32, float64): vcontact reads no "
                         "integer coordinates from PLY; export the mesh with floating-point "
                         "coordinates, or as STL or OBJ");
    }
  }
}

// The face index types CGAL 5.5 does not read (it refused the file as "not a valid ply file")
// are named; the 32-bit ones it reads are read.
TEST_F(MeshFiles, PlyFaceIndexTypeIsNamed) {
  for (const char* type : {"uchar", "short", "ushort", "char", "int16"}) {
    const std::string name = std::string("faces_") + type + ".ply";
    const std::string msg = rejection(write(name, integerPly("", "ascii", type, "double")));
    EXPECT_EQ(msg, path(name) +
                       ": cannot read mesh: PLY header line 8: face indices "
                       "'vertex_indices' are of type '" +
                       type + "'; expected int or uint (int32, uint32)");
  }
  for (const char* type : {"int", "uint", "int32", "uint32"}) {
    const std::string name = std::string("faces_") + type + ".ply";
    const MeshReadResult r = readMesh(write(name, integerPly("", "ascii", type, "double")));
    EXPECT_NEAR(geometry::meshMoments(r.mesh).m0, 6.0, 1e-12);  // 1 x 2 x 3, exact in double
  }
}

// Issue 36: "--out X.OBJ" wrote a binary STL that the reader then refused. The extension
// chooses the format in any case; one that names no format written is refused.
TEST_F(MeshFiles, WriteMeshChoosesTheFormatByItsExtensionInAnyCase) {
  for (const char* name : {"a.obj", "b.OBJ", "c.Obj", "d.stl", "e.STL"}) {
    writeMesh(box_, path(name));
    std::ifstream in(path(name), std::ios::binary);
    std::string first;
    std::getline(in, first);
    const bool obj = lowerExtension(name) == ".obj";
    EXPECT_EQ(first.rfind(obj ? "# vcontact mesh" : "vcontact binary STL", 0), 0u) << name;
    EXPECT_NEAR(geometry::meshMoments(readMesh(path(name)).mesh).m0 / boxVolume_, 1.0,
                obj ? 1e-12 : kFloatVolumeTolerance)  // OBJ: 17 digits read back exactly
        << name;
  }
  for (const char* name : {"f.ply", "g"}) {
    const std::string msg = test::inputErrorMessage([&] { writeMesh(box_, path(name)); });
    EXPECT_NE(msg.find("expected a file name ending in .stl (binary STL) or .obj"),
              std::string::npos)
        << msg;
    EXPECT_FALSE(fs::exists(path(name)));
  }
}

// A broken file of a CGAL format is refused by CGAL's reader, not handed on to assimp (which
// aborted the process on a crafted PLY file).
TEST_F(MeshFiles, BrokenCgalFormatIsRefusedWithoutAssimp) {
  for (const char* name : {"cut.off", "cut.ply"}) {
    const std::string msg = rejection(write(name, "OFF\n8 12 0\n0 0 0\n"));
    EXPECT_EQ(msg.rfind(path(name) + ": cannot read mesh: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find("single precision"), std::string::npos) << msg;
  }
}

TEST_F(MeshFiles, FolderIsNotAMeshFile) {
  fs::create_directories(dir_ / "part.stl");
  EXPECT_EQ(rejection(path("part.stl")), path("part.stl") + ": is a folder; expected a mesh file");
}

// io/input_ranges.hpp: the extent in metres within [1e-6, 1e3]; at 1e300 the face checks
// reported "degenerate faces" (issue 20), at 1e-300 a volume of zero.
TEST_F(MeshFiles, ExtentOutsideThePhysicalRangeIsNamed) {
  writeStl(box_, path("box.stl"));
  for (const double scale : {1e300, 1e5, 1e-6}) {
    const std::string msg = rejection(path("box.stl"), scale);
    EXPECT_NE(msg.find("expected the part's extent in [1e-06, 1000] m"), std::string::npos) << msg;
  }
  EXPECT_EQ(rejection(path("box.stl"), 1e4), "");  // 700 m across: the limit allows it
}

}  // namespace
}  // namespace vcontact::io
