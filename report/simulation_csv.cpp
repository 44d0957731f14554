#include "report/simulation_csv.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/file_names.hpp"
#include "report/csv_number.hpp"

namespace vcontact::report {
namespace {

void put(CsvBuffer& row, const Eigen::Vector3d& v) {
  row.number(v.x());
  row.number(v.y());
  row.number(v.z());
}

void putHeader3(std::ostream& o, const std::string& prefix) {
  o << ',' << prefix << "x," << prefix << "y," << prefix << "z";
}

// The columns a pair row and a patch row share: the contact, the wrench on the payload at its
// centroid, the friction figures and the states.
void putContactHeader(std::ostream& f, const dynamics::ContactPair& pair) {
  f << ",V,depth,area,r_gyr";
  putHeader3(f, "c");
  putHeader3(f, "n");
  putHeader3(f, "f");
  putHeader3(f, "tau");
  f << ",f_n,s,mu_max";
  for (const auto& name : pair.model.stateLayout().valueNames()) f << ',' << name;
}

void putContact(CsvBuffer& row, const volume::ContactVolume& cv, const dynamics::ContactResult& r,
                const dynamics::PairState& state, int state_size) {
  for (double x : {cv.volume, cv.depth, cv.area, cv.r_gyr}) row.number(x);
  put(row, cv.p_WC);
  put(row, cv.n_W);
  put(row, r.wrench.f_W);
  put(row, r.wrench.tau_W);
  for (double x : {r.f_n, r.s, r.mu_max}) row.number(x);
  for (int i = 0; i < state_size; ++i) row.number(state[i]);
}

// One share per declared column, whatever the result holds: the header names a column for each
// effect of the model, and every row has the header's fields (issue 36: a result that carried
// no shares wrote a short row). A share the result lacks is an effect that did not act: zero.
void putShares(CsvBuffer& row, const std::vector<dynamics::Wrench>& shares, std::size_t effects) {
  assert(shares.empty() || shares.size() == effects);
  for (std::size_t i = 0; i < effects; ++i) {
    const dynamics::Wrench share = i < shares.size() ? shares[i] : dynamics::Wrench{};
    put(row, share.f_W);
    put(row, share.tau_W);
  }
}

// The buffer's text onto the file, in one write.
void flush(const CsvBuffer& text, std::ostream& f) {
  f.write(text.view().data(), static_cast<std::streamsize>(text.view().size()));
}

}  // namespace

std::ostream& SimulationCsvWriter::open(const std::string& path) {
  files_.push_back(path);
  return set_.open(path);
}

SimulationCsvWriter::SimulationCsvWriter(const std::string& dir, const dynamics::Scenario& scenario,
                                         const formats::OutputSelection& outputs)
    : dir_(dir), scenario_(scenario), outputs_(outputs), set_(dir) {
  const std::filesystem::path base(dir);
  const bool loads = outputs_.loads && (!scenario.loads.empty() || !scenario.springs.empty());
  if (outputs_.bodies) {
    bodies_ = &open((base / "bodies.csv").string());
    *bodies_ << "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  }
  if (loads) {
    loads_ = &open((base / "loads.csv").string());
    *loads_ << "t,load,body,px,py,pz,fx,fy,fz,taux,tauy,tauz\n";
  }
  if (!outputs_.pairs) return;
  for (const auto& pair : scenario.pairs) {
    std::ostream& f =
        *pairs_.emplace_back(&open((base / ("pair_" + io::fileSafe(pair.name) + ".csv")).string()));
    f << "t";
    putContactHeader(f, pair);
    if (outputs_.shares) {
      for (const auto& id : pair.model.effectIds()) {
        putHeader3(f, id + ".f");
        putHeader3(f, id + ".tau");
      }
    }
    f << '\n';
    patches_.push_back(nullptr);
    if (dynamics::patchSlots(scenario, pair) < 2) continue;
    patches_.back() = &open((base / ("pair_" + io::fileSafe(pair.name) + "_patches.csv")).string());
    std::ostream& g = *patches_.back();
    g << "t,patch,slot";
    putContactHeader(g, pair);
    g << '\n';
  }
}

void SimulationCsvWriter::write(const dynamics::Snapshot& s) {
  if (outputs_.bodies) writeBodies(s);
  if (loads_) writeLoads(s);
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const dynamics::PairOutput& p = s.pairs[k];
    const int state_size = scenario_.pairs[k].model.stateLayout().size();
    text_.clear();
    text_.first(s.t);
    putContact(text_, p.cv, p.result, p.state, state_size);
    if (outputs_.shares) putShares(text_, p.result.shares, scenario_.pairs[k].model.effectCount());
    text_.endRow();
    flush(text_, *pairs_[k]);
    if (patches_[k]) writePatches(s.t, p, state_size, *patches_[k]);
  }
  checkWrites();
}

void SimulationCsvWriter::writeBodies(const dynamics::Snapshot& s) {
  text_.clear();
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const dynamics::BodyKinematics& k = s.bodies[i];
    const Eigen::Quaterniond q(k.X_WB.linear());
    text_.first(s.t);
    text_.text(scenario_.bodies[i].name);
    put(text_, k.X_WB.translation());
    text_.number(q.w());
    put(text_, q.vec());
    put(text_, k.pointVelocity(k.X_WB.translation()));
    put(text_, k.w_WB);
    text_.endRow();
  }
  flush(text_, *bodies_);
}

