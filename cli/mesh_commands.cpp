#include <iostream>
#include <variant>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "io/shape_spec.hpp"

namespace vcontact::cli {
namespace {

struct MeshInfoOptions {
  std::string shape;
  double density = 7900.0;
};

void runMeshInfo(const MeshInfoOptions& o) {
  const io::ParsedShape s = io::parseShape(o.shape, o.shape);
  printWarnings(s.warnings);
  const geometry::Moments M = geometry::solidMoments(s.shape);
  const geometry::MassProperties p = geometry::massProperties(M, o.density);
  std::cout.precision(10);
  std::cout << geometry::describe(s.shape) << "\n";
  if (const auto* m = std::get_if<geometry::Mesh>(&s.shape)) {
    const geometry::Aabb box = geometry::bounds(*m->mesh);
    std::cout << "  vertices       " << m->mesh->vertexCount() << "\n"
              << "  triangles      " << m->mesh->triangleCount() << "\n"
              << "  bounds         (" << box.min.transpose() << ") .. (" << box.max.transpose()
              << ")  m\n"
              << "  checks         closed, consistently oriented, outward, no degenerate faces\n";
  }
  std::cout << "  volume         " << M.m0 << "  m^3\n"
            << "  centroid       (" << p.com.transpose() << ")  m\n"
            << "  density        " << o.density << "  kg/m^3\n"
            << "  mass           " << p.mass << "  kg\n"
            << "  inertia (com)  " << p.inertia.row(0) << "\n"
            << "                 " << p.inertia.row(1) << "\n"
            << "                 " << p.inertia.row(2) << "  kg m^2\n";
}

struct TessellateOptions {
  std::string shape, out;
  int segments = 64;
  int rings = 32;
};

void runTessellate(const TessellateOptions& o) {
  if (o.segments < 3 || o.rings < 2) {
    throw InputError("--segments/--rings", "need at least 3 segments and 2 rings");
  }
  const io::ParsedShape s = io::parseShape(o.shape, o.shape);
  geometry::TriangleMesh mesh;
  if (const auto* sp = std::get_if<geometry::Sphere>(&s.shape)) {
    mesh = geometry::tessellateSphere(sp->radius, o.segments, o.rings);
  } else if (const auto* c = std::get_if<geometry::Cylinder>(&s.shape)) {
    mesh = geometry::tessellateCylinder(c->radius, c->length, o.segments);
  } else if (const auto* b = std::get_if<geometry::Box>(&s.shape)) {
    mesh = geometry::tessellateBox(b->size);
  } else {
    throw InputError(o.shape, "only a sphere, cylinder or box can be tessellated");
  }
  const bool obj = o.out.size() > 4 && o.out.substr(o.out.size() - 4) == ".obj";
  obj ? io::writeObj(mesh, o.out) : io::writeStl(mesh, o.out);
  std::cout << "wrote " << o.out << ": " << mesh.triangleCount() << " triangles, volume "
            << geometry::meshMoments(mesh).m0 << " m^3\n";
}

}  // namespace

void addMeshInfoCommand(CLI::App& app) {
  auto opts = std::make_shared<MeshInfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-info", "Check a shape or mesh file and print its volume, centre of mass and inertia.");
  cmd->add_option("SHAPE", opts->shape, "shape or mesh file")->required();
  cmd->add_option("--density", opts->density, "kg/m^3")->capture_default_str();
  cmd->callback([opts] { runMeshInfo(*opts); });
}

void addTessellateCommand(CLI::App& app) {
  auto opts = std::make_shared<TessellateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tessellate", "Write a triangle mesh of a sphere, cylinder or box (binary STL, or OBJ).");
  cmd->add_option("SHAPE", opts->shape, "sphere:R | cylinder:R,L | box:X,Y,Z")->required();
  cmd->add_option("--out", opts->out, "output file (.stl or .obj)")->required();
  cmd->add_option("--segments", opts->segments, "segments around the axis")->capture_default_str();
  cmd->add_option("--rings", opts->rings, "rings pole to pole (sphere)")->capture_default_str();
  cmd->callback([opts] { runTessellate(*opts); });
}

}  // namespace vcontact::cli
