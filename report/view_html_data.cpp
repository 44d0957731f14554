// viewData: reads a simulation output folder and its scenario into the JSON the viewer plays.

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "formats/dataset_file.hpp"
#include "formats/scenario_file.hpp"
#include "geometry/error.hpp"
#include "geometry/tessellate.hpp"
#include "io/file_names.hpp"
#include "io/json_file.hpp"
#include "report/simulation_csv.hpp"
#include "report/view_html.hpp"

namespace vcontact::report {
namespace {

namespace fs = std::filesystem;

// Facets of the primitives drawn by the viewer: a sphere of 48 × 24 facets deviates from the
// true one by 1 − cos(π/48) ≈ 0.2 % of its radius, less than a pixel at the default zoom.
constexpr int kSphereSegments = 48;
constexpr int kSphereRings = 24;
constexpr int kCylinderSegments = 48;

// A CSV table of numbers with a header (the files report/simulation_csv writes); columns that
// are text (bodies.csv's body name) are kept as text.
struct CsvTable {
  std::string path;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
  }
  int requireColumn(const std::string& name) const {
    const int c = column(name);
    if (c < 0) throw InputError(path, "line 1: no column '" + name + "' in the header");
    return c;
  }
  double number(std::size_t row, int col) const {
    const std::string& s = rows[row][static_cast<std::size_t>(col)];
    double x = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
      throw InputError(path, "line " + std::to_string(row + 2) + ", column '" + header[col] +
                                 "': expected a number, found '" + s + "'");
    }
    return x;
  }
};

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream s(line);
  while (std::getline(s, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

CsvTable readCsv(const fs::path& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path.string(), "cannot open for reading");
  CsvTable t{path.string(), {}, {}};
  std::string line;
  if (!std::getline(f, line)) throw InputError(path.string(), "empty file; expected a header");
  t.header = splitCsvLine(line);
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    t.rows.push_back(splitCsvLine(line));
    if (t.rows.back().size() != t.header.size()) {
      throw InputError(path.string(), "line " + std::to_string(t.rows.size() + 1) + ": " +
                                          std::to_string(t.rows.back().size()) +
                                          " fields, expected " + std::to_string(t.header.size()));
    }
  }
  return t;
}

// Meshes go to the page in single precision: a float keeps 7 digits, far below a pixel.
nlohmann::json meshJson(const geometry::TriangleMesh& m) {
  std::vector<float> v(m.vertices.data(), m.vertices.data() + m.vertices.size());
  std::vector<int> f(m.triangles.data(), m.triangles.data() + m.triangles.size());
  return {{"vertices", v}, {"faces", f}};
}

nlohmann::json bodyShapeJson(const geometry::Shape& shape) {
  using namespace geometry;
  if (std::holds_alternative<HalfSpace>(shape)) return {{"halfspace", true}};
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    return meshJson(tessellateSphere(s->radius, kSphereSegments, kSphereRings));
  }
  if (const auto* c = std::get_if<Cylinder>(&shape)) {
    return meshJson(tessellateCylinder(c->radius, c->length, kCylinderSegments));
  }
  if (const auto* b = std::get_if<Box>(&shape)) return meshJson(tessellateBox(b->size));
  return meshJson(*std::get<Mesh>(shape).mesh);
}

std::string scenarioPath(const ViewOptions& o) {
  if (!o.scenario.empty()) return o.scenario;
  const fs::path summary = fs::path(o.out_dir) / "summary.json";
  if (!fs::exists(summary)) {
    throw InputError(o.out_dir,
                     "no summary.json: not a folder written by vcontact simulate (nor by "
                     "vcontact compare on a dynamic dataset: compare.json and trajectory.csv)");
  }
  const nlohmann::json j = io::readJsonFile(summary.string());
  if (!j.contains("scenario") || !j["scenario"].is_string()) {
    throw InputError(summary.string(),
                     "no \"scenario\" key (written by vcontact simulate since the viewer); "
                     "name the scenario with --scenario FILE");
  }
  return j["scenario"].get<std::string>();
}

