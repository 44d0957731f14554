// vcontact compare | fit | diagnose as a user runs them: files written on good input; on every
// bad input of DATASET.md a message, exit code 2 and nothing in --out; the report renders
// every chart in headless Chromium.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "formats/dataset_file.hpp"
#include "formats/model_file.hpp"
#include "support/run_command.hpp"
#include "support/scratch_dir.hpp"
#include "validation/effect_cases.hpp"

namespace vcontact {
namespace {

namespace fs = std::filesystem;

using test::CommandResult;
using test::runCommand;

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

class ValidationCli : public ::testing::Test {
 public:
  void SetUp() override {
    scratch_.reset();
    const auto truth = test::trueModel({"stiffness", "coulomb", "viscous"});
    formats::writeDataset(test::syntheticDataset("drive", 200, truth, 3),
                          (dir_ / "drive.json").string());
    writeText(dir_ / "model.json",
              R"({"format": "vcontact.model/1", "effects": {"stiffness": {}, "coulomb": {}},
                  "fixed": ["coulomb.v_s"]})");
  }

  CommandResult run(const std::string& args) const {
    return runCommand(std::string(VCONTACT_BINARY) + " " + args, dir_ / "stderr.txt");
  }
  std::string standardArgs(const std::string& command) const {
    return command + " " + (dir_ / "drive.json").string() + " --model " +
           (dir_ / "model.json").string() + " --out " + out().string();
  }
  fs::path out() const { return dir_ / "out"; }

  // Replaces the cell of `column` on CSV line `line` (1-based, header = 1) or the header name.
  void editCsv(std::size_t line, const std::string& column, const std::string& value) const {
    std::istringstream in(readText(dir_ / "drive.csv"));
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    std::vector<std::string> header;
    std::stringstream hs(lines[0]);
    for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
    const auto col =
        static_cast<std::size_t>(std::find(header.begin(), header.end(), column) - header.begin());
    std::vector<std::string> cells;
    std::stringstream ls(lines[line - 1]);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    cells[col] = value;
    std::ostringstream row;
    for (std::size_t i = 0; i < cells.size(); ++i) row << (i ? "," : "") << cells[i];
    lines[line - 1] = row.str();
    std::ostringstream all;
    for (const auto& l : lines) all << l << '\n';
    writeText(dir_ / "drive.csv", all.str());
  }
  std::string cell(std::size_t line, const std::string& column) const {
    std::istringstream in(readText(dir_ / "drive.csv"));
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    std::vector<std::string> header, cells;
    std::stringstream hs(lines[0]), ls(lines[line - 1]);
    for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    return cells[static_cast<std::size_t>(std::find(header.begin(), header.end(), column) -
                                          header.begin())];
  }

