#include "report/depth_map_csv.hpp"

#include <ostream>

#include "io/output_file.hpp"

namespace vcontact::report {

void putDepthMapCsv(const volume::DepthField& field, std::ostream& f) {
  f.precision(17);
  f << "x_m,y_m,z_m,delta_m\n";
  for (std::size_t i = 0; i < field.depth.size(); ++i) {
    const Eigen::Vector3d& p_W = field.points_W[i];
    f << p_W.x() << ',' << p_W.y() << ',' << p_W.z() << ',' << field.depth[i] << '\n';
  }
}

void writeDepthMapCsv(const volume::DepthField& field, const std::string& path) {
  io::writeFile(path, [&](std::ostream& f) { putDepthMapCsv(field, f); });
}

}  // namespace vcontact::report
