// Faceting error of tessellated bodies against the closed forms of MODEL.md §5, written as
// CSV: the error is the mesh's, not the clip's (the clip is exact for the polyhedron); beside
// it, the error of the same mesh on its recovered surface (docs/SURFACES.md).
//   usage: vcontact_error_table OUTPUT_DIR
// writes OUTPUT_DIR/faceting_error_sphere.csv and OUTPUT_DIR/faceting_error_cylinder.csv,
// faceting_error_chamfered_pin.csv (a solid of revolution, by slices:
// volume/recovered/revolution_body.hpp) and faceting_error_pin_in_bore.csv (two meshes, the pin's
// slices in the bore's section: volume/recovered/bore_pair.hpp).

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "geometry/mesh_topology.hpp"
#include "geometry/tessellate.hpp"
#include "io/mesh_io.hpp"
#include "volume/analytic/primitive_on_plane.hpp"
#include "volume/fast/surface_integration.hpp"
#include "volume/halfspace/clip.hpp"
#include "volume/recovered/recovered_surface.hpp"
#include "volume/recovered/refinement.hpp"

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using vcontact::volume::ContactVolume;

constexpr double kRadius = 0.01;                                               // m
constexpr double kLength = 0.03;                                               // m, cylinder
const double kDepths[] = {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 0.5};  // d/R

/// Rows: triangles, d/R, V_mesh, V_exact, relative errors of V and of r_gyr.
void writeTable(const std::string& path, const std::string& shape, const int (&resolutions)[4],
                const std::function<vcontact::geometry::TriangleMesh(int)>& tessellate,
                const std::function<Isometry3d(double)>& poseAtDepth,
                const std::function<ContactVolume(const Isometry3d&)>& exact) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(10);
  f << "shape,triangles,d_over_R,V_mesh_m3,V_exact_m3,V_rel_error,r_gyr_rel_error,"
       "representation,V_recovered_m3,V_recovered_rel_error\n";
  const Isometry3d H = Isometry3d::Identity();
  for (int res : resolutions) {
    const vcontact::geometry::TriangleMesh mesh = tessellate(res);
    const vcontact::geometry::SurfaceRecognition surfaces =
        vcontact::geometry::recogniseSurfaces(mesh);
    for (double dR : kDepths) {
      const Isometry3d X = poseAtDepth(dR * kRadius);
      const ContactVolume m = vcontact::volume::meshHalfspaceContact(mesh, X, H);
      const ContactVolume e = exact(X);
      const vcontact::volume::RecoveredContact r =
          vcontact::volume::recoveredHalfspaceContact(mesh, surfaces, X, H);
      f << shape << ',' << mesh.triangleCount() << ',' << dR << ',' << m.volume << ',' << e.volume
        << ',' << (m.volume - e.volume) / e.volume << ',' << (m.r_gyr - e.r_gyr) / e.r_gyr << ','
        << representationName(r.representation) << ',' << r.cv.volume << ','
        << (r.cv.volume - e.volume) / e.volume << '\n';
    }
  }
  std::cout << "wrote " << path << '\n';
}

// Area of a circular segment of height h on radius ρ, stable for h ≪ ρ.
double segment(double rho, double h) {
  if (h <= 0.0) return 0.0;
  return rho * rho * 2.0 * std::asin(std::sqrt(h / (2.0 * rho))) -
         (rho - h) * std::sqrt(h * (2.0 * rho - h));
}

// A pin of radius r, length L along z from 0, 45° chamfers c, 64 segments.
vcontact::geometry::TriangleMesh chamferedPin(double r, double L, double c) {
  return vcontact::geometry::tessellateRevolution({{r - c, 0.0}, {r, c}, {r, L - c}, {r - c, L}},
                                                  64);
}

void writeRefinedRow(std::ofstream& f, const std::string& shape, long triangles, double ratio,
                     double poly, double exact, const vcontact::volume::RecoveredContact& r,
                     double seconds) {
  f << shape << ',' << triangles << ',' << ratio << ',' << poly << ',' << exact << ','
    << (poly - exact) / exact << ',' << representationName(r.representation) << ',' << r.cv.volume
    << ',' << (r.cv.volume - exact) / exact << ',' << r.level << ',' << r.converged << ','
    << r.volume_error_bound / exact << ',' << seconds << '\n';
}

