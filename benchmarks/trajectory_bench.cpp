// trajectory/<case>: one toss of a 0.1 m cube on a half-space (0.7 s of motion, landing on an
// edge, sliding and settling: the cube-toss record's kind), simulated from its initial state
// by validation::evaluateTrial as a trajectory fit does per trial and parameter vector; the
// reference in the same run is the same cube in free flight over the same 0.7 s (no contact),
// so the figure to read is the ratio. Issue 34's target: a toss in <= 20 ms.
#include <benchmark/benchmark.h>

#include "../tests/validation/toss_fixtures.hpp"

namespace {

using namespace vcontact;

dynamics::Model cubeModel() {
  dynamics::Model m = dynamics::Model::withEffects({"stiffness", "damping", "coulomb", "spin"});
  m.setParameter("stiffness.kv", 1e9);
  m.setParameter("damping.a", 5.0);
  m.setParameter("coulomb.mu", 0.2);
  return m;
}

validation::Trial toss(double height) {
  validation::testing::TossSpec spec;
  spec.size = Eigen::Vector3d::Constant(0.1048);
  spec.inertia = Eigen::Vector3d::Constant(0.00081);
  spec.X0.translation() = Eigen::Vector3d(0, 0, height);
  spec.X0.linear() =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  spec.v0 = Eigen::Vector3d(-1.0, -0.8, -0.6);
  spec.w0 = Eigen::Vector3d(4.3, -3.0, 0.1);
  spec.duration = 0.7;
  spec.rate = 148.0;
  validation::Trial t;
  t.data = validation::testing::tossTemplate(spec, "bench");
  t.start = validation::initialState(t.data);
  t.phases.assign(t.data.size(), validation::TrajectoryPhase::kFlight);
  return t;
}

void run(benchmark::State& state, double height, dynamics::Integrator integrator) {
  const validation::Trial t = toss(height);
  const dynamics::Model model = cubeModel();
  validation::TrajectorySettings s;
  s.integrator = integrator;
  for (auto _ : state) benchmark::DoNotOptimize(validation::evaluateTrial(model, t, s).loss);
}

void BM_TossDiscrete(benchmark::State& s) { run(s, 0.105, dynamics::Integrator::kDiscrete); }
void BM_TossDopri5(benchmark::State& s) { run(s, 0.105, dynamics::Integrator::kDopri5); }
void BM_FreeFlightReference(benchmark::State& s) { run(s, 10.0, dynamics::Integrator::kDiscrete); }

BENCHMARK(BM_TossDiscrete)->Name("trajectory/toss/discrete")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TossDopri5)->Name("trajectory/toss/dopri5")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeFlightReference)
    ->Name("trajectory/free_flight/discrete")
    ->Unit(benchmark::kMillisecond);

}  // namespace
