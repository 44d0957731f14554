#pragma once
// DIR/report.html: one self-contained page (inline SVG and CSS, no network) that shows the
// measured against the model for each output, the residuals with the failing windows, the
// residuals against the regime variables, the candidate table, the fitted parameters with
// their uncertainties and the chi of each model stage (issue #5, item 6). For diagnose also the
// verdict of every stage (effect, rig finding, none or unexplained with what the residual looks
// like), each stage's chi fitted and held out (cross-validation) as a chart, and parameters at
// a bound marked (issue 15). Residuals, failing windows and regime panels are the final
// model's; a regime panel is drawn only for a variable that varies over the record. Charts
// span the page width (1060 px; regime panels three to a row).
//
// An inline script checks on load that every <svg class="chart"> has a non-empty bounding
// box and writes "rendered/total" into <body data-charts-rendered> and the title, so that a
// headless browser's DOM dump proves the charts rendered.

#include <string>
#include <vector>

#include "validation/diagnose.hpp"

namespace vcontact::report {

struct ReportStage {
  std::string label;                 ///< e.g. "stiffness + coulomb", "+ contensou"
  const validation::FitResult* fit;  ///< prediction, comparison, parameters
  /// diagnose: the stage (held-out χ², verdict, rig findings); null for compare and fit
  const validation::DiagnosisStage* stage = nullptr;
};

struct ReportInput {
  std::string command;  ///< "compare", "fit" or "diagnose"
  const validation::Dataset* dataset = nullptr;
  validation::NoiseLevels noise;
  std::vector<ReportStage> stages;               ///< first: the user's model; last: the final one
  std::vector<validation::FailureWindow> where;  ///< of the last stage (the final model)
  const std::vector<validation::Candidate>* ranking = nullptr;  ///< of the last stage
  /// What the record says without the model (validation/direct_estimates.hpp), shown beside
  /// the final model's parameters; null: none.
  const std::vector<validation::DirectEstimate>* direct = nullptr;
};

std::string reportHtml(const ReportInput& input);

/// Writes reportHtml(input) to `path`.
/// @throws InputError naming `path` when it cannot be opened for writing
void writeReportHtml(const ReportInput& input, const std::string& path);

}  // namespace vcontact::report
