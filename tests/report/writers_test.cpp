// The report layer's file writers: what they write, and that a file that cannot be opened is
// an InputError naming it (report.html used to be written through an unchecked stream).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "geometry/error.hpp"
#include "io/json_file.hpp"
#include "report/depth_map_csv.hpp"
#include "report/friction_map_csv.hpp"
#include "report/report_html.hpp"

namespace vcontact::report {
namespace {

namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  return fs::temp_directory_path() / ("vcontact_writers_" + std::to_string(getpid()) + "_" + name);
}

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The source of the InputError that `write` throws, or "" when it throws none.
template <class Write>
std::string errorSource(Write write) {
  try {
    write();
  } catch (const InputError& e) {
    return e.source();
  }
  return "";
}

TEST(ReportWriters, AFileThatCannotBeOpenedIsAnInputErrorNamingIt) {
  const std::string path = (tempFile("no_such_folder") / "out").string();
  EXPECT_EQ(errorSource([&] { writeJson(nlohmann::json::object(), path); }), path);
  // The HTML is not built when the file does not open, so an empty input is never read.
  EXPECT_EQ(errorSource([&] { writeReportHtml(ReportInput{}, path); }), path);
  EXPECT_EQ(errorSource([&] { writeDepthMapCsv(volume::DepthField{}, path); }), path);
  EXPECT_EQ(errorSource([&] { writeFrictionMapCsv(validation::FrictionMap{}, path); }), path);
}

TEST(ReportWriters, DepthMapCsvHasOneRowPerColumnAtFullPrecision) {
  const fs::path path = tempFile("depth.csv");
  volume::DepthField field;
  field.points_W = {{0.1, -0.2, 0.3}, {1.0 / 3.0, 0.0, -1e-9}};
  field.depth = {2e-6, 0.7e-6};
  writeDepthMapCsv(field, path.string());
  EXPECT_EQ(contents(path),
            "x_m,y_m,z_m,delta_m\n"
            "0.10000000000000001,-0.20000000000000001,0.29999999999999999,1.9999999999999999e-06\n"
            "0.33333333333333331,0,-1.0000000000000001e-09,6.9999999999999997e-07\n");
  fs::remove(path);
}

TEST(ReportWriters, FrictionMapCsvLeavesTheExactColumnsEmptyWithoutAClosedForm) {
  const fs::path path = tempFile("friction.csv");
  validation::FrictionMap map;
  map.f_n = 10.0;
  map.mu = 0.5;
  map.R = 0.01;
  map.rows.push_back({0.0, 0.0, 100.0, 0.0, 0.0, 1.0, 2.0, validation::PunchFriction{0.0, 0.5}});
  map.rows.push_back({1.0, 1.0, 100.0, 3.0, 4.0, 0.0, 0.0, std::nullopt});
  writeFrictionMapCsv(map, path.string());
  const std::string csv = contents(path);
  // Exact columns are μ f_n F/μN and μ f_n R M/μNR; a zero lumped value has no ratio (nan).
  EXPECT_NE(csv.find("\n0,0,100,10,0,0,0,1,2,0.025,nan,0.5\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n1,1,100,10,3,4,,0,0,,0.75,nan\n"), std::string::npos) << csv;
  fs::remove(path);
}

}  // namespace
}  // namespace vcontact::report
