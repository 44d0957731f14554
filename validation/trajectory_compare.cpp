#include "validation/trajectory_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "dynamics/simulator.hpp"
#include "volume/contact.hpp"

namespace vcontact::validation {
namespace {

constexpr double kPartPosition = 0.5;  // of h: the paths have parted by half the e_q length
constexpr double kPartAngle = 0.25;    // rad (14°)

double payloadSize(const Dataset& d) { return dynamics::characteristicSize(d.payload); }

double lengthH(const Dataset& d, const TrajectorySettings& s) {
  return std::isnan(s.h) ? 0.5 * payloadSize(d) : s.h;
}

double angleBetween(const Eigen::Matrix3d& R1, const Eigen::Matrix3d& R2) {
  return Eigen::AngleAxisd(R1 * R2.transpose()).angle();
}

bool inContact(const Dataset& d, const Eigen::Isometry3d& X_BA, double margin) {
  const double c = clearance(d, X_BA);
  if (!std::isnan(c)) return c <= margin;
  return volume::computeContact(d.payload, X_BA, d.plate, d.X_BP).aggregate.inContact();
}

// The mean speed of the payload's fastest point over the kRestWindow around sample i, |v̄| +
// |ω̄| r with v̄ and ω̄ from the poses at the window's ends: the velocity columns of a resting
// body hold its ringing on the contact and the noise of differentiated markers, not its motion.
double pointSpeed(const Dataset& d, std::size_t i, double radius) {
  const auto& s = d.samples;
  std::size_t a = i, b = i;
  while (a > 0 && s[i].t - s[a].t < 0.5 * kRestWindow) --a;
  while (b + 1 < s.size() && s[b].t - s[i].t < 0.5 * kRestWindow) ++b;
  if (a == b) return s[i].v_BA.norm() + s[i].w_BA.norm() * radius;
  const double dt = s[b].t - s[a].t;
  const double v = (s[b].X_BA.translation() - s[a].X_BA.translation()).norm() / dt;
  const double w = angleBetween(s[b].X_BA.linear(), s[a].X_BA.linear()) / dt;
  return v + w * radius;
}

// The simulator's outputs, at k / rate s after the first sample.
struct Outputs {
  std::vector<dynamics::BodyKinematics> body;
  std::vector<double> depth;
};

// Pose and velocities at τ from the outputs around it: linear in position and velocity, slerp
// in attitude (exact at output times; the rate is the record's, so sample times are output
// times up to round-off on a uniform record).
void interpolate(const Outputs& o, double tau, double rate, const Eigen::Vector3d& com,
                 SimulatedPath& path) {
  const double k = tau * rate;
  const std::size_t last = o.body.size() - 1;
  const std::size_t k0 = std::min(last, static_cast<std::size_t>(std::max(0.0, std::floor(k))));
  const std::size_t k1 = std::min(last, k0 + 1);
  const double f = std::clamp(k - static_cast<double>(k0), 0.0, 1.0);
  const auto& a = o.body[k0];
  const auto& b = o.body[k1];
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = (1 - f) * a.X_WB.translation() + f * b.X_WB.translation();
  X.linear() = Eigen::Quaterniond(a.X_WB.linear())
                   .slerp(f, Eigen::Quaterniond(b.X_WB.linear()))
                   .toRotationMatrix();
  const Eigen::Vector3d w = (1 - f) * a.w_WB + f * b.w_WB;
  const Eigen::Vector3d v_cm = (1 - f) * a.v_WBcm + f * b.v_WBcm;
  path.X_BA.push_back(X);
  path.w_BA.push_back(w);
  path.v_BA.push_back(v_cm - w.cross(X.linear() * com));  // v_o = v_cm + ω × (o − cm)
  path.penetration.push_back((1 - f) * o.depth[k0] + f * o.depth[k1]);
}

double medianStep(const Dataset& d) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < d.size(); ++i) dt.push_back(d.samples[i].t - d.samples[i - 1].t);
  std::nth_element(dt.begin(), dt.begin() + static_cast<long>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

double noiseOf(const Dataset& d, const std::string& output) {
  const auto it = d.noise.find(output);
  return it == d.noise.end() ? 0.0 : it->second;
}

}  // namespace

const char* trajectoryPhaseName(TrajectoryPhase p) {
  switch (p) {
    case TrajectoryPhase::kFlight:
      return "flight";
    case TrajectoryPhase::kImpact:
      return "impacts";
    case TrajectoryPhase::kSliding:
      return "sliding or rolling";
    case TrajectoryPhase::kRest:
      return "rest";
  }
  return "?";
}

double contactMargin(const Dataset& d) {
  return std::max(3.0 * noiseOf(d, "position"), 0.02 * payloadSize(d));
}

double recordedSink(const Dataset& d) {
  double sink = -std::numeric_limits<double>::infinity();
  for (const Sample& s : d.samples) {
    const double c = clearance(d, s.X_BA);
    if (std::isnan(c)) return c;
    sink = std::max(sink, -c);
  }
  return sink;
}

std::vector<TrajectoryPhase> recordPhases(const Dataset& d) {
  const double size = payloadSize(d);
  const double margin = contactMargin(d);
  std::vector<TrajectoryPhase> phases(d.size(), TrajectoryPhase::kFlight);
  int sinceFlight = kImpactSamples;  // a record that starts in contact starts with no impact
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!inContact(d, d.samples[i].X_BA, margin)) {
      phases[i] = TrajectoryPhase::kFlight;
      sinceFlight = 0;
      continue;
    }
    if (sinceFlight < kImpactSamples && i > 0) {
      phases[i] = TrajectoryPhase::kImpact;
      ++sinceFlight;
      continue;
    }
    sinceFlight = kImpactSamples;
    // hysteresis: a payload at rest stays so until it moves at twice the rest speed, so that
    // the noise of a slowing slide does not flicker between the two
    const double limit =
        (i > 0 && phases[i - 1] == TrajectoryPhase::kRest ? 2.0 : 1.0) * kTossRestSpeed;
    phases[i] =
        pointSpeed(d, i, 0.5 * size) < limit ? TrajectoryPhase::kRest : TrajectoryPhase::kSliding;
  }
  return phases;
}

