#pragma once
// compare and fit on dynamic datasets (docs/DATASET.md, "Dynamic datasets"): one trial
// simulated against its record, or one model fitted to many trials (validation/trajectory_*).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "formats/dataset_file.hpp"

namespace vcontact::cli {

struct TrajectoryOptions {
  double h = 0.0;  ///< m, e_q's length; 0: half the payload's smallest extent
  std::string integrator = "discrete";
  int folds = 5;
  int globalEvaluations = 48;
  int localEvaluations = 32;
  int polishes = 2;
  bool fixPlate = false;
  double plateOffset = 0.0;  ///< m, compare only: the plate's offset along its normal
  /// fit only: run one of the k + 1 fits of a cross-validated fit alone ("all" or a fold
  /// 0 … k−1) and write OUT/fold.json; empty: the whole fit
  std::string fold;
  std::vector<std::string> merge;  ///< fit only: fold.json parts to assemble, no search
};

/// The options above on a command (compare: h, integrator, plate offset; fit: all).
void addTrajectoryOptions(CLI::App* cmd, TrajectoryOptions& o, bool fits);

/// --fold and --merge on `fit` (docs/DIAGNOSIS.md, "One fold at a time").
void addFoldOptions(CLI::App* cmd, TrajectoryOptions& o);

/// DATASET arguments to sidecar paths: a folder gives its *.json dataset sidecars (sorted by
/// name), a file whose name ends in .txt or .list one path per line (relative to it), anything
/// else itself. @throws InputError on a folder without datasets or an unreadable list
std::vector<std::string> expandDatasets(const std::vector<std::string>& args);

void runTrajectoryCompare(const formats::DatasetReadResult& data, const dynamics::Model& model,
                          const std::string& modelPath, const TrajectoryOptions& o,
                          const std::string& out);

void runTrajectoryFit(const std::vector<std::string>& datasets, const dynamics::Model& model,
                      const TrajectoryOptions& o, const std::string& out);

/// Ranks the candidate effects (a candidates file, or the library's when empty) by the
/// cross-validated e_q of the trials: diagnosis.json, model.json (the accepted candidate's fit,
/// else the baseline's), trials.csv and report.html in `out`.
void runTrajectoryDiagnose(const std::vector<std::string>& datasets, const dynamics::Model& model,
                           const TrajectoryOptions& o, const std::string& candidates,
                           const std::string& out);

}  // namespace vcontact::cli
