// columns/<case>: the columns method (volume/columns/columns.hpp) on the cases where its line
// casting was measured against Embree's (benchmarks/README.md, "Columns line casting"), with the
// volume found (counter V, m³) beside the time; the trees are built once, outside the timed loop.
//
// Cases, the bundled punch (assets/scenarios/meshes/punch.stl: R = 10 mm, L = 8 mm, 64-sided
// prism, 256 triangles) 0.6 µm into its support (the static penetration of
// punch_lumped_vs_distributed), tilted 1e-5 rad and turned 0.3 rad about its axis:
//   punch_halfspace_fixed64: on a half-space, ColumnOptions::fixed(64), the grid of
//     distributed friction at every right-hand side;
//   punch_plate_fixed64: on a tessellated plate (two meshes), the same grid;
//   punch_halfspace_refined, punch_plate_refined: the refined default (to 1e-3);
//   sphere10k_pair_refined: two 10k-triangle spheres, 0.2 mm overlap, the refined default;
//   sphere{10k,100k}_halfspace_deep_fixed64: a sphere of R = 10 mm 3 mm into a half-space,
//     fixed(64): many triangles a line, where a ray's logarithmic traversal could pay.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <functional>
#include <string>

#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "volume/columns/columns.hpp"

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using vcontact::geometry::MeshBvh;
using vcontact::volume::ColumnBody;
using vcontact::volume::ColumnOptions;

const MeshBvh& punch() {
  static const MeshBvh s(
      vcontact::io::readMesh((std::filesystem::path(__FILE__).parent_path().parent_path() /
                              "assets/scenarios/meshes/punch.stl")
                                 .string())
          .mesh);
  return s;
}

const MeshBvh& plate() {
  static const MeshBvh s(vcontact::geometry::tessellateBox(Vector3d(0.06, 0.05, 0.01)));
  return s;
}

const MeshBvh& sphere10k() {
  static const MeshBvh s(vcontact::geometry::tessellateSphere(0.01, 100, 51));
  return s;
}

const MeshBvh& sphere100k() {
  static const MeshBvh s(vcontact::geometry::tessellateSphere(0.01, 316, 159));
  return s;
}

constexpr double kPenetration = 6e-7;  // m, punch_lumped_vs_distributed at rest

/// The punch face down (its face at z_M = −4 mm) kPenetration below z = 0.
Isometry3d punchPose() {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(0.3, Vector3d::UnitZ()) *
                Eigen::AngleAxisd(1e-5, Vector3d(1, 2, 0).normalized()))
                   .toRotationMatrix();
  X.translation() = Vector3d(0.0013, -0.0007, 0.004 - kPenetration);
  return X;
}

struct Case {
  const MeshBvh* a;
  Isometry3d X_WA;
  const MeshBvh* b;  ///< null: the half-space z ≤ 0
  Isometry3d X_WB;
  ColumnOptions options;
};

/// Makes the case on first use (the meshes are read and built then, not at static
/// initialisation).
using CaseMaker = std::function<Case()>;

void run(benchmark::State& state, const CaseMaker& make) {
  const Case c = make();
  const ColumnBody a{c.a, c.X_WA};
  const ColumnBody b{c.b, c.X_WB};
  vcontact::volume::ContactVolume cv;
  for (auto _ : state) {
    cv = vcontact::volume::columnsContact(a, b, c.options);
    benchmark::DoNotOptimize(cv);
  }
  state.counters["V"] = cv.volume;
}

void registerCase(const std::string& name, const CaseMaker& c) {
  benchmark::RegisterBenchmark(("columns/" + name).c_str(), [=](benchmark::State& s) {
    run(s, c);
  })->Unit(benchmark::kMicrosecond);
}

[[maybe_unused]] const bool kRegistered = [] {
  const Isometry3d X_WPlate(Eigen::Translation3d(0.0, 0.0, -0.005));  // top face at z = 0
  const ColumnOptions fixed = ColumnOptions::fixed(64), refined;
  auto onPlate = [=](const ColumnOptions& o) {
    return [=] { return Case{&punch(), punchPose(), &plate(), X_WPlate, o}; };
  };
  auto onHalfspace = [](const ColumnOptions& o) {
    return [=] { return Case{&punch(), punchPose(), nullptr, Isometry3d::Identity(), o}; };
  };
  registerCase("punch_halfspace_fixed64", onHalfspace(fixed));
  registerCase("punch_plate_fixed64", onPlate(fixed));
  registerCase("punch_halfspace_refined", onHalfspace(refined));
  registerCase("punch_plate_refined", onPlate(refined));
  for (const auto& [name, sphere] :
       {std::pair{"sphere10k", &sphere10k}, {"sphere100k", &sphere100k}}) {
    registerCase(std::string(name) + "_halfspace_deep_fixed64", [=] {
      Isometry3d X_WS = Isometry3d::Identity();
      X_WS.translation() = Vector3d(0.0013, -0.0007, 0.01 - 0.003);
      return Case{&sphere(), X_WS, nullptr, Isometry3d::Identity(), fixed};
    });
  }
  registerCase("sphere10k_pair_refined", [=] {
    Isometry3d X_WA = Isometry3d::Identity();
    X_WA.linear() = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 0).normalized()).toRotationMatrix();
    X_WA.translation() = Vector3d(0.0013, -0.0007, 0.02 - 0.0002);
    return Case{&sphere10k(), X_WA, &sphere10k(), Isometry3d::Identity(), refined};
  });
  return true;
}();

}  // namespace
