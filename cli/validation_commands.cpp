// vcontact compare | fit | diagnose DATASET --model MODEL --out DIR, and vcontact synth:
// the validation workflow of issue #5. Every input is read and checked before DIR is
// created, so that bad input writes nothing.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands.hpp"
#include "formats/dataset_file.hpp"
#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "report/report_html.hpp"
#include "report/validation_output.hpp"
#include "validation/diagnose.hpp"
#include "validation/synthetic.hpp"

namespace vcontact::cli {
namespace {

namespace fs = std::filesystem;

struct ValidationOptions {
  std::string dataset, model, out;
  std::string loss = "none";
  int maxIterations = 100;
  bool iterate = false;
};

struct Inputs {
  formats::DatasetReadResult data;
  dynamics::Model model;
  validation::Loss loss;
};

// Reads and checks everything; creates nothing.
Inputs readInputs(const ValidationOptions& o) {
  if (fs::exists(o.out) && !fs::is_directory(o.out)) {
    throw InputError("--out", o.out + " exists and is not a directory");
  }
  if (o.maxIterations < 1) throw InputError("--max-iterations", "expected a positive count");
  Inputs in{
      formats::readDataset(o.dataset), formats::readModelFile(o.model),
      namingOptions({{"robust loss", "--loss"}}, [&] { return validation::parseLoss(o.loss); })};
  printWarnings(in.data.warnings);
  return in;
}

void printNoise(const validation::NoiseLevels& noise) {
  for (const auto& [o, n] : noise) {
    std::cout << "sigma " << o << " = " << n.sigma
              << (n.estimated
                      ? " (estimated from the data: 1.4826 MAD of second differences / sqrt(6))"
                      : " (from the sidecar's noise)")
              << '\n';
  }
}

void printComparison(const std::string& label, const validation::Comparison& c) {
  std::cout << label << ": chi = " << c.chi << ", rms:";
  for (const auto& o : c.outputs) std::cout << ' ' << o.output << " = " << o.rms;
  std::cout << '\n';
}

std::string joined(const std::vector<std::string>& ids, const char* sep) {
  std::ostringstream s;
  for (std::size_t i = 0; i < ids.size(); ++i) s << (i ? sep : "") << ids[i];
  return s.str();
}

std::string label(const std::vector<std::string>& effects) {
  return effects.empty() ? std::string("(no effects)") : joined(effects, " + ");
}

void writeReport(const std::string& dir, const report::ReportInput& report) {
  report::writeReportHtml(report, dir + "/report.html");
}

// Every parameter held: the model exactly as given.
validation::FitResult asGiven(validation::Replayer& replayer, const validation::NoiseLevels& noise,
                              dynamics::Model model) {
  model.setFixed(model.parameterNames());
  return validation::fit(replayer, noise, model);
}

void runCompare(const ValidationOptions& o) {
  const Inputs in = readInputs(o);
  const validation::Dataset& d = in.data.dataset;
  const auto noise = validation::noiseLevels(d);
  validation::Replayer replayer(d);
  const validation::FitResult r = asGiven(replayer, noise, in.model);
  printNoise(noise);
  printComparison("model", r.comparison);
  fs::create_directories(o.out);
  report::writeResidualsCsv(d, r.comparison, o.out + "/residuals.csv");
  io::writeJson(report::comparisonJson(r.comparison, noise), o.out + "/compare.json");
  writeReport(o.out, {"compare",
                      &d,
                      noise,
                      {{label(in.model.effectIds()), &r}},
                      validation::failureWindows(d, r.comparison, r.prediction),
                      nullptr});
}

void runFit(const ValidationOptions& o) {
  const Inputs in = readInputs(o);
  const validation::Dataset& d = in.data.dataset;
  const auto noise = validation::noiseLevels(d);
  validation::Replayer replayer(d);
  const validation::FitResult before = asGiven(replayer, noise, in.model);
  const validation::FitResult r =
      validation::fit(replayer, noise, in.model, {in.loss, o.maxIterations});
  printNoise(noise);
  printComparison("as given", before.comparison);
  printComparison("fitted", r.comparison);
  for (const auto& p : r.parameters) {
    if (!p.fixed)
      std::cout << p.name << " = " << p.value << " ± " << p.stdError << ' ' << p.unit << '\n';
  }
  printWarnings(r.warnings);
  fs::create_directories(o.out);
  io::writeJson(formats::modelToJson(r.model), o.out + "/model.json");
  io::writeJson(report::fitJson(r, noise, in.loss), o.out + "/fit.json");
  report::writeResidualsCsv(d, r.comparison, o.out + "/residuals.csv");
  writeReport(o.out, {"fit",
                      &d,
                      noise,
                      {{"as given", &before}, {"fitted", &r}},
                      validation::failureWindows(d, r.comparison, r.prediction),
                      nullptr});
}

void runDiagnose(const ValidationOptions& o) {
  const Inputs in = readInputs(o);
  const validation::Dataset& d = in.data.dataset;
  const auto noise = validation::noiseLevels(d);
  printNoise(noise);
  const auto start = std::chrono::steady_clock::now();
  const validation::Diagnosis diag =
      validation::diagnose(d, noise, in.model, {{in.loss, o.maxIterations}, o.iterate});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report::ReportInput report{
      "diagnose", &d, noise, {}, diag.stages.front().where, &diag.stages.front().ranking};
  for (std::size_t i = 0; i < diag.stages.size(); ++i) {
    const auto& s = diag.stages[i];
    const std::string stageLabel = i == 0               ? label(s.effects)
                                   : !s.removed.empty() ? "- " + s.removed
                                                        : "+ " + diag.stages[i - 1].verdict;
    report.stages.push_back({stageLabel, &s.baseline});
    printComparison(label(s.effects), s.baseline.comparison);
    std::cout << "  verdict: " << s.verdict;
    if (!s.ranking.empty() && s.ranking.front().error.empty()) {
      std::cout << " (best: " << s.ranking.front().effect << ", chi "
                << s.ranking.front().fit.comparison.chi << ", delta BIC "
                << s.ranking.front().deltaBic << ")";
    }
    std::cout << '\n';
  }
  for (const auto& w : diag.stages.front().where) {
    std::cout << "  fails: " << w.output << " t = " << w.t0 << " .. " << w.t1 << " s, chi " << w.chi
              << ", " << w.regime << '\n';
  }
  std::cout << "diagnose took " << seconds << " s\n";
  fs::create_directories(o.out);
  io::writeJson(report::diagnosisJson(diag, noise), o.out + "/diagnosis.json");
  io::writeJson(formats::modelToJson(diag.final().model), o.out + "/model.json");
  report::writeResidualsCsv(d, diag.final().comparison, o.out + "/residuals.csv");
  writeReport(o.out, report);
}

struct SynthOptions {
  std::string profile, model, out;
  std::size_t samples = 2000;
  unsigned seed = 1;
  double noiseScale = 1.0;
};

void runSynth(const SynthOptions& o) {
  const fs::path out(o.out);
  if (out.extension() != ".json") throw InputError("--out", "expected NAME.json (the sidecar)");
  if (!out.parent_path().empty() && !fs::is_directory(out.parent_path())) {
    throw InputError("--out", out.parent_path().string() + " is not a directory");
  }
  // A thousand times the profile's noise already buries every force in it.
  if (!(o.noiseScale >= 0.0 && o.noiseScale <= 1e3)) {
    throw InputError("--noise-scale",
                     "expected a number in [0, 1000], got " + std::to_string(o.noiseScale));
  }
  if (o.samples < io::kMinSamples || o.samples > io::kMaxSamples) {
    throw InputError("--samples", "expected a sample count in [" + std::to_string(io::kMinSamples) +
                                      ", " + std::to_string(io::kMaxSamples) + "], got " +
                                      std::to_string(o.samples));
  }
  const dynamics::Model truth = formats::readModelFile(o.model);
  validation::Dataset d =
      namingOptions({{"rig profile", "--profile"}, {"sample count", "--samples"}},
                    [&] { return validation::rigMotion(o.profile, o.samples); });
  for (auto& [output, sigma] : d.noise) sigma *= o.noiseScale;
  if (o.noiseScale == 0.0) d.noise.clear();
  d.name = out.stem().string();
  std::ostringstream notes;
  notes << d.notes << " (true model " << fs::path(o.model).filename().string() << ": "
        << formats::modelToJson(truth)["effects"].dump() << "; seed " << o.seed << ")";
  d.notes = notes.str();
  validation::synthesizeMeasurement(d, truth, o.seed);
  formats::writeDataset(d, o.out);
  std::cout << "wrote " << o.out << " (" << d.size() << " samples, profile " << o.profile << ")\n";
}

void addValidationOptions(CLI::App* cmd, const std::shared_ptr<ValidationOptions>& o, bool fits) {
  cmd->add_option("DATASET", o->dataset, "dataset sidecar NAME.json (DATASET.md)")->required();
  cmd->add_option("--model", o->model, "model file (vcontact.model/1)")->required();
  cmd->add_option("--out", o->out, "output directory")->required();
  if (!fits) return;
  cmd->add_option("--loss", o->loss, "none | huber | cauchy (robust loss on residual/sigma)")
      ->capture_default_str();
  cmd->add_option("--max-iterations", o->maxIterations, "Ceres iterations per fit")
      ->capture_default_str();
}

}  // namespace

void addValidationCommands(CLI::App& app) {
  auto compare = std::make_shared<ValidationOptions>();
  CLI::App* c = app.add_subcommand(
      "compare",
      "Replay a dataset through a model: residuals.csv, compare.json (chi, RMS), report.html.");
  addValidationOptions(c, compare, false);
  c->callback([compare] { runCompare(*compare); });

  auto fit = std::make_shared<ValidationOptions>();
  CLI::App* f = app.add_subcommand("fit",
                                   "Fit the model's free parameters to a dataset: model.json, "
                                   "fit.json, residuals.csv, report.html.");
  addValidationOptions(f, fit, true);
  f->callback([fit] { runFit(*fit); });

  auto diag = std::make_shared<ValidationOptions>();
  CLI::App* g = app.add_subcommand(
      "diagnose",
      "Fit, then rank every missing effect by delta BIC: diagnosis.json, model.json, report.html.");
  addValidationOptions(g, diag, true);
  g->add_flag("--iterate", diag->iterate,
              "add the best effect and repeat until the verdict is none");
  g->callback([diag] { runDiagnose(*diag); });

  auto synth = std::make_shared<SynthOptions>();
  CLI::App* s = app.add_subcommand(
      "synth",
      "Write a synthetic rig dataset: a rig profile replayed through a known model plus noise.");
  s->add_option("--profile", synth->profile,
                "loading | impacts | friction-ramp | drive | dwell | slide-spin | rolling")
      ->required();
  s->add_option("--model", synth->model, "the true model file")->required();
  s->add_option("--out", synth->out, "dataset sidecar to write, NAME.json (NAME.csv beside it)")
      ->required();
  s->add_option("--samples", synth->samples, "number of samples")->capture_default_str();
  s->add_option("--seed", synth->seed, "noise seed")->capture_default_str();
  s->add_option("--noise-scale", synth->noiseScale, "multiplies the profile's noise sigma")
      ->capture_default_str();
  s->callback([synth] { runSynth(*synth); });
}

}  // namespace vcontact::cli
