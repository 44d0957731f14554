#pragma once
// A record that needs a load-dependent friction coefficient: the drive profile with the punch's
// depth swinging between 10 and 30 nm (three cycles), so that the load varies while it slides,
// and the hidden effect μ(f_n) = μ_C + b f_n as the expression effect "mu_load" (-b*f_n^2).

#include <cmath>
#include <numbers>

#include "dynamics/effects/expression.hpp"
#include "validation/synthetic.hpp"

namespace vcontact::test {

inline std::unique_ptr<dynamics::Effect> muLoad(double b) {
  auto d = std::make_shared<dynamics::ExpressionDefinition>();
  d->id = "mu_load";
  d->parameters = {{"b", "1/N", 0.0, 0.0, 1.0, "growth of mu with the load"}};
  d->tangential = "-b*f_n^2";
  d->requires_list = {"stiffness", "coulomb"};
  auto e = dynamics::makeExpressionEffect(d);
  e->setParameter(0, b);
  return e;
}

inline validation::Dataset loadVaryingDrive(std::size_t n) {
  validation::Dataset d = validation::rigMotion("drive", n);
  const double T = d.samples.back().t / 3.0, w = 2.0 * std::numbers::pi / T;
  for (std::size_t i = 0; i < n; ++i) {
    validation::Sample& s = d.samples[i];
    const double depth0 = 0.01 - s.X_BA.translation().z();  // 20 nm
    const double depth = depth0 * (1.0 + 0.5 * std::sin(w * s.t));
    s.X_BA.translation().z() = 0.01 - depth;
    s.v_BA.z() = -depth0 * 0.5 * w * std::cos(w * s.t);
    d.columns["z"][static_cast<Eigen::Index>(i)] = s.X_BA.translation().z();
    d.columns["vz"][static_cast<Eigen::Index>(i)] = s.v_BA.z();
  }
  return d;
}

}  // namespace vcontact::test
