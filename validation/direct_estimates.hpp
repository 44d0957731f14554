#pragma once
// What a record says without the model (issue 37 item 1; docs/DIAGNOSIS.md "Direct
// estimates"), to set beside a fitted value:
//
//   coulomb.mu    |F_t|/F_n over the sliding samples (phases.hpp), F_t = |(f_x, f_y)| of the
//                 measured tangential outputs, F_n the measured f_z where the record has a fz
//                 column (an output or not), else the replayed model's normal load; samples
//                 with F_n ≤ 3 σ_fz (or ≤ 0) left out. Value: the median; range: the 10–90 %
//                 quantiles.
//   power_law.p   the slope of log f_z against log V over the loading samples with
//                 f_z > 5 σ_fz (V replayed from the record's poses): the exponent of the
//                 normal law in the volume, 1 for the volumetric law f_n = kv V. Range: the
//                 slopes over the lower and upper halves of those samples (they differ when
//                 the law is not a power). The load–depth exponent (f_z ∝ d^m, the slope
//                 against the depth) is given in the text.
//   lag <output>  the shift τ (s) of the fitted prediction that maximises its correlation with
//                 the measured column, over ±kMaxLagFraction of the record, refined within a
//                 sample by a parabola through the peak; range ± one sample.
// A restitution coefficient is not estimated: a kinematic record's motion is prescribed by
// the rig, so its rebounds say nothing of the contact.
//
// Beside a fit (compareWithFit): a fitted value outside the estimate's range by more than 2 % of
// the estimate, the estimate's own precision (a parameter the model lacks is taken at its
// neutral value: power_law.p = 1, lag 0), is flagged, with the
// reason the fit moved there: the model is replayed with the parameter at the direct estimate
// (the others held) and the change of χ² is split by phase and by output: the parts whose χ²
// would rise pull the fit away from the record's own estimate.

#include <limits>
#include <string>
#include <vector>

#include "validation/fit.hpp"

namespace vcontact::validation {

struct DirectEstimate {
  std::string parameter;  ///< "coulomb.mu", "power_law.p", "lag fx"
  std::string unit;
  std::string method;  ///< how it was measured, e.g. "|F_t|/F_n over 96 sliding samples"
  double value = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  std::size_t samples = 0;
  double t0 = 0.0, t1 = 0.0;  ///< first and last sample used, s
  // ---- beside a fit ----
  double fitted = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not compared
  bool far = false;                                          ///< fitted outside [low, high]
  std::string pull;  ///< which samples pull the fit away (when far)
};

/// The direct estimates the record allows, from its measured columns and `prediction` (a
/// replay of the record: phases, volumes, loads).
std::vector<DirectEstimate> directEstimates(const Dataset& dataset, const NoiseLevels& noise,
                                            const Prediction& prediction);

/// Sets fitted, far and pull of each estimate against `fit` and adds a warning to
/// fit.warnings for each one far from it (see the header). Costs one replay per far estimate.
void compareWithFit(const Dataset& dataset, FitResult& fit, std::vector<DirectEstimate>& estimates);

/// directEstimates of the fit's own prediction, compared with it (compareWithFit): what
/// `fit` shows beside its values (the CLI and Python alike).
std::vector<DirectEstimate> estimatesBeside(const Dataset& dataset, const NoiseLevels& noise,
                                            FitResult& fit);

/// Failure windows and phases share one smoothing window: 1 % of the record, at least 5.
std::size_t phaseHalfWindow(std::size_t samples);

}  // namespace vcontact::validation
