#include "cli/trajectory_commands.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "cli/commands.hpp"
#include "formats/candidates_file.hpp"
#include "formats/model_file.hpp"
#include "io/json_file.hpp"
#include "io/output_file.hpp"
#include "io/progress.hpp"
#include "report/trajectory_output.hpp"

namespace vcontact::cli {
namespace {

namespace fs = std::filesystem;

validation::TrajectorySettings settingsOf(const TrajectoryOptions& o) {
  validation::TrajectorySettings s;
  if (o.integrator == "dopri5")
    s.integrator = dynamics::Integrator::kDopri5;
  else if (o.integrator == "bdf")
    s.integrator = dynamics::Integrator::kBdf;
  else if (o.integrator == "discrete")
    s.integrator = dynamics::Integrator::kDiscrete;
  else
    throw InputError("--integrator",
                     "expected dopri5, bdf or discrete, got \"" + o.integrator + "\"");
  if (!(o.h >= 0.0) || !std::isfinite(o.h))
    throw InputError("--h", "expected a length in m >= 0 (0: half the payload's smallest extent)");
  if (o.h > 0.0) s.h = o.h;
  if (!(std::abs(o.plateOffset) <= validation::kPlateOffsetRange))
    throw InputError("--plate-offset", "expected a length within ±" +
                                           std::to_string(validation::kPlateOffsetRange) + " m");
  s.plateOffset = o.plateOffset;
  return s;
}

bool isDatasetSidecar(const fs::path& p) {
  try {
    const auto j = io::readJsonFile(p.string());
    return j.is_object() && j.contains("format") && j.at("format") == "vcontact.dataset/1";
  } catch (const InputError&) {
    return false;
  }
}

std::string modelLabel(const dynamics::Model& m) {
  std::string s;
  for (const auto& id : m.effectIds()) s += (s.empty() ? "" : " + ") + id;
  return s.empty() ? "(no effects)" : s;
}

void addText(io::OutputSet& files, const std::string& path, const std::string& text) {
  files.add(path, [text](std::ostream& out) { out << text; });
}

}  // namespace

void addTrajectoryOptions(CLI::App* cmd, TrajectoryOptions& o, bool fits) {
  cmd->add_option("--h", o.h,
                  "dynamic datasets: the length h of e_q = mean |dp|^2/h + mean theta^2, m "
                  "(0: half the payload's smallest extent)")
      ->capture_default_str();
  cmd->add_option("--integrator", o.integrator, "dynamic datasets: dopri5 | bdf | discrete")
      ->capture_default_str();
  cmd->add_option("--plate-offset", o.plateOffset,
                  "dynamic datasets: the plate's surface this far along its normal, m (a "
                  "trajectory fit's plate.offset; fit: its start, or its value with --fix-plate)")
      ->capture_default_str();
  if (!fits) return;
  cmd->add_option("--folds", o.folds,
                  "dynamic datasets: k of the k-fold cross-validation by trial (0: none)")
      ->capture_default_str();
  cmd->add_option("--global-evaluations", o.globalEvaluations,
                  "dynamic datasets: evaluations of the global search (NLopt DIRECT-L)")
      ->capture_default_str();
  cmd->add_option("--local-evaluations", o.localEvaluations,
                  "dynamic datasets: evaluations of each local polish (NLopt Subplex)")
      ->capture_default_str();
  cmd->add_option("--polishes", o.polishes,
                  "dynamic datasets: local polishes from the best distinct global points")
      ->capture_default_str();
  cmd->add_flag("--fix-plate", o.fixPlate,
                "dynamic datasets: do not fit the plate's offset along its normal");
}

void addFoldOptions(CLI::App* cmd, TrajectoryOptions& o) {
  cmd->add_option("--fold", o.fold,
                  "dynamic datasets: run one of the k+1 fits of the cross-validated fit alone, "
                  "\"all\" (the fit on all trials) or a fold 0..k-1 (fitted without it, its "
                  "trials scored), and write OUT/fold.json");
  cmd->add_option("--merge", o.merge,
                  "dynamic datasets: assemble the fit from fold.json parts (\"all\" and every "
                  "fold, made with the same datasets, model and options) instead of searching")
      ->expected(1, -1);
}

std::vector<std::string> expandDatasets(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const auto& a : args) {
    const fs::path p(a);
    if (fs::is_directory(p)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(p))
        if (e.path().extension() == ".json" && isDatasetSidecar(e.path()))
          found.push_back(e.path().string());
      if (found.empty()) throw InputError(a, "a folder with no dataset sidecar (*.json)");
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else if (p.extension() == ".txt" || p.extension() == ".list") {
      std::ifstream in(p);
      if (!in) throw InputError(a, "cannot read the list of datasets");
      std::string line;
      while (std::getline(in, line)) {
        line.erase(0, line.find_first_not_of(" \t\r"));
        line.erase(line.find_last_not_of(" \t\r") + 1);
        if (line.empty() || line[0] == '#') continue;
        const fs::path item(line);
        out.push_back((item.is_absolute() ? item : p.parent_path() / item).string());
      }
    } else {
      out.push_back(a);
    }
  }
  if (out.empty()) throw InputError("DATASET", "no dataset given");
  return out;
}

