#include "report/depth_map_csv.hpp"

#include <fstream>

#include "geometry/error.hpp"

namespace vcontact::report {

void writeDepthMapCsv(const volume::DepthField& field, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError(path, "cannot open for writing");
  f.precision(17);
  f << "x_m,y_m,z_m,delta_m\n";
  for (std::size_t i = 0; i < field.depth.size(); ++i) {
    const Eigen::Vector3d& p_W = field.points_W[i];
    f << p_W.x() << ',' << p_W.y() << ',' << p_W.z() << ',' << field.depth[i] << '\n';
  }
}

}  // namespace vcontact::report
