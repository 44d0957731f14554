// Surface recognition of capsules (a cylinder between two hemispheres that meet it without a
// crease), as a CAD exporter writes them at 24 to 256 segments: each must come back as two
// spheres and one cylinder, every face taken. Before the fixes in surface_recognition.cpp a
// capsule's cylinder was left free-form at every segment count tried: its vertex samples
// were filed under the hemispheres' faces (freeSamples), a cone of tiny angle proposed for it
// failed to polish (cylinderAlong), and at coarse counts no candidate held both its rims
// (bandSurface).

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "geometry/surface_recognition.hpp"

namespace vcontact::geometry {
namespace {

// A capsule of radius r and cylinder length L along z from z = 0, n segments around and
// n / 4 rings in each quarter of its profile, turned and moved off the axes.
TriangleMesh capsule(double r, double L, int n) {
  const int m = n / 4;
  std::vector<std::pair<double, double>> profile{{0.0, 0.0}};  // (radius, height)
  for (int k = 1; k <= m; ++k)
    profile.emplace_back(r * std::sin(M_PI / 2 * k / m), r * (1.0 - std::cos(M_PI / 2 * k / m)));
  for (int k = 0; k < m; ++k)
    profile.emplace_back(r * std::cos(M_PI / 2 * k / m), r + L + r * std::sin(M_PI / 2 * k / m));
  profile.emplace_back(0.0, 2.0 * r + L);
  const int rings = static_cast<int>(profile.size()) - 2;  // between the two poles
  TriangleMesh mesh;
  mesh.vertices.resize(rings * n + 2, 3);
  const Eigen::Isometry3d X = Eigen::Translation3d(0.01, -0.02, 0.005) *
                              Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  const auto put = [&](int row, double x, double y, double z) {
    mesh.vertices.row(row) = (X * Eigen::Vector3d(x, y, z)).transpose();
  };
  put(0, 0.0, 0.0, profile.front().second);
  put(rings * n + 1, 0.0, 0.0, profile.back().second);
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * M_PI * i / n, rho = profile[k + 1].first;
      put(1 + k * n + i, rho * std::cos(t), rho * std::sin(t), profile[k + 1].second);
    }
  const auto ring = [&](int k, int i) { return 1 + k * n + i % n; };
  mesh.triangles.resize(2 * n * rings, 3);
  int f = 0;
  for (int i = 0; i < n; ++i) {
    mesh.triangles.row(f++) << 0, ring(0, i + 1), ring(0, i);  // the fans face the poles' way
    mesh.triangles.row(f++) << rings * n + 1, ring(rings - 1, i), ring(rings - 1, i + 1);
    for (int k = 0; k + 1 < rings; ++k) {
      mesh.triangles.row(f++) << ring(k, i), ring(k, i + 1), ring(k + 1, i + 1);
      mesh.triangles.row(f++) << ring(k, i), ring(k + 1, i + 1), ring(k + 1, i);
    }
  }
  return mesh;
}

class Capsule : public ::testing::TestWithParam<int> {};

TEST_P(Capsule, IsTwoSpheresAndACylinder) {
  const double r = 0.007, L = 0.018;
  const int n = GetParam();
  const TriangleMesh mesh = capsule(r, L, n);
  const SurfaceRecognition rec = recogniseSurfaces(mesh);
  std::map<SurfaceKind, int> kinds;
  for (const RecognisedSurface& s : rec.surfaces) ++kinds[s.kind];
  EXPECT_EQ(kinds,
            (std::map<SurfaceKind, int>{{SurfaceKind::kSphere, 2}, {SurfaceKind::kCylinder, 1}}));
  EXPECT_EQ(rec.free_form_faces, 0);
  for (const RecognisedSurface& s : rec.surfaces) {
    // Every vertex lies on its surface to rounding; the fits return r to rounding times their
    // conditioning (1e-9 of the part, as in surface_recognition_test.cpp).
    EXPECT_NEAR(s.radius, r, 1e-9 * (L + 2 * r));
    EXPECT_TRUE(s.convex);
    if (s.kind == SurfaceKind::kCylinder)
      EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(2 * n));
  }
}

INSTANTIATE_TEST_SUITE_P(SegmentCounts, Capsule, ::testing::Values(24, 48, 96, 256));

}  // namespace
}  // namespace vcontact::geometry