void runTrajectoryCompare(const formats::DatasetReadResult& data, const dynamics::Model& model,
                          const std::string& modelPath, const TrajectoryOptions& o,
                          const std::string& out) {
  const validation::TrajectorySettings settings = settingsOf(o);
  const validation::Trial trial = validation::prepareTrial(data.dataset);
  const validation::TrialEvaluation e = validation::evaluateTrial(model, trial, settings);
  const auto& r = e.errors;
  std::cout << "initial state: "
            << (trial.start.estimated
                    ? "free flight over " + std::to_string(trial.start.samplesUsed) +
                          " samples before the first contact (residual " +
                          std::to_string(trial.start.positionRms) + " m, " +
                          std::to_string(trial.start.attitudeRms) + " rad)"
                    : std::string("the velocity columns at the first sample"))
            << "\ne_q = " << r.e_q << " (position " << r.e_position << ", attitude " << r.e_attitude
            << ", h = " << r.h << " m)\nmean position error " << 100 * r.positionFraction
            << " % of the payload's size, mean rotation error " << r.rotationDeg
            << " deg, deepest penetration " << r.maxPenetration << " m\n";
  for (const auto& p : r.phases)
    std::cout << "  " << validation::trajectoryPhaseName(p.phase) << " (" << p.samples
              << " samples): e_q " << p.e_q << ", position " << 100 * p.positionFraction
              << " %, rotation " << p.rotationDeg << " deg\n";
  if (!std::isnan(r.partTime))
    std::cout << "the paths part " << r.partTime << " s after the start\n";
  if (!e.path.stopped.empty()) printWarnings({"the simulation stopped: " + e.path.stopped});
  io::OutputSet files(out);
  files.add(out + "/trajectory.csv",
            [&](std::ostream& s) { report::putTrajectoryCsv(trial, e, s); });
  files.add(out + "/compare.json", [&](std::ostream& s) {
    auto j = report::trajectoryCompareJson(trial, e);
    j["model"] = modelPath;
    j["plate_offset_m"] = settings.plateOffset;
    io::putJson(j, s);
  });
  addText(files, out + "/report.html", report::trajectoryReportHtml(trial, e, modelLabel(model)));
  files.commit();
}

namespace {

constexpr const char* kFoldFormat = "vcontact.fit-fold/1";

validation::TrajectoryFitOptions fitOptionsOf(const TrajectoryOptions& o) {
  validation::TrajectoryFitOptions options;
  options.settings = settingsOf(o);
  if (o.folds < 0 || o.folds == 1) throw InputError("--folds", "expected 0 (none) or k >= 2");
  if (o.globalEvaluations < 1 || o.localEvaluations < 0 || o.polishes < 0)
    throw InputError("--global-evaluations", "expected positive evaluation counts");
  options.folds = o.folds;
  options.globalEvaluations = o.globalEvaluations;
  options.localEvaluations = o.localEvaluations;
  options.starts = o.polishes;
  options.fitPlateOffset = !o.fixPlate;
  return options;
}

std::vector<validation::Trial> readTrials(const std::vector<std::string>& datasets) {
  std::vector<validation::Trial> trials;
  for (const auto& path : datasets) {
    formats::DatasetReadResult r = formats::readDataset(path);
    if (r.dataset.mode != validation::DatasetMode::kDynamic)
      throw InputError(path,
                       "a fit of several datasets takes dynamic datasets (\"mode\": "
                       "\"dynamic\"); this one is kinematic");
    trials.push_back(validation::prepareTrial(std::move(r.dataset)));
  }
  return trials;
}

// What fixes a fold's result besides its index: the trials in order, the start model and
// every option of the search. A part made with anything else is refused by --merge.
nlohmann::json foldIdentity(const std::vector<validation::Trial>& trials,
                            const dynamics::Model& model, const TrajectoryOptions& o) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& t : trials) names.push_back(t.data.name);
  return {{"trials", names},
          {"model", formats::modelToJson(model)},
          {"options",
           {{"h", o.h},
            {"integrator", o.integrator},
            {"plate_offset", o.plateOffset},
            {"folds", o.folds},
            {"global_evaluations", o.globalEvaluations},
            {"local_evaluations", o.localEvaluations},
            {"polishes", o.polishes},
            {"fix_plate", o.fixPlate}}}};
}

