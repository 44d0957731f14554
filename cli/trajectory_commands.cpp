#include "cli/trajectory_commands.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/commands.hpp"
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
    io::putJson(j, s);
  });
  addText(files, out + "/report.html", report::trajectoryReportHtml(trial, e, modelLabel(model)));
  files.commit();
}

void runTrajectoryFit(const std::vector<std::string>& datasets, const dynamics::Model& model,
                      const TrajectoryOptions& o, const std::string& out) {
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
  std::vector<validation::Trial> trials;
  for (const auto& path : datasets) {
    formats::DatasetReadResult r = formats::readDataset(path);
    if (r.dataset.mode != validation::DatasetMode::kDynamic)
      throw InputError(path,
                       "a fit of several datasets takes dynamic datasets (\"mode\": "
                       "\"dynamic\"); this one is kinematic");
    trials.push_back(validation::prepareTrial(std::move(r.dataset)));
  }
  if (options.folds > static_cast<int>(trials.size()))
    throw InputError("--folds", std::to_string(options.folds) + " folds need as many trials; " +
                                    std::to_string(trials.size()) + " given");
  std::cout << "fitting " << modelLabel(model) << " to " << trials.size() << " trials\n";
  io::Progress progress("fit", 0.0, "");
  options.progress = [&](const std::string& what, int done, int total) {
    progress.update(what, done, total);
  };
  const validation::TrajectoryFitResult r = validation::fitTrajectories(trials, model, options);
  progress.finish();
  std::cout << "mean e_q: start " << r.meanStart << ", fitted " << r.meanFitted;
  if (!std::isnan(r.meanHeldOut))
    std::cout << ", " << options.folds << "-fold cross-validated " << r.meanHeldOut;
  std::cout << "\n";
  for (const auto& p : r.parameters)
    std::cout << p.name << " = " << p.value << " ± " << p.stdError << ' ' << p.unit << '\n';
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

}  // namespace vcontact::cli
