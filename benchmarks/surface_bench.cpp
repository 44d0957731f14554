// surface/<case>/<path>: a query on the recovered surface (docs/SURFACES.md) against the
// polyhedral clip of the same mesh on the same pose, so their ratio is the cost of the true
// surface. Cases: a 10,000-triangle sphere and a 512-triangle cylinder on their side, whole
// bodies of one closed form; the same sphere with a free-form patch on top, so that each
// query scans the vertices for the faces that reach the plane; and the rolling ball of
// assets/scenarios/ball_roll_recovered.json.

#include <benchmark/benchmark.h>

#include <functional>
#include <memory>
#include <string>

#include "geometry/bvh.hpp"
#include "geometry/surface_recognition.hpp"
#include "geometry/tessellate.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/recovered_surface.hpp"

namespace {

using Eigen::Isometry3d;
using vcontact::geometry::TriangleMesh;

constexpr double kRadius = 0.01;      // m
constexpr double kDepthRatio = 1e-3;  // d/R: a metal contact's depth

struct Case {
  TriangleMesh mesh;
  std::unique_ptr<vcontact::geometry::MeshBvh> bvh;
  vcontact::geometry::SurfaceRecognition surfaces;
  std::unique_ptr<vcontact::volume::RecoveredBody> body;
  Isometry3d X_WM = Isometry3d::Identity();
};

// The mesh prepared once: its tree, its surfaces, the recovered body; the sphere's (or the
// side-lying cylinder's) lowest point at depth d = depth_ratio R.
std::shared_ptr<Case> prepare(TriangleMesh mesh, const Isometry3d& rotation,
                              double depth_ratio = kDepthRatio) {
  auto c = std::make_shared<Case>();
  c->mesh = std::move(mesh);
  c->bvh = std::make_unique<vcontact::geometry::MeshBvh>(c->mesh);
  c->surfaces = vcontact::geometry::recogniseSurfaces(c->mesh);
  c->body = std::make_unique<vcontact::volume::RecoveredBody>(c->mesh, c->surfaces);
  c->X_WM = rotation;
  c->X_WM.translation().z() = kRadius * (1.0 - depth_ratio);
  return c;
}

// The sphere with its top cap's vertices pushed out by 1e-4 R: free-form faces away from
// the contact, so the body is not one closed form.
TriangleMesh bumpySphere() {
  TriangleMesh m = vcontact::geometry::tessellateSphere(kRadius, 100, 50);
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i)
    if (m.vertices(i, 2) > 0.9 * kRadius) m.vertices.row(i) *= 1.0 + 1e-4;
  return m;
}

// Each case is prepared on its first run (recognition takes a second), not at start-up.
void registerCase(const std::string& name, std::function<std::shared_ptr<Case>()> make) {
  const auto once = [make, c = std::make_shared<std::shared_ptr<Case>>()] {
    if (!*c) *c = make();
    return *c;
  };
  const Isometry3d H = Isometry3d::Identity();
  benchmark::RegisterBenchmark(("surface/" + name + "/mesh").c_str(), [=](benchmark::State& s) {
    const std::shared_ptr<Case> c = once();
    vcontact::volume::ContactVolume cv;
    for (auto _ : s) {
      cv = vcontact::volume::meshHalfspaceContact(*c->bvh, c->X_WM, H);
      benchmark::DoNotOptimize(cv);
    }
    s.counters["V"] = cv.volume;
  });
  benchmark::RegisterBenchmark(("surface/" + name + "/recovered").c_str(),
                               [=](benchmark::State& s) {
                                 const std::shared_ptr<Case> c = once();
                                 vcontact::volume::RecoveredContact r;
                                 for (auto _ : s) {
                                   r = c->body->halfspaceContact(c->X_WM, H);
                                   benchmark::DoNotOptimize(r);
                                 }
                                 s.counters["V"] = r.cv.volume;
                                 s.SetLabel(r.representation);
                               });
}

[[maybe_unused]] const bool kRegistered = [] {
  registerCase("sphere10k", [] {
    return prepare(vcontact::geometry::tessellateSphere(kRadius, 100, 50), Isometry3d::Identity());
  });
  registerCase("cylinder512", [] {
    Isometry3d side = Isometry3d::Identity();
    side.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return prepare(vcontact::geometry::tessellateCylinder(kRadius, 0.03, 128), side);
  });
  registerCase("sphere10k_freeform_top",
               [] { return prepare(bumpySphere(), Isometry3d::Identity()); });
  // The ball of ball_roll_recovered.json (2,000 triangles: 40 segments, 26 rings) at its
  // static penetration, d/R = 1.41e-4, turned 0.3 rad as it rolls: the polyhedron touches at
  // a few faces near a vertex, the recovered surface is the sphere's closed form.
  registerCase("ball2k_rolling", [] {
    Isometry3d rolled = Isometry3d::Identity();
    rolled.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return prepare(vcontact::geometry::tessellateSphere(kRadius, 40, 26), rolled, 1.41378e-4);
  });
  return true;
}();

}  // namespace
