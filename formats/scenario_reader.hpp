#pragma once
// The reading of a scenario file's JSON objects, shared by formats/scenario_file.cpp and
// formats/scenario_loads.cpp (internal to the formats layer): every message names the file,
// the place in it and what was expected (docs/SCENARIO.md).

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/input_ranges.hpp"
#include "io/shape_spec.hpp"

namespace vcontact::formats::detail {

/// Why `name` cannot stand in a CSV field or column name, "" when it can. The simulation's CSV
/// files are written without quoting (docs/SCENARIO.md, "Names"): a comma, a double quote,
/// a line break or another control character would split or join fields, so a name holding one
/// is refused where it is read; so is an empty name.
inline std::string csvNameProblem(const std::string& name) {
  if (name.empty()) return "expected a name, got an empty string";
  const auto bad = [](unsigned char u) { return u == ',' || u == '"' || u < 0x20 || u == 0x7f; };
  if (std::none_of(name.begin(), name.end(), [&](char c) { return bad(c); })) return "";
  std::ostringstream s;  // the name with its control characters as \xNN, so the message is one line
  s << "the name '" << std::hex;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      s << "\\x" << (u < 0x10 ? "0" : "") << int(u);
    } else {
      s << c;
    }
  }
  s << "' holds a comma, a double quote or a control character (a line break, a tab); a name "
       "goes into the CSV output unquoted, so it may hold none of them";
  return s.str();
}

// Reads one JSON object, knowing the file and the place in it for every message.
class Reader {
 public:
  Reader(const nlohmann::json& j, std::string source, std::string place)
      : j_(j), source_(std::move(source)), place_(std::move(place)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expectation) const {
    throw InputError(source_, at(key) + ": " + expectation);
  }
  std::string at(const std::string& key) const {
    return place_.empty() ? key : (key.empty() ? place_ : place_ + "." + key);
  }
  bool has(const std::string& key) const { return j_.contains(key); }
  const nlohmann::json& operator[](const std::string& key) const { return j_.at(key); }

  void allowOnly(std::initializer_list<const char*> keys) const {
    for (const auto& item : j_.items()) {
      // a plain variable, not a structured binding: clang 14 (the fuzz build) cannot capture one
      const std::string key = item.key();
      if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return key == k; }) !=
          keys.end()) {
        continue;
      }
      std::ostringstream s;
      s << "unknown key; expected one of:";
      for (const char* k : keys) s << ' ' << k;
      fail(key, s.str());
    }
  }

  double number(const std::string& key, double fallback, double lower, double upper) const {
    if (!has(key)) return fallback;
    const auto& v = j_[key];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lower ||
        v.get<double>() > upper) {
      std::ostringstream s;
      s << "expected a number in [" << lower << ", " << upper << "]";
      fail(key, s.str());
    }
    return v.get<double>();
  }
  double positive(const std::string& key, double fallback) const {
    const double v = number(key, fallback, 0.0, HUGE_VAL);
    if (!(v > 0.0)) fail(key, "expected a positive number");
    return v;
  }
  std::string text(const std::string& key) const {
    if (!has(key) || !j_[key].is_string()) fail(key, "expected a string");
    return j_[key].get<std::string>();
  }
  /// A name that goes into the simulation's CSV files (a body, pair, load or spring): a string
  /// checked by csvNameProblem.
  std::string name(const std::string& key) const {
    const std::string s = text(key);
    const std::string why = csvNameProblem(s);
    if (!why.empty()) fail(key, why);
    return s;
  }
  std::vector<double> numbers(const std::string& key) const {
    const auto& v = j_[key];
    std::vector<double> out;
    if (v.is_array()) {
      for (const auto& x : v) {
        if (!x.is_number() || !std::isfinite(x.get<double>())) fail(key, "expected numbers");
        out.push_back(x.get<double>());
      }
    }
    return out;
  }
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback) const {
    if (!has(key)) return fallback;
    const auto v = numbers(key);
    if (v.size() != 3) fail(key, "expected an array of 3 numbers");
    return {v[0], v[1], v[2]};
  }
  /// A vector each of whose components is within +-limit (io/input_ranges.hpp).
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback, double limit,
                          const char* unit) const {
    const Eigen::Vector3d v = vector3(key, fallback);
    if (v.cwiseAbs().maxCoeff() > limit) {
      std::ostringstream s;
      s << "expected components within +-" << limit << " " << unit << ", got [" << v.x() << ", "
        << v.y() << ", " << v.z() << "]";
      fail(key, s.str());
    }
    return v;
  }
  double inRange(const std::string& key, double fallback, const io::Range& range) const {
    if (has(key) && !j_[key].is_number()) fail(key, "expected a number");
    const double v = has(key) ? j_[key].get<double>() : fallback;
    const std::string why = io::outOfRange(v, range, "a number");
    if (!why.empty()) fail(key, why);
    return v;
  }
  bool flag(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!j_[key].is_boolean()) fail(key, "expected true or false");
    return j_[key].get<bool>();
  }
  Reader child(const std::string& key) const {
    if (!has(key) || !j_[key].is_object()) fail(key, "expected an object");
    return Reader(j_[key], source_, at(key));
  }
  const std::string& source() const { return source_; }

 private:
  const nlohmann::json& j_;
  std::string source_;
  std::string place_;
};

inline std::string resolve(const std::string& path, const std::string& base_dir) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(base_dir) / p).string();
}

inline Eigen::Isometry3d readPose(const Reader& r, const std::string& key) {
  if (!r.has(key)) return Eigen::Isometry3d::Identity();
  const auto& v = r[key];
  if (v.is_string()) return io::parsePose(v.get<std::string>(), r.source() + ": " + r.at(key));
  const auto n = r.numbers(key);
  if (n.size() != 3 && n.size() != 6 && n.size() != 7) {
    r.fail(key,
           "expected \"x,y,z[,roll,pitch,yaw | ,qw,qx,qy,qz]\" or an array of 3, 6 or 7 "
           "numbers");
  }
  std::ostringstream s;
  s.precision(17);
  for (std::size_t i = 0; i < n.size(); ++i) s << (i ? "," : "") << n[i];
  return io::parsePose(s.str(), r.source() + ": " + r.at(key));
}

}  // namespace vcontact::formats::detail
