// The default mesh–mesh query against Simbody's elastic foundation on the same two meshes at the
// same pose (issue 33's reference): simbody/sphere_pair_<n>/<variant>. Built only where CMake
// finds Simbody (libsimbody-dev, scripts/setup.sh); the rest of the tree does not need it.
//
// The pair is volume_bench.cpp's sphere_pair_<n>: two UV spheres of radius 10 mm with about n
// triangles, B at the origin, A turned 0.3 rad about (1, 2, 0) and 19.8 mm off (0.2 mm overlap
// along the line of centres). Variants, each timed per query in one run so that the figures are
// ratios:
//   vcontact         volume::computeContact(a, X_WA, b, X_WB): the default query (`fast`, no
//                    exact depth), all a force evaluation needs (V, p_c, n, J_v, J_s, area);
//   vcontact_depth   the same asked for the exact depth (DepthMode::kDeepest);
//   elastic_foundation  Simbody 3.7's ElasticFoundationForce through its GeneralContactSubsystem
//                    (the faces of each mesh inside the other, then a spring at each such face's
//                    centre displaced to the nearest point of the other mesh): a Free body's pose
//                    set (which invalidates the Position stage) and the system realised to
//                    Dynamics, the contact force read back. The multibody work of one free body
//                    is a few µs of that.
// The law is the same Winkler bed: vcontact's f_n = kv·V; Simbody's f = k·a·x per face, with
// springs on both meshes, so k = kv/2 on each makes its total about kv·V (counter
// `F_over_kvV`, about 1: its springs sample the lens at the faces' centres).

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "geometry/tessellate.hpp"
#include "simbody_pair.hpp"
#include "volume/contact.hpp"

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

constexpr double kRadius = 0.01;  // m
constexpr double kKv = 1e11;      // N/m³, the volumetric stiffness of both laws

/// volume_bench.cpp's sphere of about `triangles` faces (2·s·(r − 1) with r ≈ s/2).
vcontact::geometry::TriangleMesh sphereMesh(int triangles) {
  const int segments = static_cast<int>(std::lround(std::sqrt(double(triangles))));
  const int rings = triangles / (2 * segments) + 1;
  return vcontact::geometry::tessellateSphere(kRadius, segments, rings);
}

/// The pose of A (B at the identity): volume_bench.cpp's registerPair.
Isometry3d poseA() {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  X.translation() = Vector3d(0.0013, -0.0007, 2.0 * kRadius - 0.0002);
  return X;
}

/// A simbody_pair.hpp pair of two copies of `m` at k = kv/2 each.
vcontact::bench::SimbodyPair simbodyPair(const vcontact::geometry::TriangleMesh& m) {
  std::vector<double> vertices;
  std::vector<int> triangles;
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) {
    const Vector3d v = m.vertex(i);
    vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
  }
  for (Eigen::Index f = 0; f < m.triangleCount(); ++f)
    for (int c = 0; c < 3; ++c) triangles.push_back(m.triangles(f, c));
  return vcontact::bench::SimbodyPair(vertices, triangles, 0.5 * kKv);
}

vcontact::geometry::Shape meshShape(vcontact::geometry::TriangleMesh m) {
  return vcontact::geometry::Mesh{
      std::make_shared<const vcontact::geometry::TriangleMesh>(std::move(m)), "sphere"};
}

void registerPair(const char* size, int triangles) {
  const std::string name = std::string("simbody/sphere_pair_") + size + "/";
  for (const bool deepest : {false, true}) {
    benchmark::RegisterBenchmark(
        (name + (deepest ? "vcontact_depth" : "vcontact")).c_str(),
        [=](benchmark::State& s) {
          const vcontact::geometry::Shape shape = meshShape(sphereMesh(triangles));
          const Isometry3d X_WA = poseA(), X_WB = Isometry3d::Identity();
          vcontact::volume::QueryOptions options;
          if (deepest) options.depth = vcontact::volume::DepthMode::kDeepest;
          vcontact::volume::computeContact(shape, X_WA, shape, X_WB);  // the caches (trees)
          vcontact::volume::ContactVolume cv;
          for (auto _ : s) {
            cv = vcontact::volume::computeContact(shape, X_WA, shape, X_WB, options).aggregate;
            benchmark::DoNotOptimize(cv);
          }
          s.counters["V"] = cv.volume;
          s.counters["F"] = kKv * cv.volume;  // f_n = kv·V
          s.counters["depth"] = cv.depth;
          s.counters["triangles"] =
              double(std::get<vcontact::geometry::Mesh>(shape).mesh->triangleCount());
        })
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark((name + "elastic_foundation").c_str(), [=](benchmark::State& s) {
    const vcontact::geometry::TriangleMesh mesh = sphereMesh(triangles);
    vcontact::bench::SimbodyPair pair = simbodyPair(mesh);
    const Isometry3d X = poseA();
    std::array<double, 9> R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R[static_cast<std::size_t>(3 * r + c)] = X.linear()(r, c);
    const std::array<double, 3> p{X.translation().x(), X.translation().y(), X.translation().z()};
    std::array<double, 3> f = pair.force(R, p);  // the first realisation builds the trees
    for (auto _ : s) {
      f = pair.force(R, p);
      benchmark::DoNotOptimize(f);
    }
    const double F = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    const vcontact::geometry::Shape shape = meshShape(mesh);
    const double V = vcontact::volume::computeContact(shape, poseA(), shape, Isometry3d::Identity())
                         .aggregate.volume;
    s.counters["F"] = F;
    s.counters["F_over_kvV"] = F / (kKv * V);
    s.counters["triangles"] = double(mesh.triangleCount());
  })->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) {
  registerPair("1k", 1000);
  registerPair("10k", 10000);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
