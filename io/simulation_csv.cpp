#include "io/simulation_csv.hpp"

#include <cctype>
#include <filesystem>

#include "geometry/error.hpp"

namespace vcontact::io {
namespace {

constexpr int kDigits = 12;  // enough for µm penetrations on metre positions

void put(std::ostream& o, const Eigen::Vector3d& v) {
  o << ',' << v.x() << ',' << v.y() << ',' << v.z();
}

void putHeader3(std::ostream& o, const std::string& prefix) {
  o << ',' << prefix << "x," << prefix << "y," << prefix << "z";
}

}  // namespace

std::string fileSafe(const std::string& name) {
  std::string s = name;
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return s;
}

std::ofstream SimulationCsvWriter::open(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError(path, "cannot open for writing");
  f.precision(kDigits);
  files_.push_back(path);
  return f;
}

SimulationCsvWriter::SimulationCsvWriter(const std::string& dir,
                                         const dynamics::Scenario& scenario,
                                         const OutputSelection& outputs)
    : scenario_(scenario), outputs_(outputs) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create output directory: " + ec.message());
  const std::filesystem::path base(dir);
  if (outputs_.bodies) {
    bodies_ = open((base / "bodies.csv").string());
    bodies_ << "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  }
  if (!outputs_.pairs) return;
  for (const auto& pair : scenario.pairs) {
    std::ofstream& f = pairs_.emplace_back(open((base / ("pair_" + fileSafe(pair.name) + ".csv")).string()));
    f << "t,V,depth,area,r_gyr";
    putHeader3(f, "c");
    putHeader3(f, "n");
    putHeader3(f, "f");
    putHeader3(f, "tau");
    f << ",f_n,s,mu_max";
    putHeader3(f, "z");
    f << ",theta_n,s_dw";
    if (outputs_.shares) {
      for (const auto& id : pair.model.effectIds()) {
        putHeader3(f, id + ".f");
        putHeader3(f, id + ".tau");
      }
    }
    f << '\n';
  }
}

void SimulationCsvWriter::write(const dynamics::Snapshot& s) {
  if (outputs_.bodies) {
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      const dynamics::BodyKinematics& k = s.bodies[i];
      const Eigen::Quaterniond q(k.X_WB.linear());
      bodies_ << s.t << ',' << scenario_.bodies[i].name;
      put(bodies_, k.X_WB.translation());
      bodies_ << ',' << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z();
      put(bodies_, k.pointVelocity(k.X_WB.translation()));
      put(bodies_, k.w_WB);
      bodies_ << '\n';
    }
    bodies_.flush();
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const dynamics::PairOutput& p = s.pairs[k];
    std::ofstream& f = pairs_[k];
    f << s.t << ',' << p.cv.volume << ',' << p.cv.depth << ',' << p.cv.area << ',' << p.cv.r_gyr;
    put(f, p.cv.centroid);
    put(f, p.cv.normal);
    put(f, p.result.wrench.f_W);
    put(f, p.result.wrench.tau_W);
    f << ',' << p.result.f_n << ',' << p.result.s << ',' << p.result.mu_max;
    put(f, p.state.z_W);
    f << ',' << p.state.theta_n << ',' << p.state.s_dw;
    if (outputs_.shares) {
      for (const auto& share : p.result.shares) {
        put(f, share.f_W);
        put(f, share.tau_W);
      }
    }
    f << '\n';
    f.flush();
  }
}

}  // namespace vcontact::io
