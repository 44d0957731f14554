#include "formats/dataset_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "geometry/error.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "io/shape_json.hpp"

namespace vcontact::formats {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kFormat = "vcontact.dataset/1";
const std::vector<std::string> kRequired = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
// Three samples are the fewest a second-order derivative needs.
constexpr std::size_t kMinimumSamples = 3;

bool isWrench(const std::string& c) {
  return std::find(validation::kWrenchColumns.begin(), validation::kWrenchColumns.end(), c) !=
         validation::kWrenchColumns.end();
}

std::string requireString(const json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where, "missing \"" + key + "\"");
  if (!j.at(key).is_string()) throw InputError(where, "\"" + key + "\" must be a string");
  return j.at(key).get<std::string>();
}

// --- CSV -------------------------------------------------------------------------------

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::stringstream ss(line);
  while (std::getline(ss, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    fields.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// The largest magnitude a column may hold (io/input_ranges.hpp) and its unit; a column of
// another name (a quaternion part, an extra column) is only checked finite.
std::pair<double, const char*> columnLimit(const std::string& name) {
  if (name == "t") return {io::kMaxTime, "s"};
  if (name == "x" || name == "y" || name == "z") return {io::kMaxPosition, "m"};
  if (name == "vx" || name == "vy" || name == "vz") return {io::kMaxSpeed, "m/s"};
  if (name == "wx" || name == "wy" || name == "wz") return {io::kMaxAngularSpeed, "rad/s"};
  if (name == "fx" || name == "fy" || name == "fz") return {io::kMaxForce, "N"};
  if (name == "tx" || name == "ty" || name == "tz") return {io::kMaxTorque, "N m"};
  return {HUGE_VAL, ""};
}

// A header that a spreadsheet in a decimal-comma locale or a UTF-8 editor wrote: named as
// such, since the generic "missing column" would not say why.
void checkHeader(const std::string& line, const std::string& path) {
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) {
    throw InputError(path,
                     "line 1: starts with a UTF-8 byte order mark; expected plain text (save "
                     "the CSV as UTF-8 without BOM)");
  }
  if (line.find(';') != std::string::npos && line.find(',') == std::string::npos) {
    throw InputError(path,
                     "line 1: columns are separated by ';'; expected ',' and numbers with a "
                     "decimal point (a CSV written with decimal commas is not read)");
  }
}

struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::vector<std::size_t> lineOf;  // file line of each row, for messages
};

Table readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot be read");
  Table table;
  std::string line;
  std::size_t lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (table.names.empty()) {
      checkHeader(line, path);
      table.names = splitFields(line);
      std::set<std::string> seen;
      for (const auto& n : table.names) {
        if (n.empty()) throw InputError(path, "line 1: empty column name");
        if (!seen.insert(n).second)
          throw InputError(path, "line 1: column '" + n + "' appears twice");
      }
      continue;
    }
    const auto fields = splitFields(line);
    if (fields.size() != table.names.size()) {
      std::ostringstream os;
      os << "line " << lineNo << ": " << fields.size() << " fields, but the header names "
         << table.names.size() << " columns";
      throw InputError(path, os.str());
    }
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), row[c]);
      const std::string where =
          "line " + std::to_string(lineNo) + ", column '" + table.names[c] + "'";
      if (f.empty() || ec != std::errc() || end != f.data() + f.size()) {
        throw InputError(path, where + ": '" + f + "' is not a number");
      }
      if (!std::isfinite(row[c])) throw InputError(path, where + ": '" + f + "' is not finite");
      const auto [limit, unit] = columnLimit(table.names[c]);
      if (std::abs(row[c]) > limit) {
        std::ostringstream os;
        os << where << ": " << f << " is beyond +-" << limit << " " << unit
           << " (io/input_ranges.hpp)";
        throw InputError(path, os.str());
      }
    }
    table.rows.push_back(std::move(row));
    table.lineOf.push_back(lineNo);
  }
  if (table.names.empty())
    throw InputError(path, "empty file: expected a header line of column names");
  return table;
}

std::size_t columnIndex(const Table& t, const std::string& name) {
  return static_cast<std::size_t>(std::find(t.names.begin(), t.names.end(), name) -
                                  t.names.begin());
}