// bodies.csv: the output times and, per body, its poses as flat [x y z qw qx qy qz ...].
void addBodyPoses(const CsvTable& t, nlohmann::json& data) {
  const int name = t.requireColumn("body");
  std::vector<int> cols;
  for (const char* c : {"t", "x", "y", "z", "qw", "qx", "qy", "qz"}) {
    cols.push_back(t.requireColumn(c));
  }
  std::map<std::string, std::vector<double>> poses;
  std::vector<double> times;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const double time = t.number(r, cols[0]);
    if (times.empty() || time != times.back()) times.push_back(time);
    auto& p = poses[t.rows[r][static_cast<std::size_t>(name)]];
    for (std::size_t k = 1; k < cols.size(); ++k) p.push_back(t.number(r, cols[k]));
  }
  for (auto& body : data["bodies"]) {
    const auto it = poses.find(body["name"].get<std::string>());
    if (it == poses.end() || it->second.size() != 7 * times.size()) {
      throw InputError(t.path, "body '" + body["name"].get<std::string>() +
                                   "' lacks a row at some of the " + std::to_string(times.size()) +
                                   " output times");
    }
    body["poses"] = it->second;
  }
  data["times"] = times;
}

std::vector<int> columns(const CsvTable& t, std::initializer_list<const char*> names) {
  std::vector<int> cols;
  for (const char* n : names) cols.push_back(t.requireColumn(n));
  return cols;
}

// The pair's wrench series (pair_<name>.csv) and its patches per output time: one row per
// patch in pair_<name>_patches.csv when present, else the aggregate when V > 0.
nlohmann::json pairJson(const fs::path& dir, const dynamics::ContactPair& pair, std::size_t frames,
                        std::vector<std::string>& warnings) {
  const std::string base = "pair_" + io::fileSafe(pair.name);
  const CsvTable agg = readCsv(dir / (base + ".csv"));
  if (agg.rows.size() != frames) {
    throw InputError(agg.path, std::to_string(agg.rows.size()) +
                                   " rows, expected one per time of "
                                   "bodies.csv (" +
                                   std::to_string(frames) + ")");
  }
  const auto series = columns(agg, {"t", "fx", "fy", "fz", "taux", "tauy", "tauz", "f_n", "V"});
  nlohmann::json wrench = nlohmann::json::object();
  const char* names[] = {"t", "fx", "fy", "fz", "taux", "tauy", "tauz", "f_n", "V"};
  for (std::size_t k = 0; k < series.size(); ++k) {
    std::vector<double> s;
    for (std::size_t r = 0; r < frames; ++r) s.push_back(agg.number(r, series[k]));
    wrench[names[k]] = s;
  }
  const fs::path patchFile = dir / (base + "_patches.csv");
  const bool perPatch = fs::exists(patchFile);
  const CsvTable table = perPatch ? readCsv(patchFile) : agg;
  const auto c = columns(table, {"t", "V", "cx", "cy", "cz", "nx", "ny", "nz", "f_n"});
  std::vector<std::vector<double>> patches(frames);
  const auto& times = wrench["t"];
  std::size_t frame = 0;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double t = table.number(r, c[0]);
    while (frame < frames && times[frame].get<double>() < t) ++frame;
    if (frame == frames || times[frame].get<double>() != t) {
      throw InputError(table.path, "line " + std::to_string(r + 2) +
                                       ": time not among the output times of bodies.csv");
    }
    if (table.number(r, c[1]) <= 0.0) continue;
    for (std::size_t k = 2; k < c.size(); ++k) patches[frame].push_back(table.number(r, c[k]));
  }
  if (!perPatch) warnings.push_back(base + "_patches.csv absent: the aggregate contact is shown");
  return {{"name", pair.name}, {"a", pair.a},        {"b", pair.b},
          {"wrench", wrench},  {"patches", patches}, {"per_patch", perPatch}};
}

