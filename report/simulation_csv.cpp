#include "report/simulation_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "geometry/error.hpp"

namespace vcontact::report {
namespace {

// Shortest round-trip form of a double (std::to_chars): exact, and several times faster than
// stream formatting, which dominated the cost of a simulation at high output rates.
void put(std::string& row, double x) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  row.push_back(',');
  row.append(buf, end);
}

void put(std::string& row, const Eigen::Vector3d& v) {
  put(row, v.x());
  put(row, v.y());
  put(row, v.z());
}

// The row's first field (time), without the leading comma.
std::string startRow(double t) {
  std::string row;
  put(row, t);
  row.erase(0, 1);
  return row;
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

io::OutputFile& SimulationCsvWriter::open(const std::string& path) {
  files_.push_back(path);
  return files_out_.emplace_back(path);
}

SimulationCsvWriter::SimulationCsvWriter(const std::string& dir, const dynamics::Scenario& scenario,
                                         const formats::OutputSelection& outputs)
    : scenario_(scenario), outputs_(outputs) {
  io::makeOutputFolder(dir);
  const std::filesystem::path base(dir);
  // Every OutputFile first, the pointers after: files_out_ does not move once filled.
  files_out_.reserve((outputs_.bodies ? 1 : 0) + (outputs_.pairs ? scenario.pairs.size() : 0));
  if (outputs_.bodies) {
    bodies_ = &open((base / "bodies.csv").string());
    bodies_->stream() << "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  }
  if (!outputs_.pairs) return;
  for (const auto& pair : scenario.pairs) {
    std::ostream& f =
        pairs_.emplace_back(&open((base / ("pair_" + fileSafe(pair.name) + ".csv")).string()))
            ->stream();
    f << "t,V,depth,area,r_gyr";
    putHeader3(f, "c");
    putHeader3(f, "n");
    putHeader3(f, "f");
    putHeader3(f, "tau");
    f << ",f_n,s,mu_max";
    for (const auto& name : pair.model.stateLayout().valueNames()) f << ',' << name;
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
      std::string row = startRow(s.t);
      row += ',' + scenario_.bodies[i].name;
      put(row, k.X_WB.translation());
      put(row, q.w());
      put(row, q.vec());
      put(row, k.pointVelocity(k.X_WB.translation()));
      put(row, k.w_WB);
      bodies_->stream() << row << '\n';
    }
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const dynamics::PairOutput& p = s.pairs[k];
    std::string row = startRow(s.t);
    for (double x : {p.cv.volume, p.cv.depth, p.cv.area, p.cv.r_gyr}) put(row, x);
    put(row, p.cv.p_WC);
    put(row, p.cv.n_W);
    put(row, p.result.wrench.f_W);
    put(row, p.result.wrench.tau_W);
    for (double x : {p.result.f_n, p.result.s, p.result.mu_max}) put(row, x);
    for (int i = 0; i < scenario_.pairs[k].model.stateLayout().size(); ++i) put(row, p.state[i]);
    if (outputs_.shares) {
      for (const auto& share : p.result.shares) {
        put(row, share.f_W);
        put(row, share.tau_W);
      }
    }
    pairs_[k]->stream() << row << '\n';
  }
  checkWrites();
}

// On a failed write every file is given up, not only the one that failed: a run's files
// belong together. Destroying the OutputFiles deletes their temporaries.
void SimulationCsvWriter::checkWrites() {
  for (io::OutputFile& f : files_out_) {
    if (f.stream()) continue;
    try {
      f.check();
    } catch (...) {
      files_out_.clear();
      pairs_.clear();
      bodies_ = nullptr;
      throw;
    }
  }
}

void SimulationCsvWriter::commit() {
  for (io::OutputFile& f : files_out_) f.stream().flush();
  checkWrites();
  for (io::OutputFile& f : files_out_) f.commit();
}

std::uint64_t outputRowCount(const dynamics::Scenario& scenario,
                             const formats::OutputSelection& outputs) {
  const dynamics::SimulationSettings& set = scenario.settings;
  const double times = std::floor(set.duration * set.output_rate_hz) + 1.0;
  const double per_time = (outputs.bodies ? static_cast<double>(scenario.bodies.size()) : 0.0) +
                          (outputs.pairs ? static_cast<double>(scenario.pairs.size()) : 0.0);
  const double rows = times * per_time;
  constexpr double kBeyond = 1e19;  // beyond any limit; keeps the cast defined
  return static_cast<std::uint64_t>(std::min(rows, kBeyond));
}

}  // namespace vcontact::report