Trial prepareTrial(Dataset data) {
  Trial t;
  t.data = std::move(data);
  t.start = initialState(t.data);
  t.phases = recordPhases(t.data);
  return t;
}

dynamics::Scenario trialScenario(const Trial& trial, const dynamics::Model& model,
                                 const TrajectorySettings& settings) {
  const Dataset& d = trial.data;
  dynamics::Scenario s;
  dynamics::RigidBody plate;
  plate.name = "plate";
  plate.shape = d.plate;
  plate.motion = dynamics::BodyMotion::kFixed;
  plate.X_WB0 = d.X_BP;
  plate.X_WB0.translation() += settings.plateOffset * d.X_BP.linear().col(2);
  dynamics::RigidBody payload;
  payload.name = d.name.empty() ? "payload" : d.name;
  payload.shape = d.payload;
  payload.surface = d.payload_surface;
  payload.mass = d.inertia->mass;
  payload.I_BBcm_B = d.inertia->inertia;
  payload.p_BBcm = d.inertia->com;
  payload.X_WB0 = trial.start.X_BA;
  payload.v_WBcm0 = trial.start.v_BAcm;
  payload.w_WB0 = trial.start.w_BA;
  s.bodies = {plate, payload};
  dynamics::ContactPair pair;
  pair.name = "payload-plate";
  pair.a = 1;
  pair.b = 0;
  pair.model = model;
  s.pairs = {pair};
  s.gravity_W = d.gravity_B;
  auto& o = s.settings;
  o.integrator = settings.integrator;
  o.duration = d.samples.back().t - d.samples.front().t;
  o.output_rate_hz = 1.0 / medianStep(d);
  o.abs_tol = settings.absTol;
  o.rel_tol = settings.relTol;
  o.step = settings.step;
  // every bounce, however small, is compared with the record: each impact resolved (the
  // scenario default, "auto", would leave rebounds below 0.05 m/s to the plain step)
  o.impacts = dynamics::ImpactMode::kResolve;
  return s;
}

