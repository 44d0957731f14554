// Sphere of radius 1 cm, 1 mm into a half-space, through the installed library: prints the
// interference volume (and the report layer's table of it, so that the top layer's package
// links too) and exits 0 when it matches the spherical cap πd²(3R − d)/3.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "geometry/primitives.hpp"
#include "report/contact_volume_format.hpp"
#include "volume/contact.hpp"

int main() {
  const double R = 0.01, d = 0.001;
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();
  X_WA.translation().z() = R - d;
  const vcontact::volume::ContactVolume cv =
      vcontact::volume::computeContact(vcontact::geometry::Sphere{R}, X_WA,
                                       vcontact::geometry::HalfSpace{},
                                       Eigen::Isometry3d::Identity())
          .aggregate;
  const double cap = std::numbers::pi * d * d * (3.0 * R - d) / 3.0;
  std::printf("V = %.17g m^3, cap = %.17g m^3\n%s", cv.volume, cap,
              vcontact::report::toTable(cv).c_str());
  return std::abs(cv.volume - cap) <= 1e-14 * cap ? 0 : 1;
}
