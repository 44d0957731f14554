#pragma once
// Synthetic identification cases shared by the validation tests: for every effect of the
// library, the rig profile that exercises it, the true model and the start model without it.

#include <map>
#include <string>
#include <vector>

#include "dynamics/effects/registry.hpp"
#include "dynamics/model.hpp"
#include "validation/synthetic.hpp"

namespace vcontact::test {

/// True parameter values of the synthetic rig (MODEL.md §4 magnitudes, deliberately away from
/// the library defaults so that a fit has to move).
inline const std::map<std::string, double>& trueParameters() {
  static const std::map<std::string, double> p = {
      {"stiffness.kv", 4.2e12},    {"damping.a", 400.0},        {"coulomb.mu", 0.15},
      {"coulomb.v_s", 1.5e-3},     {"stribeck.mu_s", 0.3},      {"bristle.sigma0", 6000.0},
      {"bristle.sigma1", 300.0},   {"viscous.sigma2", 4.0},     {"dwell.tau_dw", 0.4},
      {"misalignment.rx", 1.5e-6}, {"misalignment.ry", -1e-6},  {"power_law.p", 0.75},
      {"viscoelastic.tau", 0.3},   {"viscoelastic.ratio", 0.6}, {"adhesion.sigma_a", 2e6}};
  return p;
}

/// A model of `ids` with the true parameter values.
inline dynamics::Model trueModel(const std::vector<std::string>& ids) {
  dynamics::Model m = dynamics::Model::withEffects(ids);
  for (const auto& name : m.parameterNames()) m.setParameter(name, trueParameters().at(name));
  return m;
}

struct EffectCase {
  std::string effect;              ///< hidden in the start model
  std::string profile;             ///< rig profile that exercises it
  std::vector<std::string> truth;  ///< effects of the simulated data
  std::size_t samples;
};

/// One case per effect of the library.
inline const std::vector<EffectCase>& effectCases() {
  static const std::vector<EffectCase> c = {
      {"stiffness", "loading", {"stiffness"}, 300},
      {"damping", "impacts", {"stiffness", "damping"}, 400},
      {"rolling_resistance", "rolling", {"stiffness", "damping", "rolling_resistance"}, 300},
      {"coulomb", "drive", {"stiffness", "coulomb"}, 300},
      {"stribeck", "friction-ramp", {"stiffness", "coulomb", "stribeck"}, 400},
      {"bristle", "friction-ramp", {"stiffness", "coulomb", "bristle"}, 400},
      {"viscous", "drive", {"stiffness", "coulomb", "viscous"}, 300},
      {"spin", "slide-spin", {"stiffness", "coulomb", "spin"}, 300},
      {"contensou", "slide-spin", {"stiffness", "coulomb", "spin", "contensou"}, 300},
      {"dwell", "dwell", {"stiffness", "coulomb", "stribeck", "dwell"}, 600},
      {"misalignment", "loading", {"stiffness", "misalignment"}, 300},
      {"power_law", "indentation", {"stiffness", "power_law"}, 400},
      {"viscoelastic", "indentation", {"stiffness", "viscoelastic"}, 400},
      {"adhesion", "indentation", {"stiffness", "adhesion"}, 400},
  };
  return c;
}

/// The true effects without `hidden`, at the library defaults (a fit has to find the values).
inline dynamics::Model startModel(const std::vector<std::string>& truth,
                                  const std::string& hidden) {
  std::vector<std::string> ids;
  for (const auto& id : truth) {
    if (id != hidden) ids.push_back(id);
  }
  dynamics::Model m;
  for (const auto& id : ids) m.add(dynamics::createEffect(id));
  return m;
}

inline validation::Dataset syntheticDataset(const std::string& profile, std::size_t samples,
                                            const dynamics::Model& truth, unsigned seed) {
  validation::Dataset d = validation::rigMotion(profile, samples);
  validation::synthesizeMeasurement(d, truth, seed);
  return d;
}

}  // namespace vcontact::test