SimulatedPath simulateTrial(const Trial& trial, const dynamics::Model& model,
                            const TrajectorySettings& settings) {
  const Dataset& d = trial.data;
  dynamics::Scenario scenario = trialScenario(trial, model, settings);
  const double rate = scenario.settings.output_rate_hz;
  dynamics::Simulator sim(std::move(scenario));
  sim.setOutputDepths(false);
  Outputs out;
  const auto keep = [&](const dynamics::Snapshot& snap) {
    out.body.push_back(snap.bodies[1]);
    const double c = clearance(d, snap.bodies[1].X_WB);
    const double depth = std::isnan(c) ? snap.pairs[0].cv.depth : settings.plateOffset - c;
    out.depth.push_back(std::isfinite(depth) ? std::max(0.0, depth) : 0.0);
  };
  dynamics::SimulationSummary summary;
  SimulatedPath path;
  try {
    sim.run(
        keep, [](double) {}, summary);
  } catch (const dynamics::SimulationError& e) {
    path.stopped = e.what();
    path.stopTime = e.time();
  }
  for (const Sample& s : d.samples)
    interpolate(out, s.t - d.samples.front().t, rate, d.inertia->com, path);
  return path;
}

TrajectoryErrors trajectoryErrors(const Trial& trial, const SimulatedPath& path,
                                  const TrajectorySettings& settings) {
  const Dataset& d = trial.data;
  TrajectoryErrors e;
  e.h = lengthH(d, settings);
  e.size = payloadSize(d);
  PhaseErrors per[kPhaseCount];
  const auto n = static_cast<double>(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double dp = (path.X_BA[i].translation() - d.samples[i].X_BA.translation()).norm();
    const double theta = angleBetween(path.X_BA[i].linear(), d.samples[i].X_BA.linear());
    e.dp.push_back(dp);
    e.dtheta.push_back(theta);
    e.e_position += dp * dp / e.h / n;
    e.e_attitude += theta * theta / n;
    e.positionFraction += dp / e.size / n;
    e.rotationDeg += theta * 180.0 / std::numbers::pi / n;
    e.maxPenetration = std::max(e.maxPenetration, path.penetration[i]);
    if (std::isnan(e.partTime) && (dp > kPartPosition * e.h || theta > kPartAngle))
      e.partTime = d.samples[i].t - d.samples.front().t;
    PhaseErrors& p = per[static_cast<int>(trial.phases[i])];
    ++p.samples;
    p.e_q += dp * dp / e.h + theta * theta;
    p.positionFraction += dp / e.size;
    p.rotationDeg += theta * 180.0 / std::numbers::pi;
    p.maxPenetration = std::max(p.maxPenetration, path.penetration[i]);
  }
  e.e_q = e.e_position + e.e_attitude;
  for (int k = 0; k < kPhaseCount; ++k) {
    PhaseErrors p = per[k];
    if (p.samples == 0) continue;
    const auto m = static_cast<double>(p.samples);
    p.phase = static_cast<TrajectoryPhase>(k);
    p.e_q /= m;
    p.positionFraction /= m;
    p.rotationDeg /= m;
    e.phases.push_back(p);
  }
  return e;
}

TrialEvaluation evaluateTrial(const dynamics::Model& model, const Trial& trial,
                              const TrajectorySettings& settings) {
  TrialEvaluation r;
  r.path = simulateTrial(trial, model, settings);
  r.errors = trajectoryErrors(trial, r.path, settings);
  r.loss = r.errors.e_q;
  const std::size_t n = trial.data.size();
  r.residuals.resize(static_cast<Eigen::Index>(2 * n));
  const double scale = 1.0 / std::sqrt(r.errors.h);
  for (std::size_t i = 0; i < n; ++i) {
    r.residuals[static_cast<Eigen::Index>(2 * i)] = r.errors.dp[i] * scale;
    r.residuals[static_cast<Eigen::Index>(2 * i + 1)] = r.errors.dtheta[i];
  }
  return r;
}

}  // namespace vcontact::validation