// loads.csv: per load and spring, in the order of their first row, one flat
// [px py pz fx fy fz ...] per output time (the point where the force acts, and the force).
nlohmann::json loadsJson(const fs::path& file, std::size_t frames) {
  const CsvTable t = readCsv(file);
  const int name = t.requireColumn("load");
  const auto c = columns(t, {"px", "py", "pz", "fx", "fy", "fz"});
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> rows;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const std::string& load = t.rows[r][static_cast<std::size_t>(name)];
    auto [it, added] = rows.try_emplace(load);
    if (added) order.push_back(load);
    for (int col : c) it->second.push_back(t.number(r, col));
  }
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& load : order) {
    if (rows[load].size() != 6 * frames) {
      throw InputError(t.path, "load '" + load + "' lacks a row at some of the " +
                                   std::to_string(frames) + " output times of bodies.csv");
    }
    out.push_back({{"name", load}, {"rows", rows[load]}});
  }
  return out;
}

// A folder `vcontact compare` wrote for a dynamic dataset, not one of `simulate`.
bool isTrajectoryCompare(const fs::path& dir) {
  return !fs::exists(dir / "summary.json") && fs::exists(dir / "compare.json") &&
         fs::exists(dir / "trajectory.csv");
}

std::string datasetPath(const ViewOptions& o, const nlohmann::json& compare,
                        const std::string& comparePath) {
  if (!o.dataset.empty()) return o.dataset;
  if (!compare.contains("dataset") || !compare["dataset"].is_string()) {
    throw InputError(comparePath,
                     "no \"dataset\" key (written by vcontact compare since the viewer plays "
                     "trajectories); name the dataset with --dataset FILE");
  }
  return compare["dataset"].get<std::string>();
}

// The 7 pose columns of trajectory.csv ending in `suffix` ("" recorded, "_sim" simulated), as
// one flat [x y z qw qx qy qz ...] per row.
std::vector<double> trajectoryPoses(const CsvTable& t, const std::string& suffix) {
  std::vector<int> cols;
  for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"})
    cols.push_back(t.requireColumn(c + suffix));
  std::vector<double> poses;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    for (int c : cols) poses.push_back(t.number(r, c));
  }
  return poses;
}

// trajectory.csv's series for the plot (heights and the position error, m) and each row's
// phase, with where the paths part (compare.json's part_time_s, null when they never do).
nlohmann::json trajectorySeries(const CsvTable& t, const nlohmann::json& compare) {
  nlohmann::json series = nlohmann::json::object();
  for (const char* name : {"z", "z_sim", "dp"}) {
    const int c = t.requireColumn(name);
    std::vector<double> s;
    for (std::size_t r = 0; r < t.rows.size(); ++r) s.push_back(t.number(r, c));
    series[name] = s;
  }
  const int phase = t.requireColumn("phase");
  std::vector<std::string> phases;
  for (const auto& row : t.rows) {
    std::string p = row[static_cast<std::size_t>(phase)];
    if (p.size() >= 2 && p.front() == '"' && p.back() == '"') p = p.substr(1, p.size() - 2);
    phases.push_back(p);
  }
  series["phase"] = phases;
  const auto part = compare.find("part_time_s");
  series["part_time"] = part != compare.end() && part->is_number() ? *part : nlohmann::json();
  return series;
}

