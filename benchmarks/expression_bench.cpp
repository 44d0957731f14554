// effect/<form>: the cost of an expression effect against the built-in effects it replaces.
// One contact evaluation (Model::evaluate, the call the integrator and the replay make per
// contact and step) of the sphere pressed 20 µm into a plate, sliding and spinning:
//   effect/builtin     stiffness + coulomb + spin
//   effect/expression  stiffness + the same friction force and spin torque as one expression
//                      effect ("-mu*f_n", "-mu*r_gyr*f_n")
// Both in one run of the binary, so that their ratio is read on the same machine state.

#include <benchmark/benchmark.h>

#include "dynamics/effects/expression.hpp"
#include "dynamics/model.hpp"
#include "volume/analytic/primitive_on_plane.hpp"

namespace {

using namespace vcontact;

volume::ContactVolume sphereContact() {
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  X_WS.translation() = Eigen::Vector3d(0.0, 0.0, 0.01 - 20e-6);
  return volume::sphereHalfspace(0.01, X_WS, Eigen::Isometry3d::Identity());
}

void evaluate(benchmark::State& state, const dynamics::Model& model) {
  const volume::ContactVolume cv = sphereContact();
  dynamics::RelativeMotion motion;
  motion.v_c_W = Eigen::Vector3d(0.01, 0.002, 0.0);
  motion.w_W = Eigen::Vector3d(0.0, 0.0, 3.0);
  dynamics::ContactResult out;
  for (auto _ : state) {
    model.evaluate(cv, motion, dynamics::PairState{}, out);
    benchmark::DoNotOptimize(out.wrench.f_W.data());
  }
  state.counters["evaluations_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void builtin(benchmark::State& state) {
  evaluate(state, dynamics::Model::withEffects({"stiffness", "coulomb", "spin"}));
}

void expression(benchmark::State& state) {
  auto def = std::make_shared<dynamics::ExpressionDefinition>();
  def->id = "friction";
  def->parameters = {{"mu", "-", 0.2, 0.0, 10.0, "friction coefficient"}};
  def->tangential = "-mu*f_n";
  def->spin = "-mu*r_gyr*f_n";
  dynamics::Model m = dynamics::Model::withEffects({"stiffness"});
  m.add(dynamics::makeExpressionEffect(def));
  evaluate(state, m);
}

}  // namespace

BENCHMARK(builtin)->Name("effect/builtin");
BENCHMARK(expression)->Name("effect/expression");
