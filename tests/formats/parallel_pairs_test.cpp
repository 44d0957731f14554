// The pairs of a right-hand side evaluated side by side (Simulator::setParallelPairs, TBB;
// issue 33 item 3) give the serial run's numbers to the bit, on one thread and two (the cores
// of this machine; more threads than cores would share them): on the
// bundled parts bin (the housing, a bracket and a hex nut in a bin: 6 mesh pairs, every impact
// resolved by Dormand–Prince and the plain steps between them) and on cad_tray_drop under
// Dormand–Prince (two 12.8k-triangle mesh pairs in contact, a third screened by the broad
// phase). Every output's bodies (pose, twist) and pairs (contact, force, patches) are compared.

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"

namespace vcontact::formats {
namespace {

const std::string kScenarios = std::string(VCONTACT_ASSETS_DIR) + "/scenarios";

bool sameBits(const double* a, const double* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}
bool sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return sameBits(a.data(), b.data(), 3);
}

struct Outputs {
  std::vector<dynamics::Snapshot> outputs;
  dynamics::SimulationSummary summary;
};

// The scenario for `duration`, its pairs in turn (threads 0) or side by side in an arena of
// `threads`.
Outputs run(const dynamics::Scenario& scenario, int threads) {
  dynamics::Simulator sim(scenario);
  sim.setParallelPairs(threads > 0);
  Outputs r;
  const auto go = [&] {
    sim.run([&](const dynamics::Snapshot& s) { r.outputs.push_back(s); }, [](double) {}, r.summary);
  };
  if (threads > 0) {
    tbb::task_arena(threads).execute(go);
  } else {
    go();
  }
  return r;
}

void expectSameBits(const Outputs& a, const Outputs& b, const std::string& what) {
  ASSERT_EQ(a.outputs.size(), b.outputs.size()) << what;
  EXPECT_EQ(a.summary.contact_evaluations, b.summary.contact_evaluations) << what;
  EXPECT_EQ(a.summary.steps, b.summary.steps) << what;
  for (std::size_t i = 0; i < a.outputs.size(); ++i) {
    const dynamics::Snapshot &x = a.outputs[i], &y = b.outputs[i];
    ASSERT_EQ(x.t, y.t) << what;
    for (std::size_t j = 0; j < x.bodies.size(); ++j) {
      const dynamics::BodyKinematics &p = x.bodies[j], &q = y.bodies[j];
      EXPECT_TRUE(sameBits(p.X_WB.matrix().data(), q.X_WB.matrix().data(), 16) &&
                  sameBits(p.v_WBcm, q.v_WBcm) && sameBits(p.w_WB, q.w_WB))
          << what << ": body " << j << " at t = " << x.t;
    }
    for (std::size_t k = 0; k < x.pairs.size(); ++k) {
      const dynamics::PairOutput &p = x.pairs[k], &q = y.pairs[k];
      EXPECT_TRUE(p.cv.volume == q.cv.volume && sameBits(p.cv.p_WC, q.cv.p_WC) &&
                  sameBits(p.result.wrench.f_W, q.result.wrench.f_W) &&
                  sameBits(p.result.wrench.tau_W, q.result.wrench.tau_W) &&
                  p.patches.size() == q.patches.size())
          << what << ": pair " << k << " at t = " << x.t;
    }
  }
}

TEST(ParallelPairs, PartsBinIsTheSerialRunToTheBit) {
  dynamics::Scenario s = readScenarioFile(kScenarios + "/parts_bin.json").scenario;
  s.settings.duration = 0.03;  // the landing: its impacts resolved and the plain steps between
  s.settings.impacts = dynamics::ImpactMode::kResolve;
  const Outputs serial = run(s, 0);
  ASSERT_GT(serial.summary.resolved_steps, 0);  // both paths of the stepper were taken
  for (const int threads : {1, 2}) {
    expectSameBits(serial, run(s, threads), std::to_string(threads) + " threads");
  }
}

TEST(ParallelPairs, CadTrayDropUnderDormandPrinceIsTheSerialRunToTheBit) {
  dynamics::Scenario s = readScenarioFile(kScenarios + "/cad_tray_drop.json").scenario;
  ASSERT_EQ(s.settings.integrator, dynamics::Integrator::kDopri5);
  s.settings.duration = 0.025;  // the tray's pins in the chamfers and the upper tray's landing
  const Outputs serial = run(s, 0);
  for (const int threads : {1, 2}) {
    expectSameBits(serial, run(s, threads), std::to_string(threads) + " threads");
  }
}

}  // namespace
}  // namespace vcontact::formats
