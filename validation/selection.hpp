#pragma once
// Out-of-sample judgement of a fitted model and a description of what it leaves unexplained
// (issue 15 item 2).
//
// Blocked cross-validation: the record is cut into kCvBlocks contiguous blocks of equal
// sample count; for each block the model is refitted on the others (the replay runs over the
// whole record, the block's residuals weighted 0, FitOptions::heldOut) from the full-record
// optimum by one Levenberg–Marquardt run (no multistart: the optimum is already the best start
// and the blocks differ little), and the block is predicted. The held-out χ² is the sum over
// blocks of Σ (r/σ)² on the held-out block: every sample is predicted once by a fit that did
// not see it. Contiguous blocks, not random samples, because neighbouring samples share their
// error (friction states, slow drift): a random split would let a model interpolate.
//
// Residual description (for the verdict "unexplained"), on the output with the largest χ²:
//   noise share        n / χ² (all outputs): the share of the residual variance the noise σ
//                      accounts for
//   dominant frequency the peak of the residual's periodogram (mean sample spacing), reported
//                      when it holds at least kRingShare of the residual's variance: it rings
//   regime correlation Pearson correlation of |r/σ| with each regime variable that varies
//                      (where the residual is large, not its sign)

#include <string>
#include <utility>
#include <vector>

#include "validation/fit.hpp"

namespace vcontact::validation {

inline constexpr int kCvBlocks = 5;
/// A periodogram peak holding this share of the residual variance is a ringing residual.
inline constexpr double kRingShare = 0.2;

/// Held-out χ² of `fitted` (its free parameters refitted without each block; see the header).
/// Folds run in parallel (TBB).
double heldOutChi2(const Dataset& dataset, const NoiseLevels& noise, const dynamics::Model& fitted,
                   const FitOptions& options);

struct ResidualDescription {
  std::string output;           ///< the output with the largest χ²
  double noiseShare = 0.0;      ///< n / χ²
  double frequency = 0.0;       ///< Hz of the periodogram peak; 0 when none rings
  double frequencyShare = 0.0;  ///< its share of the residual variance
  std::vector<std::pair<std::string, double>> correlation;  ///< regime variable → r
};

ResidualDescription describeResidual(const Dataset& dataset, const FitResult& fitted);

/// Name and value of each regime variable (the `where` variables), per sample.
struct RegimeColumn {
  std::string name;
  std::vector<double> values;
};
std::vector<RegimeColumn> regimeColumns(const std::vector<RegimeSample>& regime);

}  // namespace vcontact::validation
