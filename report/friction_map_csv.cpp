#include "report/friction_map_csv.hpp"

#include <ostream>

#include "io/output_file.hpp"

namespace vcontact::report {

namespace {

void putFrictionMap(const validation::FrictionMap& map, std::ostream& f) {
  f.precision(12);
  f << "eps,v_mps,omega_radps,f_n_N,F_lumped_N,F_distributed_N,F_exact_N,M_lumped_Nm,"
       "M_distributed_Nm,M_exact_Nm,F_lumped_over_distributed,M_lumped_over_distributed\n";
  const double fn = map.f_n;
  for (const validation::FrictionMapRow& r : map.rows) {
    f << r.eps << ',' << r.v << ',' << r.w << ',' << fn << ',' << r.f_lumped << ',' << r.f_dist
      << ',';
    if (r.exact) f << map.mu * fn * r.exact->force;
    f << ',' << r.m_lumped << ',' << r.m_dist << ',';
    if (r.exact) f << map.mu * fn * map.R * r.exact->torque;
    f << ',' << validation::lumpedOverDistributed(r.f_lumped, r.f_dist) << ','
      << validation::lumpedOverDistributed(r.m_lumped, r.m_dist) << '\n';
  }
}

}  // namespace

void writeFrictionMapCsv(const validation::FrictionMap& map, const std::string& path) {
  io::writeFile(path, [&](std::ostream& f) { putFrictionMap(map, f); });
}

}  // namespace vcontact::report
