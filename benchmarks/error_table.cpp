// Faceting error of tessellated bodies against the closed forms of MODEL.md §5, written as
// CSV: the error is the mesh's, not the clip's (the clip is exact for the polyhedron); beside
// it, the error of the same mesh on its recovered surface (docs/SURFACES.md).
//   usage: vcontact_error_table OUTPUT_DIR
// writes OUTPUT_DIR/faceting_error_sphere.csv and OUTPUT_DIR/faceting_error_cylinder.csv.

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "geometry/tessellate.hpp"
#include "volume/analytic.hpp"
#include "volume/halfspace_clip.hpp"
#include "volume/recovered_surface.hpp"

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
        << r.representation << ',' << r.cv.volume << ',' << (r.cv.volume - e.volume) / e.volume
        << '\n';
    }
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
  return 0;
}
