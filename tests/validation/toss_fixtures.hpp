#pragma once
// Tosses the engine makes itself (tests of the trajectory compare and fit): a box released
// over a half-space from a known state, simulated with a known model, recorded at a fixed
// rate with optional Gaussian noise on position and attitude.

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "validation/trajectory_compare.hpp"

namespace vcontact::validation::testing {

struct TossSpec {
  Eigen::Vector3d size = Eigen::Vector3d(0.1, 0.1, 0.1);                    ///< m
  double mass = 0.37;                                                       ///< kg
  Eigen::Vector3d inertia = Eigen::Vector3d::Constant(0.37 * 0.02 / 12.0);  ///< kg m²
  Eigen::Isometry3d X0 = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();
  double duration = 0.6;  ///< s
  double rate = 100.0;    ///< Hz
};

/// The model of the tests' tosses: a soft contact (a 0.1 m cube sinks 0.2 mm resting on a
/// face), a little damping, μ = 0.3, and friction regularised over 0.1 mm/s (v_eps) instead
/// of the default 0.01 mm/s. A box that sticks is stiff in the tangent by μ f_n / v_eps, and
/// the discrete stepper's resolved impacts integrate it with Dormand–Prince, whose step falls
/// with v_eps: a 0.1 m box settling after a toss cost 1.03 M contact evaluations for 0.3 s at
/// the default, 108 k at 1e-4 and 12 k at 1e-3, its final pose moved by 1.5 µm and 16 µm
/// (the record's noise in these tests is 100–200 µm).
inline dynamics::Model tossModel() {
  dynamics::Model m = dynamics::Model::withEffects({"stiffness", "damping", "coulomb"});
  m.settings.v_eps = 1e-4;
  m.setParameter("stiffness.kv", 2e6);
  m.setParameter("damping.a", 3.0);
  m.setParameter("coulomb.mu", 0.3);
  return m;
}

/// A dynamic dataset of `spec` with every sample at the initial state (the times only).
inline Dataset tossTemplate(const TossSpec& spec, const std::string& name) {
  Dataset d;
  d.mode = DatasetMode::kDynamic;
  d.name = name;
  d.payload = geometry::Box{spec.size};
  d.plate = geometry::HalfSpace{};
  d.outputs = {"position", "attitude"};
  d.inertia = PayloadInertia{spec.mass, spec.inertia.asDiagonal(), Eigen::Vector3d::Zero()};
  const auto n = static_cast<std::size_t>(std::lround(spec.duration * spec.rate)) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    Sample s;
    s.t = static_cast<double>(i) / spec.rate;
    s.X_BA = spec.X0;
    s.v_BA = spec.v0;
    s.w_BA = spec.w0;
    d.samples.push_back(s);
  }
  return d;
}

/// The trial of `spec` simulated by `truth` (plate offset `offset`), recorded with noise of
/// σ_position (m) and σ_attitude (rad) per component; the first sample keeps the exact state
/// and the velocity columns (the initial state is given). By default the record is made by the
/// integrator and tolerances a fit uses (TrajectorySettings' defaults), so that the truth is a
/// point of the fitted model; dopri5 where a test needs free flight exact to round-off.
inline Trial makeToss(const TossSpec& spec, const dynamics::Model& truth, double offset,
                      double sigmaPosition, double sigmaAttitude, unsigned seed,
                      const std::string& name,
                      dynamics::Integrator integrator = TrajectorySettings{}.integrator) {
  Trial t;
  t.data = tossTemplate(spec, name);
  t.start = initialState(t.data);
  TrajectorySettings s;
  s.plateOffset = offset;
  s.integrator = integrator;
  const SimulatedPath path = simulateTrial(t, truth, s);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t i = 0; i < t.data.size(); ++i) {
    Sample& r = t.data.samples[i];
    r.X_BA = path.X_BA[i];
    r.v_BA = path.v_BA[i];
    r.w_BA = path.w_BA[i];
    if (i == 0) continue;
    r.X_BA.translation() += sigmaPosition * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Vector3d phi = sigmaAttitude * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    if (phi.norm() > 0)
      r.X_BA.linear() =
          Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix() * r.X_BA.linear();
  }
  t.data.noise = {{"position", std::max(sigmaPosition, 1e-12)},
                  {"attitude", std::max(sigmaAttitude, 1e-12)}};
  t.phases = recordPhases(t.data);
  return t;
}

/// Four tosses of `duration` s that land sliding in different directions and spins, with the
/// plate at `offset`, recorded with noise σ_position = sigma and σ_attitude = 10 sigma.
inline std::vector<Trial> fourTosses(const dynamics::Model& model, double offset, double sigma,
                                     double duration) {
  std::vector<Trial> out;
  for (int k = 0; k < 4; ++k) {
    TossSpec spec;
    const double a = 0.7 * k;
    spec.X0.translation() = Eigen::Vector3d(0, 0, 0.09 + 0.01 * k);
    spec.X0.linear() = Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitX()).toRotationMatrix();
    spec.v0 = Eigen::Vector3d(0.8 * std::cos(a), 0.8 * std::sin(a), -0.2);
    spec.w0 = Eigen::Vector3d(0, 0, 1.0 + k);
    spec.duration = duration;
    out.push_back(
        makeToss(spec, model, offset, sigma, 10 * sigma, 11 + k, "toss" + std::to_string(k)));
  }
  return out;
}

}  // namespace vcontact::validation::testing
