// The discrete stepper's per-step shortcuts (Simulator::setStepShortcuts, docs/DISCRETE.md
// §4.4) change no number: the same runs with the shortcuts on and off give the same outputs
// and summaries to the bit. The runs cover what each shortcut replaces: steps in contact (the
// linearisation about the query's evaluation, with bristle states and a settle), free flight
// of a tumbling body whose world inertia is a full matrix (the per-body solve), two free
// bodies in one system, and the Dormand–Prince intervals of resolved impacts.

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "dynamics/simulator.hpp"
#include "dynamics_fixtures.hpp"

namespace vcontact::test {
namespace {

using dynamics::ImpactMode;
using dynamics::Integrator;
using dynamics::Model;
using dynamics::Scenario;
using dynamics::SimulationSummary;
using dynamics::Snapshot;
using Eigen::Vector3d;

// The steel model of the rigs with every lumped effect the discrete step linearises.
Model steel() {
  Model m = Model::withEffects(
      {"stiffness", "damping", "rolling_resistance", "coulomb", "stribeck", "bristle", "spin"});
  m.setParameter("stiffness.kv", 1e11);
  m.setParameter("damping.a", 1.0);
  return m;
}

Scenario discrete(Scenario s, double h, double duration, ImpactMode mode) {
  s.settings.integrator = Integrator::kDiscrete;
  s.settings.impacts = mode;
  s.settings.step = h;
  s.settings.duration = duration;
  s.settings.output_rate_hz = 1000.0;
  return s;
}

// A ball thrown onto the plate sideways and spinning: bounces, slides, rolls.
Scenario thrownBall() {
  dynamics::RigidBody ball = freeBody("ball", geometry::Sphere{0.01}, at({0.0, 0.0, 0.014}));
  ball.v_WBcm0 = Vector3d(0.2, 0.05, -0.3);
  ball.w_WB0 = Vector3d(3.0, -20.0, 40.0);
  return onPlate(ball, steel());
}

// A box tumbling in free flight (tilted, spinning about no principal axis: I_W is a full
// matrix and ω changes) that lands on a corner.
Scenario tumblingBox() {
  Eigen::Isometry3d X = at({0.0, 0.0, 0.03});
  X.linear() = Eigen::AngleAxisd(0.4, Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
  dynamics::RigidBody box = freeBody("box", geometry::Box{Vector3d(0.02, 0.012, 0.008)}, X);
  box.w_WB0 = Vector3d(7.0, -4.0, 11.0);
  return onPlate(box, steel());
}

// Two balls dropped from different heights beside each other: two free bodies in one system,
// one in flight while the other lands, and both in flight (the per-body solve of each).
Scenario twoBalls() {
  dynamics::RigidBody low = freeBody("low", geometry::Sphere{0.01}, at({0.0, 0.0, 0.012}));
  low.w_WB0 = Vector3d(0.0, 5.0, -8.0);
  Scenario s = onPlate(low, steel());
  dynamics::RigidBody high = freeBody("high", geometry::Sphere{0.008}, at({0.05, 0.0, 0.02}));
  high.v_WBcm0 = Vector3d(-0.1, 0.0, 0.0);
  s.bodies.push_back(high);
  s.pairs.push_back({"high-plate", 2, 0, steel(), std::nullopt});
  return s;
}

struct Outcome {
  std::vector<Snapshot> outputs;
  SimulationSummary summary;
};

Outcome runWith(const Scenario& s, bool shortcuts) {
  dynamics::Simulator sim(s);
  sim.setStepShortcuts(shortcuts);
  Outcome r;
  sim.run([&](const Snapshot& o) { r.outputs.push_back(o); }, [](double) {}, r.summary);
  return r;
}

bool sameBits(const double* a, const double* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}

// Every number of the outputs that a CSV holds, compared bit for bit.
void expectSame(const Outcome& on, const Outcome& off) {
  ASSERT_EQ(on.outputs.size(), off.outputs.size());
  for (std::size_t k = 0; k < on.outputs.size(); ++k) {
    const Snapshot& a = on.outputs[k];
    const Snapshot& b = off.outputs[k];
    SCOPED_TRACE("output at t = " + std::to_string(a.t));
    ASSERT_EQ(a.t, b.t);
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
      EXPECT_TRUE(sameBits(a.bodies[i].X_WB.matrix().data(), b.bodies[i].X_WB.matrix().data(), 16));
      EXPECT_TRUE(sameBits(a.bodies[i].v_WBcm.data(), b.bodies[i].v_WBcm.data(), 3));
      EXPECT_TRUE(sameBits(a.bodies[i].w_WB.data(), b.bodies[i].w_WB.data(), 3)) << "body " << i;
    }
    for (std::size_t p = 0; p < a.pairs.size(); ++p) {
      const dynamics::PairOutput& x = a.pairs[p];
      const dynamics::PairOutput& y = b.pairs[p];
      EXPECT_TRUE(sameBits(&x.cv.volume, &y.cv.volume, 1)) << "pair " << p;
      EXPECT_TRUE(sameBits(x.result.wrench.f_W.data(), y.result.wrench.f_W.data(), 3));
      EXPECT_TRUE(sameBits(x.result.wrench.tau_W.data(), y.result.wrench.tau_W.data(), 3));
      double sx[dynamics::PairState::kCapacity], sy[dynamics::PairState::kCapacity];
      x.state.pack(sx, dynamics::PairState::kCapacity);
      y.state.pack(sy, dynamics::PairState::kCapacity);
      EXPECT_TRUE(sameBits(sx, sy, dynamics::PairState::kCapacity)) << "pair " << p;
    }
  }
  EXPECT_EQ(on.summary.steps, off.summary.steps);
  EXPECT_EQ(on.summary.rhs_evaluations, off.summary.rhs_evaluations);
  EXPECT_EQ(on.summary.contact_evaluations, off.summary.contact_evaluations);
  EXPECT_EQ(on.summary.resolved_steps, off.summary.resolved_steps);
  EXPECT_EQ(on.summary.impacts.size(), off.summary.impacts.size());
}

// The runs must exercise what they are meant to: contact and flight, and for the resolved
// runs, Dormand–Prince intervals.
void expectContactAndFlight(const Outcome& r, bool resolved) {
  bool contact = false, flight = false;
  for (const Snapshot& s : r.outputs) {
    (s.pairs.front().cv.inContact() ? contact : flight) = true;
  }
  EXPECT_TRUE(contact);
  EXPECT_TRUE(flight);
  if (resolved) {
    EXPECT_GT(r.summary.resolved_steps, 0);
  }
}

TEST(DiscreteShortcuts, SameBitsAsTheGeneralStep) {
  struct Case {
    const char* name;
    Scenario scenario;
    double duration;
  };
  const Case cases[] = {{"thrown ball", thrownBall(), 0.12},
                        {"tumbling box", tumblingBox(), 0.15},
                        {"two balls", twoBalls(), 0.12}};
  for (const Case& c : cases) {
    for (const ImpactMode mode : {ImpactMode::kImplicit, ImpactMode::kResolve}) {
      for (const double h : {1e-3, 5e-4}) {
        SCOPED_TRACE(std::string(c.name) + (mode == ImpactMode::kResolve ? ", resolve" : "") +
                     ", h = " + std::to_string(h));
        const Scenario s = discrete(c.scenario, h, c.duration, mode);
        const Outcome on = runWith(s, true);
        expectSame(on, runWith(s, false));
        expectContactAndFlight(on, mode == ImpactMode::kResolve);
      }
    }
  }
}

}  // namespace
}  // namespace vcontact::test