  test::ScratchDir scratch_{"validation_cli"};
  const fs::path& dir_ = scratch_.path();
};

TEST_F(ValidationCli, CompareFitAndDiagnoseWriteTheirFiles) {
  const CommandResult c = run(standardArgs("compare"));
  ASSERT_EQ(c.exitCode, 0) << c.err;
  EXPECT_NE(c.out.find("sigma fx = 0.03 (from the sidecar's noise)"), std::string::npos) << c.out;
  for (const char* f : {"residuals.csv", "compare.json", "report.html"})
    EXPECT_TRUE(fs::exists(out() / f)) << f;
  const auto cmp = nlohmann::json::parse(readText(out() / "compare.json"));
  EXPECT_GT(cmp["chi"].get<double>(), 1.2);  // default parameters do not explain the data

  fs::remove_all(out());
  const CommandResult f = run(standardArgs("fit") + " --loss huber");
  ASSERT_EQ(f.exitCode, 0) << f.err;
  const auto fit = nlohmann::json::parse(readText(out() / "fit.json"));
  EXPECT_EQ(fit["loss"], "huber");
  EXPECT_EQ(fit["parameters"].size(), 3u);
  const dynamics::Model fitted = formats::readModelFile((out() / "model.json").string());
  EXPECT_NEAR(fitted.parameter("coulomb.mu"), 0.15, 0.02);  // viscous is missing: biased, close

  fs::remove_all(out());
  const CommandResult d = run(standardArgs("diagnose"));
  ASSERT_EQ(d.exitCode, 0) << d.err;
  const auto diag = nlohmann::json::parse(readText(out() / "diagnosis.json"));
  EXPECT_EQ(diag["verdict"], "viscous");
  // chi ≤ 1.2 explains the data, above does not (tests/validation/diagnose_test.cpp);
  // ΔBIC < −10 is "very strong" evidence on the Kass–Raftery scale.
  EXPECT_GT(diag["baseline"]["chi"].get<double>(), 1.2);
  EXPECT_TRUE(diag["baseline"]["rms"].contains("fx"));
  EXPECT_EQ(diag["ranking"][0]["effect"], "viscous");
  EXPECT_LT(diag["ranking"][0]["delta_bic"].get<double>(), -10.0);
  EXPECT_LE(diag["ranking"][0]["chi"].get<double>(), 1.2);
  ASSERT_FALSE(diag["where"].empty());
  EXPECT_FALSE(diag["where"][0]["regime"].get<std::string>().empty());
}

struct BadInput {
  const char* name;
  std::function<void(const ValidationCli&, const fs::path&)> spoil;
  const char* message;
};

TEST_F(ValidationCli, BadDatasetsAndModelFilesGiveAMessageExitTwoAndWriteNothing) {
  const fs::path ds = dir_ / "drive.json";
  const fs::path model = dir_ / "model.json";
  const std::vector<BadInput> cases = {
      {"sidecar not JSON", [&](auto&, auto&) { writeText(ds, "{\"format\": "); }, "not valid JSON"},
      {"wrong format",
       [&](auto&, auto&) {
         auto j = nlohmann::json::parse(readText(ds));
         j["format"] = "vcontact.dataset/9";
         writeText(ds, j.dump());
       },
       "format must be \"vcontact.dataset/1\""},
      {"missing data file", [&](auto&, auto&) { fs::remove(dir_ / "drive.csv"); }, "not found"},
      {"missing required column", [](auto& t, auto&) { t.editCsv(1, "qz", "qq"); },
       "missing required column 'qz'"},
      {"non-number", [](auto& t, auto&) { t.editCsv(5, "fx", "1.2.3"); }, "is not a number"},
      {"NaN", [](auto& t, auto&) { t.editCsv(5, "z", "nan"); }, "line 5"},
      {"time not increasing", [](auto& t, auto&) { t.editCsv(5, "t", t.cell(4, "t")); },
       "time must increase strictly"},
      {"quaternion far from unit", [](auto& t, auto&) { t.editCsv(5, "qw", "1.5"); }, "far from 1"},
      {"model not JSON", [&](auto&, auto&) { writeText(model, "{"); }, "not valid JSON"},
      {"model wrong format",
       [&](auto&, auto&) { writeText(model, R"({"format": "vcontact.model/0", "effects": {}})"); },
       "vcontact.model/1"},
      {"model unknown effect",
       [&](auto&, auto&) {
         writeText(model, R"({"format": "vcontact.model/1", "effects": {"glue": {}}})");
       },
       "unknown effect"},
      {"model value out of range",
       [&](auto&, auto&) {
         writeText(model,
                   R"({"format": "vcontact.model/1", "effects": {"stiffness": {"kv": -1}}})");
       },
       "outside its physical range"},
  };
  for (const auto& c : cases) {
    SetUp();
    c.spoil(*this, dir_);
    for (const char* command : {"compare", "diagnose"}) {
      const CommandResult r = run(standardArgs(command));
      EXPECT_EQ(r.exitCode, 2) << c.name << ' ' << command;
      EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
      EXPECT_FALSE(fs::exists(out())) << c.name << ' ' << command;
    }
  }
  SetUp();
  const CommandResult r = run(standardArgs("fit") + " --loss l1");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("unknown loss 'l1'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out()));
}

// A model whose prediction is not finite (issue 36: an expression effect b/(V − V)): compare,
// fit and diagnose stop with exit 2, a message naming the effect, its parameter and the
// sample, and nothing in --out (compare printed chi = -nan and wrote its files; fit and
// diagnose crashed).
TEST_F(ValidationCli, NonFinitePredictionExitsTwoNamingTheEffectAndWritesNothing) {
  writeText(dir_ / "model.json", R"json({"format": "vcontact.model/1", "effects": {
      "stiffness": {}, "coulomb": {},
      "broken": {"kind": "expression",
                 "parameters": {"b": {"value": 1, "unit": "N", "lower": 0, "upper": 10}},
                 "normal": "b/(V-V)"}}})json");
  for (const char* command : {"compare", "fit", "diagnose"}) {
    const CommandResult r = run(standardArgs(command));
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("effect 'broken' predicts a non-finite wrench (f"), std::string::npos)
        << command << ": " << r.err;
    EXPECT_NE(r.err.find("at sample 0 (t = 0 s) with broken.b = 1"), std::string::npos)
        << command << ": " << r.err;
    EXPECT_FALSE(fs::exists(out())) << command;
  }
}

TEST_F(ValidationCli, ReportRendersEveryChartInHeadlessChromium) {
  const fs::path chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium))
    GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  ASSERT_EQ(run(standardArgs("diagnose") + " --iterate").exitCode, 0);
  const std::string html = readText(out() / "report.html");
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org/2000/svg"));  // no network
  std::ptrdiff_t charts = 0;
  for (std::size_t p = html.find("<svg class=\"chart\""); p != std::string::npos;
       p = html.find("<svg class=\"chart\"", p + 1))
    ++charts;
  // Regime panels only for variables that vary: the drive slides at constant depth, so the
  // speed varies and the load and the penetration rate do not.
  std::ptrdiff_t panels = 0;
  for (std::size_t p = html.find("residual/σ against "); p != std::string::npos;
       p = html.find("residual/σ against ", p + 1))
    ++panels;
  panels /= 2;  // a chart writes its title twice: the <title> element and the heading text
  EXPECT_NE(html.find("against sliding speed"), std::string::npos);
  EXPECT_EQ(html.find("against normal load"), std::string::npos);
  EXPECT_EQ(html.find("against penetration rate"), std::string::npos);
  // chi chart + 2 outputs × (measured/model + residuals) + the regime panels.
  EXPECT_EQ(charts, 1 + 2 * 2 + panels);
  const fs::path profile = dir_ / "chromium-profile";
  const std::string cmd = "timeout 120 " + chromium.string() +
                          " --headless --no-sandbox --disable-gpu --disable-background-networking"
                          " --disable-component-update --disable-sync --no-first-run"
                          " --user-data-dir=" +
                          profile.string() + " --dump-dom file://" +
                          (out() / "report.html").string();
  const CommandResult r = runCommand(cmd, dir_ / "chromium.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("data-charts-rendered=\"(\\d+)/(\\d+)\"")))
      << r.out.substr(0, 500);
  EXPECT_EQ(std::stoi(m[1]), charts);
  EXPECT_EQ(std::stoi(m[2]), charts);
}

}  // namespace
}  // namespace vcontact
