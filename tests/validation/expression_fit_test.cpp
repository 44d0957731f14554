// Expression effects in fit and diagnose (issue 15, item 4): on a synthetic record whose hidden
// effect is a load-dependent friction coefficient μ(f_n) = μ_C + b f_n, written as the
// expression "-b*f_n^2", the fit recovers b, and diagnose with the user's candidate list names it.

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/effects/expression.hpp"
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

// In a replay, t is the time of the record's sample: a normal term c·t adds c t_i to fz.
TEST(ExpressionFit, TheReplayGivesAFormulaTheSampleTime) {
  const Dataset d = rigMotion("drive", 60);
  auto def = std::make_shared<dynamics::ExpressionDefinition>();
  def->id = "ramp";
  def->parameters = {{"c", "N/s", 0.0, 0.0, 1e3, "normal force growth per second"}};
  def->normal = "c*t";
  dynamics::Model plain = dynamics::Model::withEffects({"stiffness"});
  dynamics::Model ramp = plain;
  ramp.add(dynamics::makeExpressionEffect(def));
  ramp.setParameter("ramp.c", 2.0);
  Replayer replayer(d);
  const Eigen::VectorXd a = replayer.run(plain).column("fz"), b = replayer.run(ramp).column("fz");
  for (std::size_t i = 0; i < d.size(); ++i) {  // the punch is in contact at every sample
    const auto k = static_cast<Eigen::Index>(i);
    EXPECT_NEAR(b[k] - a[k], 2.0 * d.samples[i].t, 1e-12 * a.cwiseAbs().maxCoeff()) << i;
  }
}

}  // namespace
}  // namespace vcontact::validation
