// surface/<case>/<path>: a query on the recovered surface (docs/SURFACES.md) against the
// polyhedral clip of the same mesh on the same pose, so their ratio is the cost of the true
// surface. Cases: a 10,000-triangle sphere and a 512-triangle cylinder on their side, whole
// bodies of one closed form; the same sphere with a free-form patch on top, so that each
// query scans the vertices for the faces that reach the plane; and the rolling ball of
// assets/scenarios/ball_roll_recovered.json; a chamfered pin on its side on a plate, a solid
// of revolution (volume/recovered/revolution_body.hpp). Two meshes: the pin pressed into the
// bundled block's bore (surface/pin_in_bore: the fast method on the polyhedra against the
// recovered pair, by slices across the pin's axis, volume/recovered/bore_pair.hpp), and the tilted
// pin's slices alone on the true shapes (surface/pin_in_bore_tilted_slices: closed-form
// slices against polar ones, BoreSection::polar_slices).

#include <benchmark/benchmark.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "geometry/bvh.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/surface_recognition.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/recovered/pin_in_bore.hpp"
#include "volume/recovered/recovered_surface.hpp"
#include "volume/recovered/refinement.hpp"

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
                              double depth_ratio = kDepthRatio, double radius = kRadius) {
  auto c = std::make_shared<Case>();
  c->mesh = std::move(mesh);
  c->bvh = std::make_unique<vcontact::geometry::MeshBvh>(c->mesh);
  c->surfaces = vcontact::geometry::recogniseSurfaces(c->mesh);
  c->body = std::make_unique<vcontact::volume::RecoveredBody>(c->mesh, c->surfaces);
  c->X_WM = rotation;
  c->X_WM.translation().z() = radius * (1.0 - depth_ratio);
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
                                 s.SetLabel(representationName(r.representation));
                               });
}

// A pin (r 5 mm, 64 segments, chamfered) in the bundled block's 5.1 mm bore, pressed sideways
// by d/r = 1e-3: the fast method on the two polyhedra against the recovered pair (the pin's
// profile in the bore's section by slices; before them, the two meshes refined at level 50);
// `tilt` turns the pin about its middle across the pressing direction (rad).
struct PinInBore {
  TriangleMesh pin, block;
  vcontact::geometry::SurfaceRecognition recPin, recBlock;
  std::unique_ptr<vcontact::volume::RecoveredBody> a, b;
  std::unique_ptr<vcontact::geometry::MeshBvh> ta, tb;
  std::unique_ptr<vcontact::geometry::MeshTopology> topoA, topoB;
  Isometry3d X_BA = Isometry3d::Identity();
};

std::shared_ptr<PinInBore> makePinInBore(double tilt) {
  auto c = std::make_shared<PinInBore>();
  const double r = 0.005, e = 0.0051 - r + 1e-3 * r;
  c->pin = vcontact::geometry::tessellateRevolution(
      {{r - 5e-4, 0.0}, {r, 5e-4}, {r, 0.0295}, {r - 5e-4, 0.03}}, 64);
  const std::filesystem::path assets =
      std::filesystem::path(__FILE__).parent_path().parent_path() / "assets";
  c->block = vcontact::io::readMesh((assets / "scenarios/meshes/block_hole_d10.stl").string()).mesh;
  c->recPin = vcontact::geometry::recogniseSurfaces(c->pin);
  c->recBlock = vcontact::geometry::recogniseSurfaces(c->block);
  c->a = std::make_unique<vcontact::volume::RecoveredBody>(c->pin, c->recPin);
  c->b = std::make_unique<vcontact::volume::RecoveredBody>(c->block, c->recBlock);
  c->ta = std::make_unique<vcontact::geometry::MeshBvh>(c->pin);
  c->tb = std::make_unique<vcontact::geometry::MeshBvh>(c->block);
  c->topoA = std::make_unique<vcontact::geometry::MeshTopology>(c->pin);
  c->topoB = std::make_unique<vcontact::geometry::MeshTopology>(c->block);
  c->X_BA.translation() = Eigen::Vector3d(e * std::cos(0.3), e * std::sin(0.3), -0.025);
  if (tilt != 0.0) {  // tilted about the pin's middle, which stays where it was
    const Eigen::Vector3d side(-std::sin(0.3), std::cos(0.3), 0.0), middle(0, 0, 0.015);
    c->X_BA.linear() = Eigen::AngleAxisd(tilt, side).toRotationMatrix();
    c->X_BA.translation() += middle - c->X_BA.linear() * middle;
  }
  return c;
}

