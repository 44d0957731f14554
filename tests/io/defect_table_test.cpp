// The table of issue 16: meshes with the defects third-party CAD files come with, made by the
// generators of tests/geometry/defect_meshes.hpp, written to files and read as a user would,
// without and with the repair. Each row asserts what the engine says and does, and the test
// prints the table (name | without repair | with repair) in Markdown.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "geometry/defect_meshes.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "io/mesh_io.hpp"

namespace vcontact::io {
namespace {

namespace fs = std::filesystem;
using geometry::TriangleMesh;
using namespace vcontact::test;

// A repair keeps the vertices of the solid meant (a weld keeps the first copy; a filled
// triangle is the one removed), so its volume differs by summation order only.
constexpr double kVolumeTolerance = 1e-13;

struct DefectCase {
  std::string name;
  TriangleMesh mesh;
  double meantVolume = 0.0;  ///< m^3, of the solid the file means (after the scale)
  std::string saysWithout;   ///< part of the error or warning without the repair
  std::string saysWith;      ///< part of the error or first change with the repair
  bool acceptedWith = true;  ///< the repaired mesh passes the checks
  bool fillHoles = false;
  double scale = 1.0;
};

double volume(const TriangleMesh& m) { return geometry::meshMoments(m).m0; }

std::vector<DefectCase> cases() {
  const TriangleMesh box = cadBox();
  const double boxV = volume(box);
  const TriangleMesh sphere = geometry::tessellateSphere(0.02, 24, 12);
  const TriangleMesh big = geometry::tessellateBox({0.1, 0.1, 0.1});
  TriangleMesh mm = box;
  mm.vertices *= 1000.0;
  return {
      {"seam of one vertex, gap 1e-10 m", withSeam(box, 3, 1e-10), boxV,
       "4 boundary edges, mesh is not closed", "welded 1 vertex"},
      {"meridian seam of a sphere, gap 2e-9 m", sphereWithMeridianSeam(2e-9), volume(sphere),
       "boundary edges, mesh is not closed", "welded 11 vertices"},
      {"2 zero-area faces, every edge shared twice", withZeroAreaFaces(box, 2), boxV,
       "2 degenerate faces (zero area)", "dropped 2 zero-area faces"},
      {"2 faces reversed", withFacesReversed(box, {2, 7}), boxV, "orientation is inconsistent",
       "reversed 2 faces to orient the faces consistently"},
      {"every face reversed (inside out)", inverted(box), boxV, "flipped all 12 faces",
       "reversed 12 faces of outer shells that faced inward"},
      {"duplicate face", withDuplicateFace(box, 4), boxV, "shared by more than two faces",
       "dropped 1 duplicate face"},
      {"small hole: one facet missing", withoutFaces(sphere, {100}), volume(sphere),
       "3 boundary edges", "filled 1 hole with 1 triangle", true, true},
      {"large hole: one side missing", withoutFaces(box, {0, 1}), boxV, "4 boundary edges",
       "4 boundary edges", false, true},
      {"seam, reversed face and duplicate face together",
       withDuplicateFace(withFacesReversed(withSeam(box, 3, 1e-10), {9}), 0), boxV,
       "boundary edges", "welded 1 vertex"},
      {"two overlapping shells", joined(box, translated(box, {0.01, 0, 0})), 0.0,
       "closed shells intersect or touch each other", "closed shells intersect or touch each other",
       false},
      {"shell inside another, same orientation", joined(big, box), 0.0,
       "lies inside another with the same orientation",
       "lies inside another with the same orientation", false},
      {"cavity: inner shell facing inward", joined(big, inverted(box)), volume(big) - boxV, "", ""},
      {"two disjoint shells", joined(box, translated(box, {0.1, 0, 0})), 2 * boxV, "", ""},
      {"millimetre file read as metres", mm, boxV * 1e9, "70 m across, implausible", "70 m across"},
      {"millimetre file read with @mm", mm, boxV, "", "", true, false, 0.001},
  };
}

struct Outcome {
  bool accepted = false;
  std::string said;  ///< the error, or the first change or warning
  double volume = 0.0;
};

Outcome readAs(const std::string& file, const DefectCase& c, bool repair) {
  MeshReadOptions options;
  options.repair = repair;
  options.repairOptions.fillHoles = c.fillHoles;
  try {
    const MeshReadResult r = readMesh(file, c.scale, options);
    const std::string said = r.warnings.empty() ? "" : r.warnings[0].substr(file.size() + 2);
    return {true, said, volume(r.mesh)};
  } catch (const InputError& e) {
    return {false, e.message(), 0.0};
  }
}

std::string describe(const Outcome& o, double meant) {
  if (!o.accepted) return "rejected: " + o.said.substr(0, o.said.find(';'));
  std::ostringstream os;
  os.precision(2);
  os << "accepted, V/V_meant - 1 = " << (o.volume / meant - 1.0);
  if (!o.said.empty()) os << "; " << o.said.substr(0, o.said.find(';'));
  return os.str();
}

TEST(DefectTable, EachDefectIsNamedAndRepairedOrRefused) {
  const fs::path dir = fs::temp_directory_path() / ("vcontact_defects_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ostringstream table;
  table << "| mesh | without repair | with repair |\n|---|---|---|\n";
  int row = 0;
  for (const DefectCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const std::string file = (dir / ("case" + std::to_string(row++) + ".obj")).string();
    writeObj(c.mesh, file);
    const Outcome without = readAs(file, c, false);
    const Outcome with = readAs(file, c, true);
    EXPECT_NE(without.said.find(c.saysWithout), std::string::npos) << without.said;
    EXPECT_NE(with.said.find(c.saysWith), std::string::npos) << with.said;
    EXPECT_EQ(with.accepted, c.acceptedWith) << with.said;
    if (with.accepted && c.meantVolume > 0.0) {
      EXPECT_NEAR(with.volume / c.meantVolume, 1.0, kVolumeTolerance);
    }
    table << "| " << c.name << " | " << describe(without, c.meantVolume) << " | "
          << describe(with, c.meantVolume) << " |\n";
  }
  fs::remove_all(dir);
  std::cout << table.str();
}

}  // namespace
}  // namespace vcontact::io
