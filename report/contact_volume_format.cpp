#include "report/contact_volume_format.hpp"

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

namespace vcontact::report {
namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json mat(const Eigen::Matrix3d& m) {
  return {vec(m.row(0).transpose()), vec(m.row(1).transpose()), vec(m.row(2).transpose())};
}

}  // namespace

nlohmann::json toJson(const volume::ContactVolume& cv) {
  nlohmann::json j;
  j["in_contact"] = cv.inContact();
  j["method"] = volume::methodName(cv.method);
  j["volume"] = cv.volume;
  j["centroid"] = vec(cv.p_WC);
  j["normal"] = vec(cv.n_W);
  j["depth"] = cv.depth;
  j["area"] = cv.area;
  j["r_gyr"] = cv.r_gyr;
  j["J_v"] = mat(cv.J_v);
  j["J_s"] = mat(cv.J_s);
  j["relative_error"] =
      std::isnan(cv.relative_error) ? nlohmann::json(nullptr) : nlohmann::json(cv.relative_error);
  j["units"] = {{"volume", "m^3"}, {"centroid", "m"}, {"depth", "m"}, {"area", "m^2"},
                {"r_gyr", "m"},    {"J_v", "m^5"},    {"J_s", "m^5"}};
  return j;
}

namespace {

/// The rows of one region's table (V to rel. error), each indented by `indent`.
void writeRows(std::ostream& os, const volume::ContactVolume& cv, const std::string& indent) {
  auto row = [&](const char* name, const std::string& value, const char* unit) {
    os << indent << "  " << std::left << std::setw(16) << name << value << (unit[0] ? "  " : "")
       << unit << '\n';
  };
  auto num = [](double v) {
    std::ostringstream s;
    s << std::setprecision(10) << v;
    return s.str();
  };
  auto v3 = [](const Eigen::Vector3d& v) {
    std::ostringstream s;
    s << std::setprecision(10) << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
    return s.str();
  };
  row("V", num(cv.volume), "m^3");
  row("centroid p_c", v3(cv.p_WC), "m");
  row("normal n", v3(cv.n_W), "");
  row("depth", num(cv.depth), "m");
  row("area A", num(cv.area), "m^2");
  row("r_gyr", num(cv.r_gyr), "m");
  for (int r = 0; r < 3; ++r) {
    row(r == 0 ? "J_v" : "", v3(cv.J_v.row(r).transpose()), r == 0 ? "m^5" : "");
  }
  for (int r = 0; r < 3; ++r) {
    row(r == 0 ? "J_s" : "", v3(cv.J_s.row(r).transpose()), r == 0 ? "m^5" : "");
  }
  row("rel. error",
      std::isnan(cv.relative_error) ? "exact for the given shapes" : num(cv.relative_error), "");
}

}  // namespace

std::string toTable(const volume::ContactVolume& cv) {
  std::ostringstream os;
  os << "contact volume (method " << volume::methodName(cv.method) << ")\n";
  if (!cv.inContact()) {
    os << "  no contact\n";
    return os.str();
  }
  writeRows(os, cv, "");
  return os.str();
}

nlohmann::json toJson(const volume::ContactPatches& contact) {
  nlohmann::json j = toJson(contact.aggregate);
  j["in_contact"] = contact.inContact();
  j["patches"] = nlohmann::json::array();
  for (const volume::ContactVolume& patch : contact.patches) {
    nlohmann::json p = toJson(patch);
    p.erase("units");  // as the aggregate's
    j["patches"].push_back(std::move(p));
  }
  return j;
}

std::string toTable(const volume::ContactPatches& contact) {
  std::ostringstream os;
  os << toTable(contact.aggregate);
  if (!contact.inContact()) return os.str();
  os << "  patches         " << contact.patches.size()
     << (contact.patches.size() == 1 ? " (the whole region)" : "") << '\n';
  if (contact.patches.size() == 1) return os.str();
  for (std::size_t k = 0; k < contact.patches.size(); ++k) {
    os << "  patch " << k + 1 << " of " << contact.patches.size() << '\n';
    writeRows(os, contact.patches[k], "  ");
  }
  return os.str();
}

}  // namespace vcontact::report