int parseFold(const std::string& text) {
  if (text == "all") return -1;
  std::size_t used = 0;
  int fold = -2;
  try {
    fold = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || fold < 0)
    throw InputError("--fold", "expected \"all\" or a fold number 0..k-1, got \"" + text + "\"");
  return fold;
}

// NaN and infinities are written as null (JSON has no such numbers) and read back as NaN.
double numberOrNaN(const nlohmann::json& j) {
  return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json foldJson(const validation::TrajectoryFoldFit& p,
                        const std::vector<validation::Trial>& trials,
                        const nlohmann::json& identity) {
  nlohmann::json params = nlohmann::json::array(), held = nlohmann::json::array();
  for (const auto& q : p.parameters)
    params.push_back(
        {{"name", q.name},
         {"unit", q.unit},
         {"value", q.value},
         {"std_error", p.fold < 0 && std::isfinite(q.stdError) ? nlohmann::json(q.stdError)
                                                               : nlohmann::json()}});
  for (std::size_t j = 0; j < p.heldOut.size(); ++j)
    held.push_back({{"trial", p.heldOut[j]},
                    {"name", trials[p.heldOut[j]].data.name},
                    {"e_q", p.heldOutLoss[j]}});
  return {{"format", kFoldFormat},
          {"fold", p.fold < 0 ? nlohmann::json("all") : nlohmann::json(p.fold)},
          {"folds", p.folds},
          {"identity", identity},
          {"u", p.u},
          {"parameters", params},
          {"held_out", held},
          {"evaluations", p.evaluations},
          {"trial_simulations", p.trialSimulations},
          {"wall_s", p.seconds},
          {"cpu_s", p.cpuSeconds}};
}

validation::TrajectoryFoldFit readFold(const std::string& path, const nlohmann::json& identity,
                                       const std::vector<validation::Trial>& trials) {
  const nlohmann::json j = io::readJsonFile(path);
  if (!j.is_object() || j.value("format", "") != kFoldFormat)
    throw InputError(path, std::string("not a fold part (expected \"format\": \"") + kFoldFormat +
                               "\", as `vcontact fit --fold` writes)");
  const auto& id = j.at("identity");
  for (const char* key : {"trials", "model", "options"})
    if (id.value(key, nlohmann::json()) != identity.at(key))
      throw InputError(path, std::string("made with other ") + key +
                                 " than this fit's (the same datasets in the same order, model "
                                 "and options are needed)");
  validation::TrajectoryFoldFit p;
  try {
    p.fold = j.at("fold") == "all" ? -1 : j.at("fold").get<int>();
    p.folds = j.at("folds").get<int>();
    for (const auto& v : j.at("u")) p.u.push_back(v.get<double>());
    for (const auto& q : j.at("parameters")) {
      validation::TrajectoryParameter tp;
      tp.name = q.at("name").get<std::string>();
      tp.value = q.at("value").get<double>();
      tp.stdError = numberOrNaN(q.at("std_error"));
      p.parameters.push_back(tp);
    }
    for (const auto& h : j.at("held_out")) {
      const auto trial = h.at("trial").get<std::size_t>();
      if (trial >= trials.size()) throw InputError(path, "held_out: a trial index out of range");
      p.heldOut.push_back(trial);
      p.heldOutLoss.push_back(numberOrNaN(h.at("e_q")));
    }
    p.evaluations = j.at("evaluations").get<long>();
    p.trialSimulations = j.at("trial_simulations").get<long>();
    p.seconds = j.at("wall_s").get<double>();
    p.cpuSeconds = j.at("cpu_s").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path,
                     std::string("a fold part with a missing or mistyped field: ") + e.what());
  }
  return p;
}