// Either all three of a vector's columns or none.
bool hasTriple(const Table& t, const std::string& path, const std::array<std::string, 3>& cols) {
  int present = 0;
  for (const auto& c : cols) present += columnIndex(t, c) < t.names.size();
  if (present == 0) return false;
  if (present < 3) {
    throw InputError(path, "line 1: columns " + cols[0] + ", " + cols[1] + ", " + cols[2] +
                               " come together; some are missing");
  }
  return true;
}

void fillSamples(const Table& t, const std::string& path, validation::Dataset& d) {
  for (const auto& r : kRequired) {
    if (columnIndex(t, r) == t.names.size()) {
      throw InputError(path, "line 1: missing required column '" + r + "'");
    }
  }
  if (std::none_of(t.names.begin(), t.names.end(), isWrench)) {
    throw InputError(path,
                     "line 1: no wrench column; expected at least one of fx, fy, fz, tx, ty, tz");
  }
  if (t.rows.size() < kMinimumSamples) {
    throw InputError(path, "only " + std::to_string(t.rows.size()) + " samples; at least " +
                               std::to_string(kMinimumSamples) + " are needed");
  }
  const bool hasV = hasTriple(t, path, {"vx", "vy", "vz"});
  const bool hasW = hasTriple(t, path, {"wx", "wy", "wz"});
  auto col = [&](const std::string& n) { return columnIndex(t, n); };

  for (std::size_t c = 0; c < t.names.size(); ++c) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(t.rows.size()));
    for (std::size_t i = 0; i < t.rows.size(); ++i) v(static_cast<Eigen::Index>(i)) = t.rows[i][c];
    d.columns[t.names[c]] = std::move(v);
  }
  d.samples.resize(t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    const std::string where = "line " + std::to_string(t.lineOf[i]);
    validation::Sample& s = d.samples[i];
    s.t = r[col("t")];
    if (i > 0 && !(s.t > d.samples[i - 1].t)) {
      std::ostringstream os;
      os << where << ", column 't': time " << s.t << " is not after the previous sample's "
         << d.samples[i - 1].t << " (time must increase strictly)";
      throw InputError(path, os.str());
    }
    if (i > 0 && s.t - d.samples[i - 1].t < io::kMinSampleInterval) {
      std::ostringstream os;
      os << where << ", column 't': time step " << s.t - d.samples[i - 1].t << " s is below "
         << io::kMinSampleInterval << " s (a 1 GHz sampling rate)";
      throw InputError(path, os.str());
    }
    const Eigen::Vector4d q(r[col("qw")], r[col("qx")], r[col("qy")], r[col("qz")]);
    if (std::abs(q.norm() - 1.0) > kDatasetQuaternionTolerance) {
      std::ostringstream os;
      os << where << ", columns 'qw'..'qz': quaternion length " << q.norm()
         << " is far from 1 (tolerance " << kDatasetQuaternionTolerance << ")";
      throw InputError(path, os.str());
    }
    s.X_BA.linear() = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
    s.X_BA.translation() = Eigen::Vector3d(r[col("x")], r[col("y")], r[col("z")]);
    if (hasV) s.v_BA = Eigen::Vector3d(r[col("vx")], r[col("vy")], r[col("vz")]);
    if (hasW) s.w_BA = Eigen::Vector3d(r[col("wx")], r[col("wy")], r[col("wz")]);
  }
  d.velocityFromPositions = !hasV;
  d.omegaFromAttitude = !hasW;
  if (!hasV) validation::differentiatePositions(d.samples);
  if (!hasW) validation::differentiateAttitudes(d.samples);
}

void readOutputsAndNoise(const json& j, const std::string& where, const std::string& csv,
                         validation::Dataset& d) {
  if (!j.contains("outputs") || !j.at("outputs").is_array() || j.at("outputs").empty()) {
    throw InputError(where, "\"outputs\" must be a non-empty list of wrench columns");
  }
  for (const auto& o : j.at("outputs")) {
    if (!o.is_string() || !isWrench(o.get<std::string>())) {
      throw InputError(where, "outputs: " + o.dump() + " is not one of fx, fy, fz, tx, ty, tz");
    }
    const std::string name = o.get<std::string>();
    if (!d.columns.count(name)) {
      throw InputError(where, "outputs: \"" + name + "\" is not a column of " + csv);
    }
    d.outputs.push_back(name);
  }
  if (!j.contains("noise")) return;
  if (!j.at("noise").is_object())
    throw InputError(where, "\"noise\" must be an object {output: sigma}");
  for (const auto& [key, value] : j.at("noise").items()) {
    if (std::find(d.outputs.begin(), d.outputs.end(), key) == d.outputs.end()) {
      throw InputError(where, "noise: \"" + key + "\" is not one of the outputs");
    }
    if (!value.is_number() || !(value.get<double>() > 0.0) || !std::isfinite(value.get<double>())) {
      throw InputError(where,
                       "noise: \"" + key + "\" must be a positive number, got " + value.dump());
    }
    d.noise[key] = value.get<double>();
  }
}

}  // namespace