const char* kRefinedHeader =
    "shape,triangles,d_over_r,V_mesh_m3,V_exact_m3,V_rel_error,representation,V_recovered_m3,"
    "V_recovered_rel_error,level,converged,error_bound_rel,recovered_seconds\n";

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The chamfered pin (r 5 mm, 30 mm, 0.5 mm chamfers) in the bundled block's 5.1 mm bore, axes
// parallel, pressed sideways by d along the block's 20 mm: V = 20 mm times the pin's disk
// outside the bore's (the pin's segment beyond the circles' crossing chord less the bore's).
// Recovered: by slices (representation revolution_in_bore; the refinement before them).
void writePinInBore(const std::string& path, const std::string& assets) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(10);
  f << kRefinedHeader;
  const vcontact::geometry::TriangleMesh block =
      vcontact::io::readMesh(assets + "/scenarios/meshes/block_hole_d10.stl").mesh;
  const double r = 0.005, R = 0.0051;
  const vcontact::geometry::TriangleMesh pin = chamferedPin(r, 0.03, 0.0005);
  const auto recB = vcontact::geometry::recogniseSurfaces(block);
  const auto recA = vcontact::geometry::recogniseSurfaces(pin);
  const vcontact::volume::RecoveredBody a(pin, recA), b(block, recB);
  const vcontact::geometry::MeshBvh ta(pin), tb(block);
  const vcontact::geometry::MeshTopology topoA(pin), topoB(block);
  for (double ratio : {1e-4, 1e-3, 1e-2}) {
    const double d = ratio * r, e = R - r + d;
    const double hB = (r - R + e) * (r + R - e) / (2.0 * e);
    const double exact = 0.02 * (segment(r, hB + d) - segment(R, hB));
    Isometry3d X = Isometry3d::Identity();
    X.translation() = Vector3d(e * std::cos(0.3), e * std::sin(0.3), -0.025);
    const double poly = vcontact::volume::meshMeshContact(ta, topoA, X, tb, topoB,
                                                          Isometry3d::Identity(), nullptr, false)
                            .aggregate.volume;
    const auto start = std::chrono::steady_clock::now();
    const auto rc = vcontact::volume::recoveredMeshMeshContact(a, X, b, Isometry3d::Identity());
    writeRefinedRow(f, "pin_in_bore", pin.triangleCount() + block.triangleCount(), ratio, poly,
                    exact, rc, secondsSince(start));
  }
  std::cout << "wrote " << path << '\n';
}

// The same pin lying on its side on a plate, a vertex row down: the straight part's segment
// times its length, and each chamfer's sections (segment of height d − t on radius r − t),
// by Simpson's rule after t = d(1 − u²).
void writeChamferedPin(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(10);
  f << kRefinedHeader;
  const double r = 0.005, L = 0.03, c = 0.0005;
  const vcontact::geometry::TriangleMesh pin = chamferedPin(r, L, c);
  const auto rec = vcontact::geometry::recogniseSurfaces(pin);
  const vcontact::volume::RecoveredBody body(pin, rec);
  for (double ratio : {1e-4, 1e-3, 1e-2}) {
    const double d = ratio * r;
    double sum = 0.0;
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n, t = d * (1.0 - u * u);
      sum += ((i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * segment(r - t, d - t) * 2 * d * u;
    }
    const double exact = (L - 2 * c) * segment(r, d) + 2.0 * sum / (3.0 * n);
    Isometry3d X = Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
    X.translation() = Vector3d(0, 0, r - d);
    const double poly =
        vcontact::volume::meshHalfspaceContact(pin, X, Isometry3d::Identity()).volume;
    const auto start = std::chrono::steady_clock::now();
    const auto rc = body.halfspaceContact(X, Isometry3d::Identity());
    writeRefinedRow(f, "chamfered_pin", pin.triangleCount(), ratio, poly, exact, rc,
                    secondsSince(start));
  }
  std::cout << "wrote " << path << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: vcontact_error_table OUTPUT_DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  const Isometry3d H = Isometry3d::Identity();
  // Sphere, pole down: the depth of the true sphere is d; the mesh's lowest vertex is the
  // pole, so both are at the same depth.
  const int sphereSegments[] = {16, 32, 100, 316};
  writeTable(
      dir + "/faceting_error_sphere.csv", "sphere", sphereSegments,
      [](int s) { return vcontact::geometry::tessellateSphere(kRadius, s, s / 2 + 1); },
      [](double d) {
        Isometry3d X = Isometry3d::Identity();
        X.translation() = Vector3d(0, 0, kRadius - d);
        return X;
      },
      [&](const Isometry3d& X) { return vcontact::volume::sphereHalfspace(kRadius, X, H); });
  // Cylinder on its side with a vertex row straight down (azimuth 0 rotated to −z).
  const int cylinderSegments[] = {16, 32, 128, 512};
  writeTable(
      dir + "/faceting_error_cylinder.csv", "cylinder", cylinderSegments,
      [](int s) { return vcontact::geometry::tessellateCylinder(kRadius, kLength, s); },
      [](double d) {
        Isometry3d X = Isometry3d::Identity();
        X.linear() = (Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()) *
                      Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()))
                         .toRotationMatrix();
        X.translation() = Vector3d(0, 0, kRadius - d);
        return X;
      },
      [&](const Isometry3d& X) {
        return vcontact::volume::cylinderHalfspace(kRadius, kLength, X, H);
      });
  writeChamferedPin(dir + "/faceting_error_chamfered_pin.csv");
  writePinInBore(dir + "/faceting_error_pin_in_bore.csv", VCONTACT_ASSETS_DIR);
  return 0;
}
