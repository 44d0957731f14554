// The phases of a record's motion (validation/phases.hpp): the indentation profile's
// approach, loading, holding, unloading and separation at the times its program sets, and a
// dwell record's sliding and rest.

#include "validation/phases.hpp"

#include <gtest/gtest.h>

#include "validation/effect_cases.hpp"

namespace vcontact::validation {
namespace {

Phase phaseAt(const Dataset& d, const std::vector<Phase>& phases, double t) {
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (d.samples[i].t >= t) return phases[i];
  }
  return phases.back();
}

std::vector<Phase> phasesOfRecord(const Dataset& d, const dynamics::Model& model) {
  Replayer replayer(d);
  return phasesOf(replayer.run(model).regime, 2);
}

// The indentation program (validation/synthetic.hpp): approach to 0.3 s, loading to 1.5 s,
// hold to 2.5 s, unloading to 3.7 s, then separated. Times sampled mid-phase, 0.1 s or more
// from each switch (the smoothing window is ±2 samples of 0.01 s).
TEST(Phases, IndentationIsApproachLoadingHoldingUnloadingSeparation) {
  const Dataset d = rigMotion("indentation", 400);
  const auto phases = phasesOfRecord(d, dynamics::Model::withEffects({"stiffness"}));
  EXPECT_EQ(phaseAt(d, phases, 0.15), Phase::kApproach);
  EXPECT_EQ(phaseAt(d, phases, 0.9), Phase::kLoading);
  EXPECT_EQ(phaseAt(d, phases, 2.0), Phase::kHolding);
  EXPECT_EQ(phaseAt(d, phases, 3.1), Phase::kUnloading);
  EXPECT_EQ(phaseAt(d, phases, 3.9), Phase::kSeparation);
}

// Slide 0.4 s, stop 0.1 s, slide 0.4 s, stop 0.5 s, slide 0.4 s, stop 1.5 s (dwell profile,
// ramps of 0.1 s): sliding mid-slide, rest mid-stop. A record with tangential motion calls a
// stop "rest", not "holding".
TEST(Phases, DwellRecordSlidesAndRests) {
  const Dataset d = rigMotion("dwell", 600);
  const auto phases = phasesOfRecord(d, dynamics::Model::withEffects({"stiffness"}));
  EXPECT_EQ(phaseAt(d, phases, 0.3), Phase::kSliding);
  EXPECT_EQ(phaseAt(d, phases, 1.2), Phase::kRest);
  EXPECT_EQ(phaseAt(d, phases, 2.6), Phase::kRest);
  EXPECT_EQ(phaseAt(d, phases, 3.6), Phase::kSliding);
  EXPECT_EQ(phaseName(Phase::kRest), "rest");
}

// The smoothing keeps a phase whole: no run shorter than the window survives in the middle of
// another phase when one sample's label flips (a noise spike above kRestSpeed at rest).
TEST(Phases, ALoneFlippedSampleDoesNotCutAPhase) {
  std::vector<RegimeSample> regime(50);
  for (auto& r : regime) r.in_contact = true;
  for (std::size_t i = 0; i < 25; ++i) regime[i].speed = 1e-3;  // sliding, then rest
  regime[40].speed = 2e-4;                                      // one noisy sample
  const auto spans = phaseSpans(phasesOf(regime, 2));
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_EQ(spans[0].phase, Phase::kSliding);
  EXPECT_EQ(spans[1].phase, Phase::kRest);
  EXPECT_EQ(spans[1].first, 25u);
}

}  // namespace
}  // namespace vcontact::validation
