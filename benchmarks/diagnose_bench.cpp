// diagnose/<profile>/<samples>: `vcontact diagnose` on a synthetic friction record with the
// full candidate list (every effect the start model lacks), candidates in parallel (TBB).
// Issue #5 target: 6000 samples in ≤ 30 s on the 2-core reference machine.

#include <benchmark/benchmark.h>

#include "dynamics/effects/registry.hpp"
#include "validation/diagnose.hpp"
#include "validation/synthetic.hpp"

namespace {

using namespace vcontact;

// Friction ramp through zero speed (presliding, breakaway) with bristle friction in the data;
// the start model is Coulomb friction only.
void BM_DiagnoseFrictionRamp(benchmark::State& state) {
  dynamics::Model truth = dynamics::Model::withEffects({"stiffness", "coulomb", "bristle"});
  truth.setParameter("stiffness.kv", 4.2e12);
  truth.setParameter("coulomb.mu", 0.15);
  truth.setParameter("bristle.sigma0", 6000.0);
  validation::Dataset d =
      validation::rigMotion("friction-ramp", static_cast<std::size_t>(state.range(0)));
  validation::synthesizeMeasurement(d, truth, 1);
  const dynamics::Model start = dynamics::Model::withEffects({"stiffness", "coulomb"});
  const auto noise = validation::noiseLevels(d);
  validation::Diagnosis result;
  for (auto _ : state) {
    result = validation::diagnose(d, noise, start);
    benchmark::DoNotOptimize(result);
  }
  const auto& s = result.stages.front();
  state.counters["candidates"] = static_cast<double>(s.ranking.size());
  state.counters["baseline_chi"] = s.baseline.comparison.chi;
  state.counters["best_chi"] = s.ranking.front().fit.comparison.chi;
  state.SetLabel("verdict " + s.verdict);
}
BENCHMARK(BM_DiagnoseFrictionRamp)
    ->Name("diagnose/friction-ramp")
    ->Arg(6000)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
