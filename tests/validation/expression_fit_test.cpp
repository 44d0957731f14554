// Expression effects in fit and diagnose (issue 15, item 4): on a synthetic record whose hidden
// effect is a load-dependent friction coefficient μ(f_n) = μ_C + b f_n, written as the
// expression "-b*f_n^2", the fit recovers b, and diagnose with the user's candidate list names it.

#include <gtest/gtest.h>

#include <cmath>

#include "validation/diagnose.hpp"
#include "validation/effect_cases.hpp"
#include "validation/load_varying_drive.hpp"

namespace vcontact::validation {
namespace {

// A fitted value within 3 standard errors of the truth: a 99.7 % band for a Gaussian estimate.
constexpr double kStdErrors = 3.0;
constexpr double kTrueB = 5e-4;  // 1/N: μ grows by 0.013 at the mean load of about 26 N

dynamics::Model truth() {
  dynamics::Model m = test::trueModel({"stiffness", "coulomb"});
  m.add(test::muLoad(kTrueB));
  m.validate();
  return m;
}

TEST(ExpressionFit, RecoversTheLoadGrowthOfMu) {
  Dataset d = test::loadVaryingDrive(400);
  synthesizeMeasurement(d, truth(), 11);
  dynamics::Model start = dynamics::Model::withEffects({"stiffness", "coulomb"});
  start.add(test::muLoad(0.0));
  Replayer replayer(d);
  const FitResult r = fit(replayer, noiseLevels(d), start);
  EXPECT_LE(r.comparison.chi, 1.2);  // explained to the noise (chi ≈ 1 ± sampling scatter)
  for (const auto& p : r.parameters) {
    if (p.name != "mu_load.b") continue;
    EXPECT_LE(std::abs(p.value - kTrueB), kStdErrors * p.stdError)
        << p.value << " ± " << p.stdError;
    EXPECT_LT(p.stdError, 0.2 * kTrueB);  // and b is resolved, not merely bounded
  }
}

TEST(ExpressionFit, DiagnoseWithTheUsersCandidatesNamesTheExpression) {
  Dataset d = test::loadVaryingDrive(400);
  synthesizeMeasurement(d, truth(), 12);
  DiagnoseOptions options;
  options.candidates = CandidateSet();
  options.candidates.add(dynamics::createEffect("viscous"));
  options.candidates.add(test::muLoad(0.0));
  const Diagnosis diag =
      diagnose(d, noiseLevels(d), dynamics::Model::withEffects({"stiffness", "coulomb"}), options);
  const DiagnosisStage& s = diag.stages.front();
  ASSERT_EQ(s.ranking.size(), 2u);
  EXPECT_EQ(s.verdict, "mu_load");
  EXPECT_GT(s.baseline.comparison.chi, 2.0);  // the bare model misses it
  EXPECT_LE(s.ranking.front().fit.comparison.chi, 1.2);
}

}  // namespace
}  // namespace vcontact::validation