void registerPinInBore(const std::string& name, double tilt) {
  const auto once = [tilt, c = std::make_shared<std::shared_ptr<PinInBore>>()] {
    if (!*c) *c = makePinInBore(tilt);
    return *c;
  };
  const Isometry3d I = Isometry3d::Identity();
  benchmark::RegisterBenchmark(("surface/" + name + "/mesh").c_str(), [=](benchmark::State& s) {
    const auto c = once();
    vcontact::volume::ContactPatches p;
    for (auto _ : s) {
      p = vcontact::volume::meshMeshContact(*c->ta, *c->topoA, c->X_BA, *c->tb, *c->topoB, I,
                                            nullptr, false);
      benchmark::DoNotOptimize(p);
    }
    s.counters["V"] = p.aggregate.volume;
  });
  benchmark::RegisterBenchmark(
      ("surface/" + name + "/recovered").c_str(), [=](benchmark::State& s) {
        const auto c = once();
        vcontact::volume::RecoveredContact r;
        for (auto _ : s) {
          r = vcontact::volume::recoveredMeshMeshContact(*c->a, c->X_BA, *c->b, I);
          benchmark::DoNotOptimize(r);
        }
        s.counters["V"] = r.cv.volume;
        s.counters["level"] = r.level;
        s.SetLabel(representationName(r.representation));
      });
}

// The tilted pin of registerPinInBore in its bore by slices, on the true shapes (the block's
// bore of 5.1 mm along its z axis, its faces z = 0 and −20 mm) in the pin's frame R: the
// slices' cost without recognition, closed forms outside the faces' bands or rays throughout.
void registerTiltedSlices(double tilt) {
  const double r = 0.005, e = 0.0051 - r + 1e-3 * r, c = 5e-4;
  const vcontact::volume::RevolutionProfile pin = {
      {vcontact::volume::ProfilePiece::Kind::kLinear, 0.0, c, r - c, r},
      {vcontact::volume::ProfilePiece::Kind::kConstant, c, 0.03 - c, r, r},
      {vcontact::volume::ProfilePiece::Kind::kLinear, 0.03 - c, 0.03, r, r - c}};
  Isometry3d X_BA = Isometry3d::Identity();  // as makePinInBore
  X_BA.translation() = Eigen::Vector3d(e * std::cos(0.3), e * std::sin(0.3), -0.025);
  const Eigen::Vector3d side(-std::sin(0.3), std::cos(0.3), 0.0), middle(0, 0, 0.015);
  X_BA.linear() = Eigen::AngleAxisd(tilt, side).toRotationMatrix();
  X_BA.translation() += middle - X_BA.linear() * middle;
  const Isometry3d X_AB = X_BA.inverse();
  vcontact::volume::BoreSection bore;
  bore.point_R = X_AB * Eigen::Vector3d::Zero();
  bore.axis_R = X_AB.linear() * Eigen::Vector3d::UnitZ();
  bore.radius = 0.0051;
  const std::vector<vcontact::volume::BorePlane> planes = {
      {bore.axis_R, bore.point_R}, {-bore.axis_R, X_AB * Eigen::Vector3d(0.0, 0.0, -0.02)}};
  for (const bool polar : {false, true}) {
    const std::string name = polar ? "polar" : "closed";
    benchmark::RegisterBenchmark(
        ("surface/pin_in_bore_tilted_slices/" + name).c_str(), [=](benchmark::State& s) {
          vcontact::volume::BoreSection b = bore;
          b.polar_slices = polar;
          vcontact::volume::BoreContact got;
          for (auto _ : s) {
            got = vcontact::volume::revolutionInTiltedBore(pin, X_BA, b, planes);
            benchmark::DoNotOptimize(got);
          }
          s.counters["V"] = got.cv.volume;
        });
  }
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
  // The pin of the error table (r 5 mm, 30 mm, 0.5 mm 45° chamfers, 64 segments) on its side
  // with a vertex row down: the cylinder and both chamfer cones reach the plate; recovered,
  // a solid of revolution by slices (volume/analytic/revolution_on_plane.hpp). The table's radius;
  // a pin of r = 10 mm has two-ring chamfers that fit spheres too, told from them by their edges
  // (docs/SURFACES.md, "Sphere or cone: the edges decide").
  registerCase("chamfered_pin_side", [] {
    const double r = 0.005;
    Isometry3d side = Isometry3d::Identity();
    side.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return prepare(vcontact::geometry::tessellateRevolution(
                       {{r - 5e-4, 0.0}, {r, 5e-4}, {r, 0.0295}, {r - 5e-4, 0.03}}, 64),
                   side, kDepthRatio, r);
  });
  registerPinInBore("pin_in_bore", 0.0);
  // the same pin tilted by 0.2 mrad about its middle (in the bore's wall by 8 µm at the
  // block's top face and 2 µm at its bottom): an ellipse in each slice, polar slices
  registerPinInBore("pin_in_bore_tilted", 2e-4);
  registerTiltedSlices(2e-4);
  return true;
}();

}  // namespace
