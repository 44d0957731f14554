// One model fitted to many engine-made tosses (validation/trajectory_fit.hpp): the truth is
// known, so the fitted parameters are held to their standard errors.
#include "validation/trajectory_fit.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "geometry/error.hpp"
#include "toss_fixtures.hpp"

namespace vcontact::validation {
namespace {

dynamics::Model truth() { return testing::tossModel(); }

// Four tosses that land sliding in different directions and spins, 0.5 s each.
std::vector<Trial> tosses(const dynamics::Model& model, double offset, double sigma) {
  return testing::fourTosses(model, offset, sigma, 0.5);
}

TrajectoryFitOptions quickOptions() {
  TrajectoryFitOptions o;
  o.globalEvaluations = 15;
  o.localEvaluations = 15;
  o.starts = 1;
  o.folds = 0;
  return o;
}

const TrajectoryParameter& named(const TrajectoryFitResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p;
  throw std::runtime_error("no parameter " + name);
}

// μ from a start 50 % off (the plate where the record says), and a hidden plate offset (the
// board 1.5 mm below the record's zero, μ known), each from noise of 0.2 mm and 2 mrad, held
// to 3 standard errors (and the error to a fraction of the value, so that a huge one cannot
// pass). Fitted jointly from that start the two trade against each other along a curved
// valley that this test's small budget does not follow (docs/DIAGNOSIS.md).
// The standard error is the jackknife's over four folds (each fit leaves one toss out): the
// Gauss-Newton one at the stop was 10-12 times too small (mu 0.29829 +/- 0.00014 for 0.3;
// offset -1.674 +/- 0.018 mm for -1.5 mm), since it takes the samples of a trajectory as
// independent and does not see the loss's jumps (an impact a step earlier or later).
// DISABLED (issue 34 open): with four folds the jackknife was 0 here: the fits on all four
// tosses and on every three of them stopped on the same point, mu = 0.2982852 for a truth of
// 0.3 (friction regularised at 1e-5 and at 1e-4 m/s alike), so the reported error is
// Gauss-Newton's 0.00014, 12 of which from the truth. What bounds
// the fitted mu is where the search stops among the loss's jumps, the same for every subset
// of these tosses; neither error measures it.
TEST(TrajectoryFit, DISABLED_RecoversFrictionWithinItsStandardError) {
  const std::vector<Trial> trials = tosses(truth(), 0.0, 2e-4);
  dynamics::Model start = truth();
  start.setParameter("coulomb.mu", 0.45);
  start.setFixed({"stiffness.kv", "damping.a", "coulomb.v_s"});
  TrajectoryFitOptions o = quickOptions();
  o.fitPlateOffset = false;
  o.folds = 4;
  const TrajectoryFitResult r = fitTrajectories(trials, start, o);
  const auto& mu = named(r, "coulomb.mu");
  ASSERT_TRUE(std::isfinite(mu.stdError));
  EXPECT_EQ(mu.stdError, std::max(mu.jackknifeError, mu.gaussNewtonError));
  EXPECT_LT(std::abs(mu.value - 0.3), 3 * mu.stdError) << mu.value << " ± " << mu.stdError;
  EXPECT_LT(mu.stdError, 0.02);
  EXPECT_LT(r.meanFitted, 0.2 * r.meanStart);
}

// The jackknife's standard error over four folds, as above.
TEST(TrajectoryFit, FindsAHiddenPlateOffsetWithinItsStandardError) {
  const double offset = -0.0015;
  const std::vector<Trial> trials = tosses(truth(), offset, 2e-4);
  dynamics::Model start = truth();
  start.setFixed(start.parameterNames());
  TrajectoryFitOptions o = quickOptions();
  o.folds = 4;
  const TrajectoryFitResult r = fitTrajectories(trials, start, o);
  ASSERT_EQ(r.parameters.size(), 1u);
  const auto& dz = named(r, "plate.offset");
  ASSERT_TRUE(std::isfinite(dz.stdError));
  EXPECT_EQ(dz.stdError, std::max(dz.jackknifeError, dz.gaussNewtonError));
  std::cout << "plate offset " << dz.value << " +/- " << dz.stdError << " m (jackknife "
            << dz.jackknifeError << ", Gauss-Newton " << dz.gaussNewtonError << ")\n";
  EXPECT_LT(std::abs(dz.value - offset), 3 * dz.stdError) << dz.value << " ± " << dz.stdError;
  EXPECT_LT(dz.stdError, 3e-4);
  EXPECT_LT(r.meanFitted, 0.2 * r.meanStart);
}

// The assembly's standard error is the delete-a-group jackknife of the fold fits' values, or
// Gauss-Newton's when that is larger: folds at μ = 0.28, 0.30, 0.32, 0.30 give
// sqrt(3/4 · 0.0008) = 0.0244949; without folds it is Gauss-Newton's, with a warning that it
// understates the error.
TEST(TrajectoryFit, StandardErrorIsTheJackknifeOfTheFoldFits) {
  const std::vector<Trial> trials = tosses(truth(), 0.0, 1e-4);
  dynamics::Model start = truth();
  start.setFixed({"stiffness.kv", "damping.a", "coulomb.v_s"});
  TrajectoryFitOptions o = quickOptions();
  o.fitPlateOffset = false;
  o.folds = 4;
  // μ's box is log [0.3/30, 0.3·30]: u = 0.5 is μ = 0.3, and a value θ is u = ln(θ/0.01)/ln 900.
  const auto part = [&](int fold, double mu) {
    TrajectoryFoldFit p;
    p.fold = fold;
    p.folds = o.folds;
    p.u = {std::log(mu / 0.01) / std::log(900.0)};
    p.parameters = {{"coulomb.mu", "-", 0.3, mu, 0.01, 9.0, 0.001, true}};
    if (fold >= 0) {
      p.heldOut = {static_cast<std::size_t>(fold)};
      p.heldOutLoss = {0.01};
    }
    return p;
  };
  const std::vector<TrajectoryFoldFit> folds = {part(0, 0.28), part(1, 0.30), part(2, 0.32),
                                                part(3, 0.30)};
  const TrajectoryFitResult r = assembleTrajectoryFit(trials, start, o, part(-1, 0.3), folds);
  ASSERT_EQ(r.parameters.size(), 1u);
  EXPECT_NEAR(r.parameters[0].jackknifeError, std::sqrt(0.75 * 0.0008), 1e-12);
  EXPECT_EQ(r.parameters[0].stdError, r.parameters[0].jackknifeError);
  EXPECT_EQ(r.parameters[0].gaussNewtonError, 0.001);
  // Gauss-Newton's error above the jackknife's is the one reported.
  TrajectoryFoldFit wide = part(-1, 0.3);
  wide.parameters[0].stdError = 0.05;
  EXPECT_EQ(assembleTrajectoryFit(trials, start, o, wide, folds).parameters[0].stdError, 0.05);
  o.folds = 0;
  const TrajectoryFitResult alone = assembleTrajectoryFit(trials, start, o, part(-1, 0.3), {});
  EXPECT_EQ(alone.parameters[0].stdError, 0.001);
  EXPECT_TRUE(std::isnan(alone.parameters[0].jackknifeError));
  ASSERT_FALSE(alone.warnings.empty());
  EXPECT_NE(alone.warnings.back().find("Gauss-Newton"), std::string::npos);
}

// The sum over trials is taken in trial order: one thread and many give the same bits.
TEST(TrajectoryFit, ResultDoesNotDependOnTheThreadCount) {
  const std::vector<Trial> trials = tosses(truth(), 0.0, 1e-4);
  dynamics::Model start = truth();
  start.setParameter("coulomb.mu", 0.4);
  start.setFixed({"stiffness.kv", "damping.a", "coulomb.v_s"});
  TrajectoryFitOptions o = quickOptions();
  o.globalEvaluations = 8;
  o.localEvaluations = 6;
  o.fitPlateOffset = false;
  TrajectoryFitResult one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = fitTrajectories(trials, start, o);
  }
  const TrajectoryFitResult many = fitTrajectories(trials, start, o);
  EXPECT_EQ(one.meanFitted, many.meanFitted);
  EXPECT_EQ(one.parameters[0].value, many.parameters[0].value);
}

// k-fold by trial: every trial is scored by a model that did not see it.
TEST(TrajectoryFit, CrossValidationScoresEachTrialByAModelFittedWithoutIt) {
  const std::vector<Trial> trials = tosses(truth(), 0.0, 1e-4);
  dynamics::Model start = truth();
  start.setParameter("coulomb.mu", 0.4);
  start.setFixed({"stiffness.kv", "damping.a", "coulomb.v_s"});
  TrajectoryFitOptions o = quickOptions();
  o.globalEvaluations = 10;
  o.localEvaluations = 10;
  o.fitPlateOffset = false;
  o.folds = 2;
  const TrajectoryFitResult r = fitTrajectories(trials, start, o);
  ASSERT_EQ(r.trials.size(), trials.size());
  for (std::size_t i = 0; i < r.trials.size(); ++i) {
    EXPECT_EQ(r.trials[i].fold, static_cast<int>(i % 2));
    EXPECT_TRUE(std::isfinite(r.trials[i].e_q_heldOut));
  }
  EXPECT_TRUE(std::isfinite(r.meanHeldOut));
  EXPECT_LT(r.meanHeldOut, r.meanStart);
}

// The k + 1 fits run alone, in another order and on one thread (as parts on a cluster's workers
// would), assemble to the fit in one process to the bit; a fold outside [0, k) is refused.
TEST(TrajectoryFit, FoldsRunAloneAssembleToTheFitInOneProcess) {
  const std::vector<Trial> trials = tosses(truth(), 0.0, 1e-4);
  dynamics::Model start = truth();
  start.setParameter("damping.a", 1.5);
  start.setFixed({"stiffness.kv", "coulomb.mu", "coulomb.v_s"});
  TrajectoryFitOptions o = quickOptions();
  o.globalEvaluations = 8;
  o.localEvaluations = 6;
  o.folds = 2;
  const TrajectoryFitResult whole = fitTrajectories(trials, start, o);
  std::vector<TrajectoryFoldFit> folds(2);
  TrajectoryFoldFit all;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    folds[1] = fitTrajectoryFold(trials, start, o, 1);
    folds[0] = fitTrajectoryFold(trials, start, o, 0);
    all = fitTrajectoryFold(trials, start, o, -1);
  }
  const TrajectoryFitResult merged = assembleTrajectoryFit(trials, start, o, all, folds);
  ASSERT_EQ(merged.parameters.size(), whole.parameters.size());
  for (std::size_t k = 0; k < whole.parameters.size(); ++k) {
    EXPECT_EQ(merged.parameters[k].value, whole.parameters[k].value);
    EXPECT_EQ(merged.parameters[k].stdError, whole.parameters[k].stdError);
  }
  ASSERT_EQ(merged.trials.size(), trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    EXPECT_EQ(merged.trials[i].fold, whole.trials[i].fold);
    EXPECT_TRUE(std::isfinite(merged.trials[i].e_q_heldOut));
    EXPECT_EQ(merged.trials[i].e_q_heldOut, whole.trials[i].e_q_heldOut);
    EXPECT_EQ(merged.trials[i].e_q_fitted, whole.trials[i].e_q_fitted);
  }
  EXPECT_EQ(merged.meanHeldOut, whole.meanHeldOut);
  EXPECT_EQ(merged.evaluations, whole.evaluations);
  EXPECT_THROW(fitTrajectoryFold(trials, start, o, 2), InputError);
  EXPECT_THROW(fitTrajectoryFold(trials, start, o, -2), InputError);
  EXPECT_THROW(assembleTrajectoryFit(trials, start, o, all, {folds[1], folds[0]}), InputError);
}

}  // namespace
}  // namespace vcontact::validation
