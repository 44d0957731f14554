#pragma once
// What `vcontact compare`, `fit` and `diagnose` write for dynamic datasets (docs/DATASET.md,
// "Dynamic datasets"): trajectory.csv, compare.json, the trajectory fit's fit.json and
// trials.csv, the diagnosis's diagnosis.json, and their HTML reports (recorded against
// simulated height, speed and angle error).

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "validation/trajectory_diagnose.hpp"
#include "validation/trajectory_fit.hpp"

namespace vcontact::report {

/// trajectory.csv: t; x, x_sim, y, y_sim, ..., qz, qz_sim; dp (m), dtheta (rad); phase.
void putTrajectoryCsv(const validation::Trial& trial, const validation::TrialEvaluation& e,
                      std::ostream& out);

/// The errors of one trial: e_q and its parts, mean position error over the payload's size,
/// mean rotation error (degrees), deepest penetration, the same per phase, where they part.
nlohmann::json trajectoryErrorsJson(const validation::TrajectoryErrors& e);

/// compare.json of a dynamic dataset: the errors, the initial state and how it was found.
nlohmann::json trajectoryCompareJson(const validation::Trial& trial,
                                     const validation::TrialEvaluation& e);

/// report.html of `compare` on a dynamic dataset.
std::string trajectoryReportHtml(const validation::Trial& trial,
                                 const validation::TrialEvaluation& e, const std::string& model);

/// fit.json of a trajectory fit: parameters, mean e_q (start, fitted, held out), per trial.
nlohmann::json trajectoryFitJson(const validation::TrajectoryFitResult& r,
                                 const validation::TrajectoryFitOptions& o);

/// trials.csv: name, fold, e_q start, fitted, held out, worst phase, where they part.
void putTrialsCsv(const validation::TrajectoryFitResult& r, std::ostream& out);

/// "jackknife over the folds", "gauss-newton (above the jackknife)" or "gauss-newton": which
/// error the parameter's stdError is.
const char* standardErrorMethod(const validation::TrajectoryParameter& p);

/// report.html of a trajectory fit: e_q per trial (fitted against held out), the parameters,
/// and the trials ranked by held-out e_q with the phase where each fails.
std::string trajectoryFitReportHtml(const validation::TrajectoryFitResult& r,
                                    const validation::TrajectoryFitOptions& o);

/// diagnosis.json of a trajectory diagnosis: the baseline's mean e_q, the candidates ranked by
/// held-out e_q with the paired change and its standard error, the verdict, the trials no
/// model explains with their phase and hint.
nlohmann::json trajectoryDiagnosisJson(const validation::TrajectoryDiagnosis& d,
                                       const validation::TrajectoryFitOptions& o);

/// report.html of a trajectory diagnosis: the ranking table and the unexplained trials.
std::string trajectoryDiagnosisReportHtml(const validation::TrajectoryDiagnosis& d,
                                          const validation::TrajectoryFitOptions& o);

}  // namespace vcontact::report
