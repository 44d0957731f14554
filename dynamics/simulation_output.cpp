#include "dynamics/simulation_output.hpp"

#include <sstream>

#include "geometry/error.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {

std::string stopTime(double t) {
  std::ostringstream s;
  s.precision(9);
  s << "t = " << t << " s";
  return s.str();
}

const char* stopCauseName(StopCause cause) {
  switch (cause) {
    case StopCause::kNonFinite:
      return "non_finite_state";
    case StopCause::kStepCollapse:
      return "step_size_collapse";
    case StopCause::kPenetration:
      return "penetration_beyond_bound";
    case StopCause::kBlowUp:
      return "blow_up";
    case StopCause::kInterrupted:
      return "interrupted";
    case StopCause::kIntegratorFailure:
      break;
  }
  return "integrator_failure";
}

int patchSlots(const Scenario& s, const ContactPair& p) {
  if (p.friction == FrictionMode::kDistributed) return 1;
  if (p.method == volume::Method::kAnalytic) return 1;
  if (volume::convexSolid(s.bodies[p.a].shape) && volume::convexSolid(s.bodies[p.b].shape))
    return 1;
  if (p.max_patches < kMinMaxPatches || p.max_patches > kMaxMaxPatches) {
    throw InputError("pair '" + p.name + "'", "max_patches " + std::to_string(p.max_patches) +
                                                  " is outside [" + std::to_string(kMinMaxPatches) +
                                                  ", " + std::to_string(kMaxMaxPatches) + "]");
  }
  return p.max_patches;
}

}  // namespace vcontact::dynamics
