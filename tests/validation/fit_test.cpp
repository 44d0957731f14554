// fit: robust losses, identifiability warnings, covariance against the scatter of refits.

#include "validation/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "validation/effect_cases.hpp"

namespace vcontact::validation {
namespace {

TEST(Fit, RobustLossResistsOutliersThatPullTheSquaredLoss) {
  const auto truth = test::trueModel({"stiffness", "coulomb"});
  Dataset d = test::syntheticDataset("drive", 300, truth, 21);
  // Every 10th fx sample hit by a 30σ glitch of one sign (a cable snag on the rig).
  Eigen::VectorXd& fx = d.columns["fx"];
  for (Eigen::Index i = 0; i < fx.size(); i += 10) fx[i] += 30.0 * d.noise.at("fx");
  const auto noise = noiseLevels(d);
  dynamics::Model start = test::startModel({"stiffness", "coulomb"}, "");
  start.setFixed({"coulomb.v_s"});
  Replayer replayer(d);
  const FitResult squared = fit(replayer, noise, start, {Loss::kSquared});
  const FitResult huber = fit(replayer, noise, start, {Loss::kHuber});
  const FitResult cauchy = fit(replayer, noise, start, {Loss::kCauchy});
  const double mu = truth.parameter("coulomb.mu");
  const double errSquared = std::abs(squared.model.parameter("coulomb.mu") - mu);
  // The robust losses must remove most of the outliers' bias: Huber at least half of it,
  // Cauchy (which redescends) at least 80 %.
  EXPECT_LT(std::abs(huber.model.parameter("coulomb.mu") - mu), 0.5 * errSquared);
  EXPECT_LT(std::abs(cauchy.model.parameter("coulomb.mu") - mu), 0.2 * errSquared);
}

TEST(Fit, ParametersTheDataCannotSeeAreFlaggedNotGivenFalsePrecision) {
  // Without stribeck, bristle or dwell nothing depends on coulomb.v_s.
  const auto truth = test::trueModel({"stiffness", "coulomb"});
  const Dataset d = test::syntheticDataset("drive", 200, truth, 4);
  Replayer replayer(d);
  const FitResult r = fit(replayer, noiseLevels(d), test::startModel({"stiffness", "coulomb"}, ""));
  bool warned = false;
  for (const auto& p : r.parameters) {
    if (p.name == "coulomb.v_s") {
      EXPECT_FALSE(p.identifiable);
      EXPECT_TRUE(std::isinf(p.stdError));
    } else {
      EXPECT_TRUE(p.identifiable) << p.name;
      EXPECT_TRUE(std::isfinite(p.stdError)) << p.name;
    }
  }
  for (const auto& w : r.warnings)
    warned |= w.rfind("coulomb.v_s: the data cannot identify it", 0) == 0;
  EXPECT_TRUE(warned);
}

TEST(Fit, StandardErrorsMatchTheScatterOverNoiseSeeds) {
  // The covariance is a claim about repeated experiments: check it against 12 of them.
  const auto truth = test::trueModel({"stiffness", "coulomb", "viscous"});
  dynamics::Model start = test::startModel({"stiffness", "coulomb", "viscous"}, "");
  start.setFixed({"coulomb.v_s"});
  std::vector<double> values;
  double claimed = 0.0;
  for (unsigned seed = 100; seed < 112; ++seed) {
    const Dataset d = test::syntheticDataset("drive", 200, truth, seed);
    Replayer replayer(d);
    const FitResult r = fit(replayer, noiseLevels(d), start);
    values.push_back(r.model.parameter("viscous.sigma2"));
    for (const auto& p : r.parameters) {
      if (p.name == "viscous.sigma2") claimed += p.stdError / 12.0;
    }
  }
  double mean = 0.0, var = 0.0;
  for (double v : values) mean += v / 12.0;
  for (double v : values) var += (v - mean) * (v - mean) / 11.0;
  // 12 samples: the sample standard deviation is within a factor 0.6–1.4 of the true one
  // with about 95 % probability (χ² with 11 degrees of freedom).
  EXPECT_GT(std::sqrt(var) / claimed, 0.6);
  EXPECT_LT(std::sqrt(var) / claimed, 1.4);
}

}  // namespace
}  // namespace vcontact::validation