// The plate at its pose (moved by the compare's plate offset along its normal), the payload as
// simulated, and the payload as recorded, drawn as a ghost.
nlohmann::json trajectoryViewData(const ViewOptions& o) {
  const fs::path dir(o.out_dir);
  const std::string comparePath = (dir / "compare.json").string();
  const nlohmann::json compare = io::readJsonFile(comparePath);
  const std::string path = datasetPath(o, compare, comparePath);
  const validation::Dataset d = formats::readDataset(path).dataset;
  const CsvTable t = readCsv(dir / "trajectory.csv");
  if (t.rows.empty()) throw InputError(t.path, "no rows after the header");
  std::vector<double> times;
  const int tc = t.requireColumn("t");
  for (std::size_t r = 0; r < t.rows.size(); ++r) times.push_back(t.number(r, tc));

  Eigen::Isometry3d X_BP = d.X_BP;
  X_BP.translation() += compare.value("plate_offset_m", 0.0) * d.X_BP.linear().col(2);
  const Eigen::Quaterniond q(X_BP.linear());
  const std::vector<double> platePose = {X_BP.translation().x(),
                                         X_BP.translation().y(),
                                         X_BP.translation().z(),
                                         q.w(),
                                         q.x(),
                                         q.y(),
                                         q.z()};
  nlohmann::json plate = bodyShapeJson(d.plate);
  plate["name"] = "plate";
  plate["fixed"] = true;
  std::vector<double> platePoses;
  for (std::size_t r = 0; r < times.size(); ++r)
    platePoses.insert(platePoses.end(), platePose.begin(), platePose.end());
  plate["poses"] = platePoses;

  const std::string name = d.name.empty() ? "payload" : d.name;
  nlohmann::json simulated = bodyShapeJson(d.payload);
  simulated["name"] = name + " (simulated)";
  simulated["fixed"] = false;
  simulated["poses"] = trajectoryPoses(t, "_sim");
  nlohmann::json recorded = bodyShapeJson(d.payload);
  recorded["name"] = name + " (record)";
  recorded["fixed"] = false;
  recorded["ghost"] = true;
  recorded["poses"] = trajectoryPoses(t, "");

  nlohmann::json data;
  data["scenario"] = fs::path(path).filename().string();
  std::ostringstream description;
  description.precision(4);
  description << "the record (grey ghost) against the model " << compare.value("model", "?")
              << ", e_q " << compare.value("e_q", std::nan(""));
  data["description"] = description.str();
  data["bodies"] = {plate, simulated, recorded};
  data["times"] = times;
  data["pairs"] = nlohmann::json::array();
  data["loads"] = nlohmann::json::array();
  data["trajectory"] = trajectorySeries(t, compare);
  return data;
}

}  // namespace

nlohmann::json viewData(const ViewOptions& o, std::vector<std::string>& warnings) {
  const fs::path dir(o.out_dir);
  if (!fs::is_directory(dir)) throw InputError(o.out_dir, "not a folder");
  if (!o.scenario.empty() && !o.dataset.empty()) {
    throw InputError("--dataset",
                     "names a dynamic compare's dataset and --scenario a "
                     "simulation's scenario: give one of them");
  }
  if (!o.dataset.empty() || (o.scenario.empty() && isTrajectoryCompare(dir)))
    return trajectoryViewData(o);
  const std::string path = scenarioPath(o);
  const formats::ScenarioFile file = formats::readScenarioFile(path);
  nlohmann::json data;
  data["scenario"] = fs::path(path).filename().string();
  data["description"] = io::readJsonFile(path).value("description", "");
  data["bodies"] = nlohmann::json::array();
  for (const auto& body : file.scenario.bodies) {
    nlohmann::json b = bodyShapeJson(body.shape);
    b["name"] = body.name;
    b["fixed"] = body.motion == dynamics::BodyMotion::kFixed;
    data["bodies"].push_back(b);
  }
  addBodyPoses(readCsv(dir / "bodies.csv"), data);
  const std::size_t frames = data["times"].size();
  data["pairs"] = nlohmann::json::array();
  for (const auto& pair : file.scenario.pairs) {
    const std::string csv = "pair_" + io::fileSafe(pair.name) + ".csv";
    if (!fs::exists(dir / csv)) {  // "outputs": {"pairs": false} in the scenario
      warnings.push_back(csv + " absent: pair '" + pair.name + "' is not shown");
      continue;
    }
    data["pairs"].push_back(pairJson(dir, pair, frames, warnings));
  }
  data["loads"] = nlohmann::json::array();
  const bool hasLoads = !file.scenario.loads.empty() || !file.scenario.springs.empty();
  if (fs::exists(dir / "loads.csv")) {
    data["loads"] = loadsJson(dir / "loads.csv", frames);
  } else if (hasLoads) {  // "outputs": {"loads": false}
    warnings.push_back("loads.csv absent: the loads and springs are not shown");
  }
  return data;
}

}  // namespace vcontact::report
