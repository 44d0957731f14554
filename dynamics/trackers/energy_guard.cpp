#include "dynamics/trackers/energy_guard.hpp"

#include <algorithm>
#include <sstream>

#include "dynamics/simulation_output.hpp"

namespace vcontact::dynamics {

EnergyGuard::EnergyGuard(const Scenario& scenario, const std::vector<BodyKinematics>& kin0,
                         const std::vector<PairOutput>& pairs0)
    : scenario_(scenario) {
  for (std::size_t i = 0; i < scenario.bodies.size(); ++i) {
    p0_W_.push_back(kin0[i].p_WBcm);
    if (scenario.bodies[i].motion != BodyMotion::kFree) continue;
    kinetic0_ += kineticEnergy(i, kin0[i]);
    floor_ += 0.5 * scenario.bodies[i].mass * kBlowUpFloorSpeed * kBlowUpFloorSpeed;
  }
  for (const PairOutput& p : pairs0) {
    if (p.cv.inContact()) contact0_ += std::abs(p.result.f_n) * p.cv.depth;
  }
}

// ½ m v² + ½ ωᵀ (R I_B Rᵀ) ω, J.
double EnergyGuard::kineticEnergy(std::size_t i, const BodyKinematics& k) const {
  const RigidBody& b = scenario_.bodies[i];
  const Eigen::Vector3d w_B = k.X_WB.linear().transpose() * k.w_WB;
  return 0.5 * b.mass * k.v_WBcm.squaredNorm() + 0.5 * w_B.dot(b.I_BBcm_B * w_B);
}

// W, the power the non-free bodies put into their contacts: the wrench on A (f, τ at p_c) is
// −(f, τ) on B, so B delivers f·v_B(p_c) + τ·ω_B and A, when it is the moving one, −(f·v_A(p_c) +
// τ·ω_A). Fixed bodies deliver nothing (their velocity is zero).
double EnergyGuard::prescribedPower(const std::vector<BodyKinematics>& kin,
                                    const std::vector<PairOutput>& pairs) const {
  double power = 0.0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const PairOutput& p = pairs[k];
    if (!p.cv.inContact()) continue;
    const ContactPair& pair = scenario_.pairs[k];
    const Wrench& w = p.result.wrench;
    const auto delivered = [&](std::size_t body) {
      return w.f_W.dot(kin[body].pointVelocity(p.cv.p_WC)) + w.tau_W.dot(kin[body].w_WB);
    };
    if (scenario_.bodies[pair.b].motion == BodyMotion::kPrescribed) power += delivered(pair.b);
    if (scenario_.bodies[pair.a].motion == BodyMotion::kPrescribed) power -= delivered(pair.a);
  }
  return power;
}

// W, the power of the loads and springs on the free bodies (a fixed or prescribed body takes
// its share as a support would, moving nothing).
double EnergyGuard::loadPower(const std::vector<BodyKinematics>& kin,
                              const std::vector<LoadOutput>& loads) const {
  const auto on = [&](std::size_t body, const Eigen::Vector3d& f, const Eigen::Vector3d& tau,
                      const Eigen::Vector3d& p) {
    if (scenario_.bodies[body].motion != BodyMotion::kFree) return 0.0;
    return f.dot(kin[body].pointVelocity(p)) + tau.dot(kin[body].w_WB);
  };
  double power = 0.0;
  const std::size_t n_loads = scenario_.loads.size();
  for (std::size_t k = 0; k < loads.size(); ++k) {
    const LoadOutput& o = loads[k];
    if (k < n_loads) {
      power += on(scenario_.loads[k].body, o.wrench.f_W, o.wrench.tau_W, o.p_W);
      continue;
    }
    const BodySpring& spring = scenario_.springs[k - n_loads];
    power += on(spring.a, o.wrench.f_W, o.wrench.tau_W, o.p_W);
    power += on(spring.b, -o.wrench.f_W, -o.wrench.tau_W, o.q_W);
  }
  return power;
}

std::string EnergyGuard::check(const std::vector<BodyKinematics>& kin,
                               const std::vector<PairOutput>& pairs,
                               const std::vector<LoadOutput>& loads, double t) {
  work_prescribed_ += std::max(0.0, prescribedPower(kin, pairs)) * (t - t_last_);
  work_loads_ += std::max(0.0, loadPower(kin, loads)) * (t - t_last_);
  t_last_ = t;
  double kinetic = 0.0, gravity_work = 0.0, largest = -1.0;
  std::size_t fastest = 0;
  for (std::size_t i = 0; i < scenario_.bodies.size(); ++i) {
    const RigidBody& b = scenario_.bodies[i];
    if (b.motion != BodyMotion::kFree) continue;
    const double e = kineticEnergy(i, kin[i]);
    kinetic += e;
    gravity_work += b.mass * scenario_.gravity_W.dot(kin[i].p_WBcm - p0_W_[i]);
    if (e > largest) {
      largest = e;
      fastest = i;
    }
  }
  const double available = kinetic0_ + gravity_work + contact0_ + work_prescribed_ + work_loads_;
  if (!(kinetic > kBlowUpFactor * std::max(available, 0.0) + floor_)) return "";
  std::ostringstream s;
  s << "body '" << scenario_.bodies[fastest].name << "' (speed " << kin[fastest].v_WBcm.norm()
    << " m/s): the free bodies' kinetic energy " << kinetic << " J is more than " << kBlowUpFactor
    << " times the energy the scenario can have given them, " << available << " J (initial kinetic "
    << kinetic0_ << " J, work of gravity " << gravity_work << " J, contact energy at t = 0 "
    << contact0_ << " J, work of prescribed bodies " << work_prescribed_
    << " J, work of loads and springs " << work_loads_
    << " J): the integration gains energy; the contact is too stiff for "
    << "the tolerances (lower tolerances.abs and .rel, or the stiffness)";
  return s.str();
}

}  // namespace vcontact::dynamics