// One row per load, then per spring: the wrench on its body (a spring's body a) with the
// force at (px, py, pz).
void SimulationCsvWriter::writeLoads(const dynamics::Snapshot& s) {
  const std::size_t n_loads = scenario_.loads.size();
  text_.clear();
  for (std::size_t k = 0; k < s.loads.size(); ++k) {
    const bool load = k < n_loads;
    const std::string& name = load ? scenario_.loads[k].name : scenario_.springs[k - n_loads].name;
    const std::size_t body = load ? scenario_.loads[k].body : scenario_.springs[k - n_loads].a;
    text_.first(s.t);
    text_.text(name);
    text_.text(scenario_.bodies[body].name);
    put(text_, s.loads[k].p_W);
    put(text_, s.loads[k].wrench.f_W);
    put(text_, s.loads[k].wrench.tau_W);
    text_.endRow();
  }
  flush(text_, *loads_);
}

// One row per patch, in the query's order (patch = its index).
void SimulationCsvWriter::writePatches(double t, const dynamics::PairOutput& p, int state_size,
                                       std::ostream& f) {
  text_.clear();
  for (std::size_t i = 0; i < p.patches.size(); ++i) {
    const dynamics::PatchOutput& patch = p.patches[i];
    text_.first(t);
    text_.integer(static_cast<long>(i));
    text_.integer(patch.slot);
    putContact(text_, patch.cv, patch.result, patch.state, state_size);
    text_.endRow();
  }
  flush(text_, f);
}

// On a failed write every file is given up, not only the one that failed: a run's files
// belong together (io::OutputSet).
void SimulationCsvWriter::checkWrites() {
  try {
    set_.check();
  } catch (...) {
    pairs_.clear();
    patches_.clear();
    bodies_ = nullptr;
    loads_ = nullptr;
    throw;
  }
}

void SimulationCsvWriter::commit(const std::string& extraPath, const std::string& extraText) {
  if (!extraPath.empty()) set_.add(extraPath, [&](std::ostream& out) { out << extraText; });
  set_.commit();
  std::vector<std::string> written;
  for (const std::string& f : files_) written.push_back(std::filesystem::path(f).filename());
  removeStaleOutputs(dir_, written);
}

namespace {

// The first line of every CSV file a simulation writes begins with one of these.
constexpr std::array<std::string_view, 4> kOutputHeaders = {"t,body,x,y,z,", "t,load,body,",
                                                            "t,V,depth,area,", "t,patch,slot,V,"};

bool isOutputName(const std::string& name) {
  const bool pair = name.size() > 9 && name.rfind("pair_", 0) == 0 &&
                    name.compare(name.size() - 4, 4, ".csv") == 0;
  return pair || name == "bodies.csv" || name == "loads.csv";
}

bool hasOutputHeader(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  if (!std::getline(in, line)) return false;
  return std::any_of(kOutputHeaders.begin(), kOutputHeaders.end(),
                     [&](std::string_view h) { return line.rfind(h, 0) == 0; });
}

}  // namespace

std::vector<std::string> removeStaleOutputs(const std::string& dir,
                                            const std::vector<std::string>& written) {
  namespace fs = std::filesystem;
  std::vector<std::string> removed;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!isOutputName(name) || std::find(written.begin(), written.end(), name) != written.end()) {
      continue;
    }
    std::error_code rec;
    if (!it->is_regular_file(rec) || !hasOutputHeader(it->path())) continue;
    if (fs::remove(it->path(), rec)) removed.push_back(name);
  }
  return removed;
}

std::uint64_t outputRowCount(const dynamics::Scenario& scenario,
                             const formats::OutputSelection& outputs) {
  const dynamics::SimulationSettings& set = scenario.settings;
  const double times = std::floor(set.duration * set.output_rate_hz) + 1.0;
  double per_time = outputs.bodies ? static_cast<double>(scenario.bodies.size()) : 0.0;
  if (outputs.pairs) {
    for (const dynamics::ContactPair& pair : scenario.pairs) {
      const int slots = dynamics::patchSlots(scenario, pair);
      per_time += 1.0 + (slots < 2 ? 0.0 : static_cast<double>(slots));
    }
  }
  if (outputs.loads)
    per_time += static_cast<double>(scenario.loads.size() + scenario.springs.size());
  const double rows = times * per_time;
  constexpr double kBeyond = 1e19;  // beyond any limit; keeps the cast defined
  return static_cast<std::uint64_t>(std::min(rows, kBeyond));
}

}  // namespace vcontact::report
