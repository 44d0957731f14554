#pragma once
// Residuals of a prediction against the measurement, and the noise they are measured in.
//
//   r_i = measured_i − predicted_i,   RMS = sqrt(mean r²),
//   chi = sqrt(mean over all outputs and samples of (r/σ)²)      (issue #5; 1 = down to noise)
//
// σ per output comes from the sidecar's "noise"; where it is absent it is estimated from the
// measured column alone, so that every model is judged against the same σ:
//   d_i = y_{i+1} − 2 y_i + y_{i−1}  (for white noise Var d = 6σ², smooth signal cancels to
//   second order),  σ̂ = 1.4826 · median |d − median d| / √6
// (the MAD of the second differences, robust to the few samples where the signal itself
// kinks: impacts, stops). It assumes the signal is smooth over three samples.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "validation/dataset.hpp"
#include "validation/replay.hpp"

namespace vcontact::validation {

struct NoiseLevel {
  double sigma = 0.0;      ///< 1-σ, in the output's unit
  bool estimated = false;  ///< true: from the data (MAD of second differences)
};

using NoiseLevels = std::map<std::string, NoiseLevel>;

/// σ̂ of a sampled signal by the MAD of its second differences (see the header).
/// @pre y.size() ≥ 3
double estimateNoise(const Eigen::VectorXd& y);

/// σ of every output of the dataset: from the sidecar, else estimated.
NoiseLevels noiseLevels(const Dataset& dataset);

struct OutputResiduals {
  std::string output;
  Eigen::VectorXd measured, predicted, residual;  ///< residual = measured − predicted
  double sigma = 0.0;
  double rms = 0.0;
  double chi = 0.0;  ///< sqrt(mean (r/σ)²) over this output
};

struct Comparison {
  std::vector<OutputResiduals> outputs;
  double chi2 = 0.0;      ///< Σ (r/σ)² over all outputs and samples
  std::size_t count = 0;  ///< number of residuals
  double chi = 0.0;       ///< sqrt(chi2 / count)
};

Comparison compare(const Dataset& dataset, const Prediction& prediction, const NoiseLevels& noise);

/// Bayesian information criterion with known σ: BIC = χ² + k ln n (−2 ln L up to a constant
/// that is the same for every model of the same data and σ).
double bic(const Comparison& comparison, std::size_t freeParameters);

}  // namespace vcontact::validation
