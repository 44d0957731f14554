// mesh_check/<file>/<phase>: the cost of looking for a single shell's self-intersection
// (geometry/self_intersection.hpp, issue 36) against reading the same file with every check
// (io::readMesh, the self-intersection test included), on the biggest bundled meshes. The
// figure to read is the ratio self_intersection / read: the test is to stay a small fraction.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "geometry/self_intersection.hpp"
#include "io/mesh_io.hpp"

namespace {

// The meshes live next to this source tree's benchmarks/ folder (as simulation_bench.cpp finds
// its scenarios).
const std::string kMeshes =
    (std::filesystem::path(__FILE__).parent_path().parent_path() / "assets/scenarios/meshes/")
        .string();

void BM_ReadMesh(benchmark::State& state, const std::string& file) {
  for (auto _ : state) {
    const vcontact::io::MeshReadResult r = vcontact::io::readMesh(kMeshes + file);
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  state.counters["triangles"] =
      static_cast<double>(vcontact::io::readMesh(kMeshes + file).mesh.triangleCount());
}

void BM_SelfIntersection(benchmark::State& state, const std::string& file) {
  const vcontact::geometry::TriangleMesh mesh = vcontact::io::readMesh(kMeshes + file).mesh;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vcontact::geometry::findSelfIntersection(mesh));
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangleCount());
}

BENCHMARK_CAPTURE(BM_ReadMesh, fixture_10k / read, std::string("fixture_10k.stl"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SelfIntersection, fixture_10k / self_intersection,
                  std::string("fixture_10k.stl"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMesh, tray_10k / read, std::string("tray_10k.stl"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SelfIntersection, tray_10k / self_intersection, std::string("tray_10k.stl"))
    ->Unit(benchmark::kMillisecond);

}  // namespace
