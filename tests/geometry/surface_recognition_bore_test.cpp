// Surface recognition on a square block with a round through-bore, at the bore's segment counts
// that made CGAL's RANSAC crash before its parameter-space clustering was guarded
// (geometry/surface_detection.cpp, GuardedShape): a cylinder or cone candidate with a sample on
// its axis gave a NaN parameter range, and the clustering grid of that range wrote through a null
// pointer. The block was made for none of the detector's settings. Written by a script with
// another vertex order, 192, 256 and 768 were the three of 55 segment counts from 16 to 2048
// that crashed `vcontact surfaces`; this construction crashes at 192 and 768.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "geometry/surface_recognition.hpp"

namespace vcontact::geometry {
namespace {

// A block 2a x 2a x h (top face at z = 0) with a through-bore of radius R along z, n
// segments (a multiple of 8, so that the block's corners lie on segment directions): each
// segment is a quad of the top and of the bottom face from the bore's rim out to the square,
// a quad of the bore's wall and one of the outer side.
TriangleMesh boredBlock(double a, double h, double R, int n) {
  TriangleMesh m;
  m.vertices.resize(4 * n, 3);
  const auto rim = [&](int i) { return i % n; };
  const auto out = [&](int i) { return n + i % n; };
  const auto rimLow = [&](int i) { return 2 * n + i % n; };
  const auto outLow = [&](int i) { return 3 * n + i % n; };
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n, c = std::cos(t), s = std::sin(t);
    const double to_square = a / std::max(std::abs(c), std::abs(s));
    for (const double z : {0.0, -h}) {
      const int level = z == 0.0 ? 0 : 2 * n;
      m.vertices.row(level + i) << R * c, R * s, z;
      m.vertices.row(level + n + i) << to_square * c, to_square * s, z;
    }
  }
  m.triangles.resize(8 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int j = i + 1, f = 8 * i;
    m.triangles.row(f + 0) << rim(i), out(i), out(j);  // top, facing +z
    m.triangles.row(f + 1) << rim(i), out(j), rim(j);
    m.triangles.row(f + 2) << rimLow(i), outLow(j), outLow(i);  // bottom, facing −z
    m.triangles.row(f + 3) << rimLow(i), rimLow(j), outLow(j);
    m.triangles.row(f + 4) << out(i), outLow(i), outLow(j);  // outer side
    m.triangles.row(f + 5) << out(i), outLow(j), out(j);
    m.triangles.row(f + 6) << rim(i), rimLow(j), rimLow(i);  // bore wall, facing its axis
    m.triangles.row(f + 7) << rim(i), rim(j), rimLow(j);
  }
  return m;
}

class BoredBlock : public ::testing::TestWithParam<int> {};

TEST_P(BoredBlock, IsSixPlanesAndAConcaveCylinder) {
  const double a = 0.02, h = 0.02, R = 0.0051;
  const int n = GetParam();
  const SurfaceRecognition r = recogniseSurfaces(boredBlock(a, h, R, n));
  std::map<SurfaceKind, int> kinds;
  for (const RecognisedSurface& s : r.surfaces) ++kinds[s.kind];
  EXPECT_EQ(kinds,
            (std::map<SurfaceKind, int>{{SurfaceKind::kPlane, 6}, {SurfaceKind::kCylinder, 1}}));
  EXPECT_EQ(r.free_form_faces, 0);
  for (const RecognisedSurface& s : r.surfaces) {
    if (s.kind != SurfaceKind::kCylinder) continue;
    // The rims' vertices lie on the circle to rounding; the fit returns R to rounding times
    // its conditioning, 1e-9 of the part as in surface_recognition_test.cpp.
    EXPECT_NEAR(s.radius, R, 1e-9 * a);
    EXPECT_FALSE(s.convex);  // the bore's wall faces its axis
    EXPECT_NEAR(std::abs(s.axis.z()), 1.0, 1e-9);
    EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(2 * n));
  }
}

INSTANTIATE_TEST_SUITE_P(SegmentCountsThatCrashed, BoredBlock, ::testing::Values(192, 256, 768));

}  // namespace
}  // namespace vcontact::geometry
