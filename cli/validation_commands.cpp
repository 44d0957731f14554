// vcontact compare | fit | diagnose DATASET --model MODEL --out DIR, and vcontact synth:
// the validation workflow of issue #5. Every input is read and checked before DIR is
// created, so that bad input writes nothing.

#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/trajectory_commands.hpp"
#include "formats/candidates_file.hpp"
#include "formats/dataset_file.hpp"
#include "formats/model_file.hpp"
#include "geometry/error.hpp"
#include "io/file_names.hpp"
#include "io/input_ranges.hpp"
#include "io/json_file.hpp"
#include "io/output_file.hpp"
#include "io/output_folder.hpp"
#include "io/progress.hpp"
#include "io/shape_json.hpp"
#include "report/report_html.hpp"
#include "report/validation_output.hpp"
#include "validation/diagnose.hpp"
#include "validation/direct_estimates.hpp"
#include "validation/synthetic.hpp"

namespace vcontact::cli {
namespace {

namespace fs = std::filesystem;

struct ValidationOptions {
  std::string dataset, model, out;
  std::vector<std::string> datasets;  ///< fit and diagnose: every DATASET argument
  TrajectoryOptions trajectory;       ///< dynamic datasets
  std::string loss = "none";
  std::string candidates;  ///< diagnose: candidates file, empty for the library
  int maxIterations = 100;
  int starts = validation::FitOptions{}.designPoints;
  bool iterate = false;
};

validation::FitOptions fitOptions(const ValidationOptions& o, validation::Loss loss) {
  validation::FitOptions f;
  f.loss = loss;
  f.maxIterations = o.maxIterations;
  f.designPoints = o.starts;
  return f;
}

struct Inputs {
  formats::DatasetReadResult data;
  dynamics::Model model;
  validation::Loss loss;
};

// Reads and checks everything; creates nothing. `outputs` are the names of the files the
// command writes into --out: none may be one of its inputs.
// The options' own checks, before any file is read (a bad option is named first).
void checkOptions(const ValidationOptions& o) {
  try {  // the message names the option too
    io::checkOutputFolder(o.out);
  } catch (const InputError& e) {
    throw InputError("--out", e.what());
  }
  if (o.maxIterations < 1) throw InputError("--max-iterations", "expected a positive count");
  if (o.starts < 0) throw InputError("--starts", "expected a count >= 0");
}

Inputs readInputs(const ValidationOptions& o, const std::vector<std::string>& outputs) {
  checkOptions(o);
  Inputs in{
      formats::readDataset(o.dataset), formats::readModelFile(o.model),
      namingOptions({{"robust loss", "--loss"}}, [&] { return validation::parseLoss(o.loss); })};
  std::vector<std::string> paths;
  for (const std::string& name : outputs) paths.push_back((fs::path(o.out) / name).string());
  io::refuseOverwritingInputs(paths,
                              {{o.dataset, "the dataset's sidecar"},
                               {in.data.dataset.dataPath, "the dataset's CSV"},
                               {o.model, "the model file"},
                               {o.candidates, "the candidates file"}},
                              "--out");
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

// A command's files in its --out folder: all of them or none (io::OutputSet), each built only
// once the ones before it were written.
void addJson(io::OutputSet& files, const std::string& path, const nlohmann::json& j) {
  files.add(path, [&](std::ostream& out) { io::putJson(j, out); });
}

void addResiduals(io::OutputSet& files, const std::string& dir, const validation::Dataset& d,
                  const validation::Comparison& c) {
  files.add(dir + "/residuals.csv", [&](std::ostream& out) { report::putResidualsCsv(d, c, out); });
}

void addReport(io::OutputSet& files, const std::string& dir, const report::ReportInput& report) {
  files.add(dir + "/report.html", [&](std::ostream& out) { out << report::reportHtml(report); });
}

// Each direct estimate beside the fitted value it is compared with.
void printDirect(const std::vector<validation::DirectEstimate>& direct) {
  for (const auto& e : direct) {
    std::cout << "  direct estimate " << e.parameter << " = " << e.value << " (" << e.low << " .. "
              << e.high << ") " << e.unit << ": " << e.method;
    if (!std::isnan(e.fitted)) std::cout << "; fitted " << e.fitted << (e.far ? ", FAR" : "");
    std::cout << '\n';
  }
}

// Every parameter held: the model exactly as given.
validation::FitResult asGiven(validation::Replayer& replayer, const validation::NoiseLevels& noise,
                              dynamics::Model model) {
  model.setFixed(model.parameterNames());
  return validation::fit(replayer, noise, model);
}

void runCompare(const ValidationOptions& o) {
  const Inputs in = readInputs(o, {"residuals.csv", "compare.json", "report.html"});
  const validation::Dataset& d = in.data.dataset;
  if (d.mode == validation::DatasetMode::kDynamic)
    return runTrajectoryCompare(in.data, in.model, o.model, o.trajectory, o.out);
  const auto noise = validation::noiseLevels(d);
  validation::Replayer replayer(d);
  const validation::FitResult r = asGiven(replayer, noise, in.model);
  printNoise(noise);
  printComparison("model", r.comparison);
  io::OutputSet files(o.out);
  addResiduals(files, o.out, d, r.comparison);
  addJson(files, o.out + "/compare.json", report::comparisonJson(r.comparison, noise));
  addReport(files, o.out,
            {"compare",
             &d,
             noise,
             {{label(in.model.effectIds()), &r}},
             validation::failureWindows(d, r.comparison, r.prediction),
             nullptr});
  files.commit();
}

// The DATASET arguments expanded into `all` (o.dataset the first); true when they are
// trajectories: several datasets, a folder or a list, or one dynamic dataset.
bool trajectoryDatasets(ValidationOptions& o, std::vector<std::string>& all) {
  checkOptions(o);
  all = expandDatasets(o.datasets);
  o.dataset = all.front();
  return all.size() > 1 ||
         formats::readDataset(all.front()).dataset.mode == validation::DatasetMode::kDynamic;
}

// Trajectories: the trajectory fit.
bool trajectoryFit(ValidationOptions& o) {
  std::vector<std::string> all;
  if (!trajectoryDatasets(o, all)) return false;
  runTrajectoryFit(all, formats::readModelFile(o.model), o.trajectory, o.out);
  return true;
}

void runFit(ValidationOptions o) {
  if (trajectoryFit(o)) return;
  if (!o.trajectory.fold.empty() || !o.trajectory.merge.empty())
    throw InputError(o.trajectory.fold.empty() ? "--merge" : "--fold",
                     "applies to a trajectory fit of dynamic datasets; " + o.dataset +
                         " is kinematic (its fit has no folds)");
  const Inputs in = readInputs(o, {"model.json", "fit.json", "residuals.csv", "report.html"});
  const validation::Dataset& d = in.data.dataset;
  const auto noise = validation::noiseLevels(d);
  validation::Replayer replayer(d);
  const validation::FitResult before = asGiven(replayer, noise, in.model);
  validation::FitOptions options = fitOptions(o, in.loss);
  io::Progress progress("fit", 0.0, "");  // on a terminal only (io/progress.hpp)
  options.progress = [&](const std::string& what, int done, int total) {
    progress.update(what, done, total);
  };
  validation::FitResult r = validation::fit(replayer, noise, in.model, options);
  progress.finish();
  const std::vector<validation::DirectEstimate> direct = validation::estimatesBeside(d, noise, r);
  printNoise(noise);
  printComparison("as given", before.comparison);
  printComparison("fitted", r.comparison);
  for (const auto& p : r.parameters) {
    if (!p.fixed)
      std::cout << p.name << " = " << p.value << " ± " << p.stdError << ' ' << p.unit << '\n';
  }
  printDirect(direct);
  printWarnings(r.warnings);
  io::OutputSet files(o.out);
  addJson(files, o.out + "/model.json", formats::modelToJson(r.model));
  addJson(files, o.out + "/fit.json", report::fitJson(r, noise, in.loss, &direct));
  addResiduals(files, o.out, d, r.comparison);
  addReport(files, o.out,
            {"fit",
             &d,
             noise,
             {{"as given", &before}, {"fitted", &r}},
             validation::failureWindows(d, r.comparison, r.prediction),
             nullptr,
             &direct});
  files.commit();
}

// One stage's chi (fitted and held out), its verdict and why.
void printStage(const validation::DiagnosisStage& s) {
  printComparison(label(s.effects), s.baseline.comparison);
  std::cout << "  held-out chi2 " << s.heldOutChi2 << " (" << validation::kCvBlocks
            << " contiguous blocks)\n";
  printDirect(s.direct);
  printWarnings(s.baseline.warnings);
  std::cout << "  verdict: " << s.verdict << " (time: baseline fit " << s.seconds.baseline
            << " s, candidates " << s.seconds.candidates << " s, cross-validation "
            << s.seconds.crossValidation << " s, rig and residual " << s.seconds.rest << " s)\n";
  for (const auto& c : s.ranking) {
    if (!c.error.empty() || !(c.deltaBic < 0.0)) continue;
    std::cout << "    " << c.effect << ": chi " << c.fit.comparison.chi << ", delta BIC "
              << c.deltaBic;
    if (!std::isnan(c.heldOutChi2)) std::cout << ", held-out chi2 " << c.heldOutChi2;
    if (c.accepted) std::cout << ", accepted";
    if (!c.rejected.empty()) std::cout << ", rejected: " << c.rejected;
    if (!c.redundantWith.empty()) std::cout << ", redundant with " << c.redundantWith;
    std::cout << '\n';
  }
  for (const auto& r : s.rig) {
    if (r.deltaBic < 0.0) std::cout << "    rig " << r.text << ": delta BIC " << r.deltaBic << '\n';
  }
  if (s.kind != "unexplained") return;
  const auto& res = s.residual;
  std::cout << "  unexplained: the best candidate removes " << 100.0 * s.explainedFraction
            << " % of the residual chi2; noise accounts for " << 100.0 * res.noiseShare
            << " %\n  worst output " << res.output;
  if (res.frequency > 0.0)
    std::cout << ", rings at " << res.frequency << " Hz (" << 100.0 * res.frequencyShare
              << " % of its residual variance)";
  std::cout << '\n';
  for (const auto& [name, r] : res.correlation)
    std::cout << "    |residual| vs " << name << ": r = " << r << '\n';
}

void runDiagnose(ValidationOptions o) {
  std::vector<std::string> all;
  if (trajectoryDatasets(o, all)) {
    if (o.iterate)
      throw InputError("--iterate",
                       "applies to a kinematic dataset; for dynamic datasets diagnose again from "
                       "the model.json a verdict writes");
    return runTrajectoryDiagnose(all, formats::readModelFile(o.model), o.trajectory, o.candidates,
                                 o.out);
  }
  const Inputs in = readInputs(o, {"diagnosis.json", "model.json", "residuals.csv", "report.html"});
  validation::DiagnoseOptions options{fitOptions(o, in.loss), o.iterate};
  if (!o.candidates.empty()) options.candidates = formats::readCandidatesFile(o.candidates);
  const validation::Dataset& d = in.data.dataset;
  const auto noise = validation::noiseLevels(d);
  printNoise(noise);
  const auto start = std::chrono::steady_clock::now();
  io::Progress progress("diagnose", 0.0, "");  // on a terminal only (io/progress.hpp)
  options.progress = [&](const std::string& what, int done, int total) {
    progress.update(what, done, total);
  };
  const validation::Diagnosis diag = validation::diagnose(d, noise, in.model, options);
  progress.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // the failing windows and ranking shown are the final model's (the last stage's baseline)
  report::ReportInput report{"diagnose",
                             &d,
                             noise,
                             {},
                             diag.stages.back().where,
                             &diag.stages.back().ranking,
                             &diag.stages.back().direct};
  for (std::size_t i = 0; i < diag.stages.size(); ++i) {
    const auto& s = diag.stages[i];
    // every stage named by its whole model, so that the final model reads right
    const std::string stageLabel =
        label(s.effects) + (s.removed.empty() ? "" : " (- " + s.removed + ")");
    report.stages.push_back({stageLabel, &s.baseline, &s});
    printStage(s);
  }
  for (const auto& w : diag.stages.back().where) {
    std::cout << "  fails: " << w.output << " t = " << w.t0 << " .. " << w.t1 << " s (" << w.phase
              << "), chi " << w.chi << ", " << w.regime << '\n';
  }
  std::cout << "diagnose took " << seconds << " s\n";
  io::OutputSet files(o.out);
  addJson(files, o.out + "/diagnosis.json", report::diagnosisJson(diag, noise));
  addJson(files, o.out + "/model.json", formats::modelToJson(diag.final().model));
  addResiduals(files, o.out, d, diag.final().comparison);
  addReport(files, o.out, report);
  files.commit();
}

struct SynthOptions {
  std::string profile, model, out;
  std::size_t samples = 2000;
  unsigned seed = 1;
  double noiseScale = 1.0;
  std::string payload;       ///< mesh file replacing the profile's payload; empty: keep it
  std::string payloadScale;  ///< the mesh's scale to metres: a number or a unit name
  std::string motion;        ///< motion CSV replacing the profile's motion; empty: keep it
};

// The mesh payload of --payload as the sidecar will name it, read and checked now.
struct MeshPayload {
  nlohmann::json entry;  ///< {"mesh": absolute path, "scale": ...}
  geometry::Shape shape;
};

MeshPayload readMeshPayload(const SynthOptions& o) {
  MeshPayload p;
  p.entry = {{"mesh", fs::absolute(o.payload).lexically_normal().string()}};
  if (!o.payloadScale.empty()) {
    double number = 0.0;
    const auto [end, ec] = std::from_chars(o.payloadScale.data(),
                                           o.payloadScale.data() + o.payloadScale.size(), number);
    const bool isNumber = ec == std::errc() && end == o.payloadScale.data() + o.payloadScale.size();
    p.entry["scale"] = isNumber ? nlohmann::json(number) : nlohmann::json(o.payloadScale);
  }
  io::JsonShape s = io::parseShapeJson(p.entry, "--payload", "");
  printWarnings(s.warnings);
  p.shape = std::move(s.shape);
  return p;
}

// Replaces the profile's samples and kinematic columns by the motion CSV's.
void useMotion(validation::Dataset& d, const std::string& path) {
  formats::MotionReadResult m = formats::readMotionCsv(path);
  printWarnings(m.warnings);
  d.samples = std::move(m.dataset.samples);
  d.columns = std::move(m.dataset.columns);
  d.notes += "; motion from " + fs::path(path).filename().string();
}

void runSynth(const SynthOptions& o) {
  const fs::path out(o.out);
  if (!io::hasExtension(o.out, ".json")) {
    throw InputError("--out", "expected NAME.json (the sidecar)");
  }
  std::error_code ec;
  if (!out.parent_path().empty() && !fs::is_directory(out.parent_path(), ec)) {
    throw InputError("--out", out.parent_path().string() + " is not a directory" +
                                  (ec ? " (" + ec.message() + ")" : std::string()));
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
  io::refuseOverwritingInputs({o.out, fs::path(out).replace_extension(".csv").string()},
                              {{o.model, "the true model file"},
                               {o.motion, "the motion CSV"},
                               {o.payload, "the payload mesh"}},
                              "--out");
  if (!o.payloadScale.empty() && o.payload.empty())
    throw InputError("--payload-scale", "needs --payload (the mesh it scales)");
  const dynamics::Model truth = formats::readModelFile(o.model);
  validation::Dataset d =
      namingOptions({{"rig profile", "--profile"}, {"sample count", "--samples"}},
                    [&] { return validation::rigMotion(o.profile, o.samples); });
  std::optional<MeshPayload> mesh;
  if (!o.payload.empty()) {
    mesh = readMeshPayload(o);
    d.payload = mesh->shape;
    d.notes += "; payload " + fs::path(o.payload).filename().string();
  }
  if (!o.motion.empty()) useMotion(d, o.motion);
  for (auto& [output, sigma] : d.noise) sigma *= o.noiseScale;
  if (o.noiseScale == 0.0) d.noise.clear();
  d.name = out.stem().string();
  std::ostringstream notes;
  notes << d.notes << " (true model " << fs::path(o.model).filename().string() << ": "
        << formats::modelToJson(truth)["effects"].dump() << "; seed " << o.seed << ")";
  d.notes = notes.str();
  validation::synthesizeMeasurement(d, truth, o.seed);
  formats::writeDataset(d, o.out, mesh ? &mesh->entry : nullptr);
  std::cout << "wrote " << o.out << " (" << d.size() << " samples, profile " << o.profile << ")\n";
}

void addValidationOptions(CLI::App* cmd, const std::shared_ptr<ValidationOptions>& o, bool fits) {
  if (fits) {
    cmd->add_option("DATASET", o->datasets,
                    "dataset sidecars NAME.json (DATASET.md); several, a folder of them or a "
                    "list file (.txt, one per line) fit one model to many dynamic trials")
        ->required();
  } else {
    cmd->add_option("DATASET", o->dataset, "dataset sidecar NAME.json (DATASET.md)")->required();
  }
  cmd->add_option("--model", o->model, "model file (vcontact.model/1)")->required();
  cmd->add_option("--out", o->out, "output directory")->required();
  addTrajectoryOptions(cmd, o->trajectory, fits);
  if (!fits) return;
  cmd->add_option("--loss", o->loss, "none | huber | cauchy (robust loss on residual/sigma)")
      ->capture_default_str();
  cmd->add_option("--max-iterations", o->maxIterations, "Ceres iterations per fit")
      ->capture_default_str();
  cmd->add_option("--starts", o->starts,
                  "Halton design points screened besides the model's start (0: single start)")
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
  addFoldOptions(f, fit->trajectory);
  f->callback([fit] { runFit(*fit); });

  auto diag = std::make_shared<ValidationOptions>();
  CLI::App* g = app.add_subcommand(
      "diagnose",
      "Fit, then rank every missing effect by delta BIC (a kinematic dataset) or by "
      "cross-validated e_q (dynamic datasets, several at once): diagnosis.json, model.json, "
      "report.html.");
  addValidationOptions(g, diag, true);
  g->add_flag("--iterate", diag->iterate,
              "add the best effect and repeat until the verdict is none");
  g->add_option("--candidates", diag->candidates,
                "candidates file (vcontact.candidates/1): the effects to try, built-in ids and "
                "expression effects; default: every library effect");
  g->callback([diag] { runDiagnose(*diag); });

  auto synth = std::make_shared<SynthOptions>();
  CLI::App* s = app.add_subcommand(
      "synth",
      "Write a synthetic rig dataset: a rig profile replayed through a known model plus noise.");
  s->add_option(
       "--profile", synth->profile,
       "loading | impacts | friction-ramp | drive | dwell | slide-spin | rolling | indentation")
      ->required();
  s->add_option("--model", synth->model, "the true model file")->required();
  s->add_option("--out", synth->out, "dataset sidecar to write, NAME.json (NAME.csv beside it)")
      ->required();
  s->add_option("--samples", synth->samples, "number of samples")->capture_default_str();
  s->add_option("--seed", synth->seed, "noise seed")->capture_default_str();
  s->add_option("--noise-scale", synth->noiseScale,
                "multiplies the profile's noise sigma (0: an exact record, no noise)")
      ->capture_default_str();
  s->add_option("--payload", synth->payload,
                "a closed mesh file as the payload, in the payload frame (instead of the "
                "profile's punch or ball)");
  s->add_option("--payload-scale", synth->payloadScale,
                "the mesh's scale to metres: a number or a unit name (mm, in, ...)");
  auto* samples = s->get_option("--samples");
  s->add_option("--motion", synth->motion,
                "a motion CSV (t, x, y, z, qw, qx, qy, qz; optional vx, vy, vz, wx, wy, wz; "
                "docs/DATASET.md) instead of the profile's motion; the profile still gives "
                "the outputs and the noise")
      ->excludes(samples);
  s->callback([synth] { runSynth(*synth); });
}

}  // namespace vcontact::cli
