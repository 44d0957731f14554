#include "validation/phases.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace vcontact::validation {
namespace {

constexpr std::size_t kPhaseCount = 9;

// ε_n of the header: a fraction of the record's largest in-contact |δ̇|.
double normalRateThreshold(const std::vector<RegimeSample>& regime) {
  double most = 0.0;
  for (const auto& r : regime) {
    if (r.in_contact) most = std::max(most, std::abs(r.penetration_rate));
  }
  return std::max(kNormalRateFloor, kNormalRateFraction * most);
}

double tangentialSpeed(const RegimeSample& r) {
  return std::max({r.speed, r.spin_speed, r.roll_speed});
}

// The rest threshold of the header: kRestSpeed, or a share of the record's fastest tangential
// motion in contact when that is higher (velocities differentiated from motion capture are
// noise of 1e-4 m/s or more at rest).
double restThreshold(const std::vector<RegimeSample>& regime) {
  double most = 0.0;
  for (const auto& r : regime) {
    if (r.in_contact) most = std::max(most, tangentialSpeed(r));
  }
  return std::max(kRestSpeed, kRestSpeedFraction * most);
}

Phase rawPhase(const RegimeSample& r, double normalRate, double restSpeed, bool tangentialRecord) {
  if (!r.in_contact) return r.approach_rate >= 0.0 ? Phase::kApproach : Phase::kSeparation;
  if (tangentialSpeed(r) >= restSpeed) {
    if (r.speed >= r.spin_speed && r.speed >= r.roll_speed) return Phase::kSliding;
    return r.spin_speed >= r.roll_speed ? Phase::kSpinning : Phase::kRolling;
  }
  if (r.penetration_rate > normalRate) return Phase::kLoading;
  if (r.penetration_rate < -normalRate) return Phase::kUnloading;
  return tangentialRecord ? Phase::kRest : Phase::kHolding;
}

}  // namespace

std::string_view phaseName(Phase phase) {
  static constexpr std::array<std::string_view, kPhaseCount> kNames = {
      "approach", "separation", "loading",  "holding", "unloading",
      "sliding",  "rolling",    "spinning", "rest"};
  return kNames[static_cast<std::size_t>(phase)];
}

std::vector<Phase> phasesOf(const std::vector<RegimeSample>& regime, std::size_t halfWindow) {
  const double normalRate = normalRateThreshold(regime);
  const double restSpeed = restThreshold(regime);
  const bool tangential = std::any_of(regime.begin(), regime.end(), [&](const RegimeSample& r) {
    return r.in_contact && tangentialSpeed(r) >= restSpeed;
  });
  std::vector<Phase> raw;
  raw.reserve(regime.size());
  for (const auto& r : regime) raw.push_back(rawPhase(r, normalRate, restSpeed, tangential));
  // majority over the window, by a running count
  const std::size_t n = raw.size();
  std::vector<Phase> out(n);
  std::array<std::size_t, kPhaseCount> count{};
  std::size_t lo = 0, hi = 0;  // the window [lo, hi)
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i >= halfWindow ? i - halfWindow : 0;
    const std::size_t b = std::min(n, i + halfWindow + 1);
    for (; hi < b; ++hi) ++count[static_cast<std::size_t>(raw[hi])];
    for (; lo < a; ++lo) --count[static_cast<std::size_t>(raw[lo])];
    Phase best = raw[i];
    for (std::size_t k = 0; k < kPhaseCount; ++k) {
      if (count[k] > count[static_cast<std::size_t>(best)]) best = static_cast<Phase>(k);
    }
    out[i] = best;
  }
  return out;
}

std::vector<PhaseSpan> phaseSpans(const std::vector<Phase>& phases) {
  std::vector<PhaseSpan> spans;
  for (std::size_t i = 0; i < phases.size(); ++i) {
    if (spans.empty() || spans.back().phase != phases[i]) {
      spans.push_back({phases[i], i, i});
    } else {
      spans.back().last = i;
    }
  }
  return spans;
}

}  // namespace vcontact::validation