DatasetReadResult readDataset(const std::string& sidecarPath) {
  const json j = io::readJsonFile(sidecarPath);
  const std::string& where = sidecarPath;
  if (!j.is_object()) throw InputError(where, "the sidecar must be a JSON object");
  const std::string format = requireString(j, "format", where);
  if (format != kFormat) {
    throw InputError(where,
                     "format must be \"" + std::string(kFormat) + "\", got \"" + format + "\"");
  }
  const std::string mode = requireString(j, "mode", where);
  if (mode == "dynamic") {
    throw InputError(where,
                     "mode \"dynamic\" is reserved for a later version of the format; "
                     "this engine replays \"kinematic\" datasets");
  }
  if (mode != "kinematic")
    throw InputError(where, "mode must be \"kinematic\", got \"" + mode + "\"");

  DatasetReadResult result;
  validation::Dataset& d = result.dataset;
  d.sidecarPath = sidecarPath;
  const fs::path base = fs::path(sidecarPath).parent_path();
  d.name =
      j.contains("name") ? requireString(j, "name", where) : fs::path(sidecarPath).stem().string();
  if (j.contains("notes")) d.notes = requireString(j, "notes", where);
  const std::string data = requireString(j, "data", where);
  d.dataPath = (base / data).string();
  if (!fs::is_regular_file(d.dataPath)) {
    throw InputError(where, "data file \"" + data + "\" not found (looked for " + d.dataPath + ")");
  }
  for (const char* body : {"payload", "plate"}) {
    if (!j.contains(body)) throw InputError(where, std::string("missing \"") + body + "\"");
    io::JsonShape s = io::parseShapeJson(j.at(body), where + ": " + body, base.string());
    result.warnings.insert(result.warnings.end(), s.warnings.begin(), s.warnings.end());
    (std::string(body) == "payload" ? d.payload : d.plate) = std::move(s.shape);
  }
  if (std::holds_alternative<geometry::HalfSpace>(d.payload)) {
    throw InputError(where + ": payload", "the payload must be a bounded body, not a half-space");
  }
  fillSamples(readCsv(d.dataPath), d.dataPath, d);
  readOutputsAndNoise(j, where, d.dataPath, d);
  if (d.velocityFromPositions) {
    result.warnings.push_back(d.dataPath +
                              ": no vx, vy, vz columns; velocities differentiated from x, y, z");
  }
  if (d.omegaFromAttitude) {
    result.warnings.push_back(
        d.dataPath +
        ": no wx, wy, wz columns; angular velocities differentiated from the quaternions");
  }
  return result;
}

void writeDataset(const validation::Dataset& d, const std::string& sidecarPath) {
  const fs::path sidecar(sidecarPath);
  const fs::path csv = fs::path(sidecar).replace_extension(".csv");
  json j = {{"format", kFormat},
            {"name", d.name},
            {"data", csv.filename().string()},
            {"mode", "kinematic"},
            {"payload", io::shapeJson(d.payload, "payload")},
            {"plate", io::shapeJson(d.plate, "plate")},
            {"outputs", d.outputs},
            {"notes", d.notes}};
  if (!d.noise.empty()) j["noise"] = d.noise;
  std::vector<std::string> names = {"t",  "x",  "y",  "z",  "qw", "qx", "qy",
                                    "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
  for (const auto& o : d.outputs) names.push_back(o);
  for (const auto& n : names) {
    if (!d.columns.count(n)) throw InputError(sidecarPath, "dataset has no column '" + n + "'");
  }
  io::writeJson(j, sidecar.string());
  std::ofstream out(csv);
  if (!out) throw InputError(csv.string(), "cannot open for writing");
  out.precision(std::numeric_limits<double>::max_digits10);
  for (std::size_t c = 0; c < names.size(); ++c) out << (c ? "," : "") << names[c];
  out << '\n';
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(d.size()); ++i) {
    for (std::size_t c = 0; c < names.size(); ++c)
      out << (c ? "," : "") << d.columns.at(names[c])[i];
    out << '\n';
  }
}

}  // namespace vcontact::formats
