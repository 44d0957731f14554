#pragma once
// What `vcontact compare | fit | diagnose | synth` write: residual CSVs, fit.json,
// diagnosis.json, fitted model files and synthetic datasets (DATASET.md format).

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "validation/diagnose.hpp"
#include "validation/direct_estimates.hpp"
#include "validation/fit.hpp"
#include "validation/residuals.hpp"

namespace vcontact::report {

/// residuals.csv: t, then per output measured, predicted, residual, residual/σ.
void putResidualsCsv(const validation::Dataset& dataset, const validation::Comparison& comparison,
                     std::ostream& out);

/// {"chi", "rms": {output: …}, "sigma": {output: {"value", "source"}}, "samples", "residuals"}
nlohmann::json comparisonJson(const validation::Comparison& comparison,
                              const validation::NoiseLevels& noise);

/// fit.json: comparison, BIC, parameters with standard errors, correlations, warnings, and
/// with `direct` the direct estimates beside the fitted values ("direct_estimates").
nlohmann::json fitJson(const validation::FitResult& fit, const validation::NoiseLevels& noise,
                       validation::Loss loss,
                       const std::vector<validation::DirectEstimate>* direct = nullptr);

/// [{"parameter", "unit", "value", "low", "high", "samples", "t0", "t1", "method", "fitted",
///   "far", "pull"}] (validation/direct_estimates.hpp).
nlohmann::json directEstimatesJson(const std::vector<validation::DirectEstimate>& estimates);

/// diagnosis.json (issue #5): verdict, baseline, ranking, where, and the stages of --iterate.
nlohmann::json diagnosisJson(const validation::Diagnosis& diagnosis,
                             const validation::NoiseLevels& noise);

}  // namespace vcontact::report
