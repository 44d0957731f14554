#pragma once
// Scenario builders shared by the dynamics tests: bodies on a half-space plate, runs that keep
// every output snapshot, and the elastic energy of a sphere contact.

#include <cmath>
#include <numbers>
#include <vector>

#include "dynamics/simulator.hpp"
#include "geometry/mass_properties.hpp"

namespace vcontact::test {

constexpr double kSteelDensity = 7900.0;  // kg/m³

inline dynamics::RigidBody plate(const Eigen::Isometry3d& X_WP = Eigen::Isometry3d::Identity()) {
  dynamics::RigidBody b;
  b.name = "plate";
  b.shape = geometry::HalfSpace{};
  b.motion = dynamics::BodyMotion::kFixed;
  b.X_WB0 = X_WP;
  return b;
}

inline dynamics::RigidBody freeBody(const std::string& name, geometry::Shape shape,
                                    const Eigen::Isometry3d& X_WB) {
  dynamics::RigidBody b;
  b.name = name;
  b.shape = std::move(shape);
  b.X_WB0 = X_WB;
  dynamics::setMassFromDensity(b, kSteelDensity);
  return b;
}

/// Body 1 (payload) against body 0 (plate) with `model`.
inline dynamics::Scenario onPlate(dynamics::RigidBody body, dynamics::Model model,
                                  const Eigen::Isometry3d& X_WP = Eigen::Isometry3d::Identity()) {
  dynamics::Scenario s;
  s.bodies = {plate(X_WP), std::move(body)};
  s.pairs.push_back({"payload-plate", 1, 0, std::move(model), std::nullopt});
  return s;
}

/// Every output snapshot of a run; its summary into `summary` when given.
inline std::vector<dynamics::Snapshot> run(const dynamics::Scenario& scenario,
                                           dynamics::SimulationSummary* summary = nullptr) {
  dynamics::Simulator sim(scenario);
  std::vector<dynamics::Snapshot> out;
  dynamics::SimulationSummary local;
  sim.run([&](const dynamics::Snapshot& s) { out.push_back(s); }, [](double) {},
          summary ? *summary : local);
  return out;
}

/// Elastic energy of a sphere (radius R) pressed d into a half-space under `stiffness` alone:
/// E = kv ∫₀^d V(x) dx, V = π x² (3R − x)/3  ⇒  E = kv π (R d³/3 − d⁴/12)  (MODEL.md §5).
inline double sphereElasticEnergy(double kv, double R, double d) {
  if (d <= 0.0) return 0.0;
  return kv * std::numbers::pi * (R * d * d * d / 3.0 - d * d * d * d / 12.0);
}

/// The exact coefficient of restitution for α = a v_in (MODEL.md §5): the root e ∈ (0, 1] of
/// α (1 + e) = ln((1 + α)/(1 − α e)), by bisection (the left side minus the right side is
/// positive at e = 0 and changes sign once below min(1, 1/α)).
inline double exactRestitution(double alpha) {
  auto g = [alpha](double e) {
    return alpha * (1.0 + e) - std::log((1.0 + alpha) / (1.0 - alpha * e));
  };
  double lo = 0.0, hi = std::min(1.0, (1.0 - 1e-15) / alpha);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

inline Eigen::Isometry3d at(const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p;
  return X;
}

}  // namespace vcontact::test
