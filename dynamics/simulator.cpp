#include "dynamics/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <sstream>
#include <string>

#include "dynamics/steppers/bdf_stepper.hpp"
#include "dynamics/steppers/discrete_stepper.hpp"
#include "dynamics/steppers/dopri5_stepper.hpp"
#include "io/interrupt.hpp"

namespace vcontact::dynamics {
namespace {

std::unique_ptr<Stepper> makeStepper(MotionEquations& equations, ImpactTracker& impacts) {
  switch (equations.scenario().settings.integrator) {
    case Integrator::kBdf:
      return std::make_unique<BdfStepper>(equations);
    case Integrator::kDiscrete:
      return std::make_unique<DiscreteStepper>(equations, impacts);
    case Integrator::kDopri5:
      break;
  }
  return std::make_unique<Dopri5Stepper>(equations, impacts);
}

// "interrupted by SIGINT at t = 0.0123 s" (strsignal's words would depend on the locale).
SimulationError interrupted(int signal, double t) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : nullptr;
  std::ostringstream s;
  s << "interrupted by " << (name ? name : "signal " + std::to_string(signal)) << " at t = " << t
    << " s";
  return SimulationError(t, StopCause::kInterrupted, s.str());
}

// The patch figures of one output: the largest count, and the counts of the pairs in contact
// towards the mean.
void countPatches(const Snapshot& s, SimulationSummary& summary, long& samples, long& total) {
  for (const PairOutput& p : s.pairs) {
    summary.patches_max = std::max(summary.patches_max, p.patch_count);
    summary.patches_without_slot += p.without_slot;
    if (p.patch_count == 0) continue;
    ++samples;
    total += p.patch_count;
  }
}

}  // namespace

Simulator::Simulator(Scenario scenario)
    : equations_(std::move(scenario)), stepper_(makeStepper(equations_, impacts_)) {}

Simulator::~Simulator() = default;

void Simulator::run(const std::function<void(const Snapshot&)>& on_output,
                    const std::function<void(double)>& on_progress, SimulationSummary& summary) {
  const Scenario& scenario = equations_.scenario();
  PairContacts& contacts = equations_.contacts();
  const auto wall_start = std::chrono::steady_clock::now();
  const long rhs_start = equations_.rhsCount(), contacts_start = contacts.queries(),
             skipped_start = contacts.skipped();
  double t = 0.0;
  long patch_samples = 0, patch_total = 0;
  const Stepper::OutputFn output = [&](const Snapshot& s) {
    countPatches(s, summary, patch_samples, patch_total);
    on_output(s);
  };
  // Each stepper calls this after every accepted step: the one place an interruption is
  // looked for (a flag read, no system call).
  const Stepper::ProgressFn progress = [&](double t_now) {
    if (const int signal = io::interruptSignal()) throw interrupted(signal, t_now);
    on_progress(t_now);
  };
  auto finish = [&] {
    summary.patches_mean = patch_samples > 0 ? double(patch_total) / double(patch_samples) : 0.0;
    summary.simulated_time = t;
    summary.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    summary.rhs_evaluations = equations_.rhsCount() - rhs_start;
    summary.contact_evaluations = contacts.queries() - contacts_start;
    summary.surface_bodies = contacts.recovered().bodies();
    summary.surface_pairs = contacts.recovered().pairs();
    impacts_.finish(t);
    summary.impacts = impacts_.impacts();
    summary.sleep_events = equations_.sleep().events();
    summary.sleep_skipped_queries = contacts.skipped() - skipped_start;
  };

  equations_.beginRun();
  State x = equations_.initialState();
  State dxdt(x.size());
  equations_.rhs(x, dxdt, t);
  equations_.settle(x, t);
  equations_.rhs(x, dxdt, t);
  output(equations_.firstOutput(x, t));
  // An impact settles once the normal speed stays below the speed at which the discrete
  // stepper resolves impacts (at h = 1 ms at least) for five such steps.
  const double scale = std::max(scenario.settings.step, 1e-3);
  impacts_.reset(scenario, impactThreshold(scenario, scale), 5.0 * scale,
                 scenario.settings.integrator == Integrator::kDiscrete);
  impacts_.observe(t, equations_.bodies(), equations_.pairs());
  try {
    stepper_->run(x, dxdt, t, output, progress, summary);
  } catch (...) {
    finish();
    throw;
  }
  finish();
}

}  // namespace vcontact::dynamics