// The parts in the order assembleTrajectoryFit takes: "all", then folds 0 … k−1.
validation::TrajectoryFitResult mergeFolds(const std::vector<validation::Trial>& trials,
                                           const dynamics::Model& model,
                                           const validation::TrajectoryFitOptions& options,
                                           const TrajectoryOptions& o) {
  const nlohmann::json identity = foldIdentity(trials, model, o);
  std::optional<validation::TrajectoryFoldFit> all;
  std::vector<std::optional<validation::TrajectoryFoldFit>> folds(
      validation::crossValidates(options, trials.size()) ? static_cast<std::size_t>(o.folds) : 0);
  for (const auto& path : o.merge) {
    validation::TrajectoryFoldFit p = readFold(path, identity, trials);
    if (p.fold >= static_cast<int>(folds.size()))
      throw InputError(path, "fold " + std::to_string(p.fold) + " of " + std::to_string(p.folds) +
                                 ", beyond this fit's " + std::to_string(folds.size()) + " folds");
    auto& slot = p.fold < 0 ? all : folds[static_cast<std::size_t>(p.fold)];
    if (slot)
      throw InputError(path, "a second part of fold " +
                                 (p.fold < 0 ? std::string("\"all\"") : std::to_string(p.fold)));
    slot = std::move(p);
  }
  if (!all) throw InputError("--merge", "the fit on all trials (fold \"all\") is missing");
  std::vector<validation::TrajectoryFoldFit> ordered;
  for (std::size_t f = 0; f < folds.size(); ++f) {
    if (!folds[f]) throw InputError("--merge", "fold " + std::to_string(f) + " is missing");
    ordered.push_back(std::move(*folds[f]));
  }
  return validation::assembleTrajectoryFit(trials, model, options, *all, ordered);
}

void writeFit(const validation::TrajectoryFitResult& r,
              const validation::TrajectoryFitOptions& options, const std::string& out) {
  std::cout << "mean e_q: start " << r.meanStart << ", fitted " << r.meanFitted;
  if (!std::isnan(r.meanHeldOut))
    std::cout << ", " << options.folds << "-fold cross-validated " << r.meanHeldOut;
  std::cout << "\n";
  for (const auto& p : r.parameters)
    std::cout << p.name << " = " << p.value << " ± " << p.stdError << ' ' << p.unit << " ("
              << report::standardErrorMethod(p) << ")" << '\n';
  std::cout << r.evaluations << " evaluations (" << r.trialSimulations << " trial simulations) in "
            << r.seconds << " s wall, " << r.cpuSeconds << " s CPU\n";
  printWarnings(r.warnings);
  io::OutputSet files(out);
  files.add(out + "/model.json",
            [&](std::ostream& s) { io::putJson(formats::modelToJson(r.model), s); });
  files.add(out + "/fit.json",
            [&](std::ostream& s) { io::putJson(report::trajectoryFitJson(r, options), s); });
  files.add(out + "/trials.csv", [&](std::ostream& s) { report::putTrialsCsv(r, s); });
  addText(files, out + "/report.html", report::trajectoryFitReportHtml(r, options));
  files.commit();
}

}  // namespace

void runTrajectoryFit(const std::vector<std::string>& datasets, const dynamics::Model& model,
                      const TrajectoryOptions& o, const std::string& out) {
  validation::TrajectoryFitOptions options = fitOptionsOf(o);
  if (!o.fold.empty() && !o.merge.empty())
    throw InputError("--merge", "excludes --fold (a part is made, or parts are merged)");
  const int fold = o.fold.empty() ? -2 : parseFold(o.fold);
  const std::vector<validation::Trial> trials = readTrials(datasets);
  if (options.folds > static_cast<int>(trials.size()))
    throw InputError("--folds", std::to_string(options.folds) + " folds need as many trials; " +
                                    std::to_string(trials.size()) + " given");
  if (fold >= 0 && fold >= options.folds)
    throw InputError("--fold", "fold " + std::to_string(fold) + " of a " +
                                   std::to_string(options.folds) + "-fold cross-validation (" +
                                   (options.folds ? "folds 0.." + std::to_string(options.folds - 1)
                                                  : std::string("--folds 0: only \"all\"")) +
                                   ")");
  if (!o.merge.empty()) {
    std::cout << "assembling the fit of " << modelLabel(model) << " to " << trials.size()
              << " trials from " << o.merge.size() << " parts\n";
    return writeFit(mergeFolds(trials, model, options, o), options, out);
  }
  std::cout << "fitting " << modelLabel(model) << " to " << trials.size() << " trials";
  if (fold != -2) std::cout << (fold < 0 ? " (all trials alone)" : " (fold " + o.fold + " alone)");
  std::cout << "\n";
  io::Progress progress("fit", 0.0, "");
  options.progress = [&](const std::string& what, int done, int total) {
    progress.update(what, done, total);
  };
  if (fold != -2) {
    const validation::TrajectoryFoldFit p =
        validation::fitTrajectoryFold(trials, model, options, fold);
    progress.finish();
    for (const auto& q : p.parameters)
      std::cout << q.name << " = " << q.value << ' ' << q.unit << '\n';
    for (std::size_t j = 0; j < p.heldOut.size(); ++j)
      std::cout << "held out " << trials[p.heldOut[j]].data.name << ": e_q " << p.heldOutLoss[j]
                << '\n';
    std::cout << p.evaluations << " evaluations in " << p.seconds << " s wall\n";
    io::OutputSet files(out);
    files.add(out + "/fold.json", [&](std::ostream& s) {
      io::putJson(foldJson(p, trials, foldIdentity(trials, model, o)), s);
    });
    return files.commit();
  }
  const validation::TrajectoryFitResult r = validation::fitTrajectories(trials, model, options);
  progress.finish();
  writeFit(r, options, out);
}

void runTrajectoryDiagnose(const std::vector<std::string>& datasets, const dynamics::Model& model,
                           const TrajectoryOptions& o, const std::string& candidates,
                           const std::string& out) {
  validation::TrajectoryDiagnoseOptions options;
  options.fit = fitOptionsOf(o);
  if (!candidates.empty()) options.candidates = formats::readCandidatesFile(candidates);
  const std::vector<validation::Trial> trials = readTrials(datasets);
  std::cout << "diagnosing " << modelLabel(model) << " on " << trials.size() << " trials, "
            << options.fit.folds << "-fold cross-validated\n";
  io::Progress progress("diagnose", 0.0, "");
  options.progress = [&](const std::string& what, int done, int total) {
    progress.update(what, done, total);
  };
  const validation::TrajectoryDiagnosis d =
      validation::diagnoseTrajectories(trials, model, options);
  progress.finish();
  std::cout << "baseline: mean e_q fitted " << d.baseline.meanFitted << ", held out "
            << d.baseline.meanHeldOut << "\n";
  for (const auto& c : d.ranking) {
    std::cout << "  " << c.effect << ": ";
    if (!c.error.empty()) {
      std::cout << "failed: " << c.error << "\n";
      continue;
    }
    std::cout << "held out " << c.fit.meanHeldOut << ", change " << c.meanDelta << " ± "
              << c.deltaStdError << " per trial" << (c.accepted ? " (accepted)" : "") << "\n";
  }
  std::cout << "verdict: " << d.verdict << "\n";
  for (const auto& u : d.unexplained)
    std::cout << "unexplained: " << u.name << " (e_q " << u.e_q << " at best, by " << u.model
              << "; fails in " << u.phase << "): " << u.hint << "\n";
  std::cout << "in " << d.seconds << " s wall\n";
  const validation::TrajectoryFitResult& chosen = d.final();
  printWarnings(chosen.warnings);
  io::OutputSet files(out);
  files.add(out + "/diagnosis.json", [&](std::ostream& s) {
    io::putJson(report::trajectoryDiagnosisJson(d, options.fit), s);
  });
  files.add(out + "/model.json",
            [&](std::ostream& s) { io::putJson(formats::modelToJson(chosen.model), s); });
  files.add(out + "/trials.csv", [&](std::ostream& s) { report::putTrialsCsv(chosen, s); });
  addText(files, out + "/report.html", report::trajectoryDiagnosisReportHtml(d, options.fit));
  files.commit();
}

}  // namespace vcontact::cli
