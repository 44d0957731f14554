#include "validation/replay.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <map>
#include <variant>

#include "dynamics/trackers/patch_tracker.hpp"
#include "volume/contact.hpp"

namespace vcontact::validation {
namespace {

using dynamics::Model;
using dynamics::PairState;

// Relative size of the state perturbation that measures ∂ẋ/∂x. The rates are affine in the
// states (see the header), so the difference quotient is exact up to round-off; 1e-3 keeps
// the difference far above it.
constexpr double kStatePerturbation = 1e-3;
// Floor of the perturbation for a state at zero: far below any bristle deflection (m) or
// angle (rad) a rig resolves, far above round-off.
constexpr double kStatePerturbationFloor = 1e-12;

// φ(a) = (e^a − 1)/a, with φ(0) = 1.
double phi(double a) { return std::abs(a) < 1e-12 ? 1.0 + 0.5 * a : std::expm1(a) / a; }

// Geometry key: ids and parameters of the effects that act before the geometry.
std::vector<double> geometryKey(const Model& model) {
  std::vector<double> key;
  for (std::size_t i = 0; i < model.effectCount(); ++i) {
    const auto& e = model.effect(i);
    if (e.stage() != dynamics::Stage::kGeometryOnly) continue;
    key.push_back(static_cast<double>(std::hash<std::string_view>{}(e.id())));
    for (double p : e.parameters()) key.push_back(p);
  }
  return key;
}

// The contact of a body with the half-space z ≤ 0 depends only on the plane in body
// coordinates: its normal b = R_PBᵀ e_z and the origin height z. Poses that differ by a
// rotation about e_z and an in-plane translation (sliding, spinning) share one volume,
// computed once at a canonical pose and carried over by the in-plane rigid motion
// T = X_BA' X_c⁻¹. Symmetric payloads reduce b further: a sphere ignores its orientation, a
// cylinder its rotation S = Rz(φ) about its own axis (X_BA' = X_BA S turns b into
// (|b_xy|, 0, b_z)). The key is rounded to kKeyResolution so that poses equal up to
// round-off share the entry; the canonical pose is built from the rounded key.
class HalfspaceVolumes {
 public:
  /// @param surface  the payload's recovered surface, or null for its shape as it is
  volume::ContactPatches at(const geometry::Shape& payload, const volume::RecoveredSurface* surface,
                            const Eigen::Isometry3d& X_BA) {
    const Eigen::Isometry3d X = symmetryReduced(payload, X_BA);
    const Eigen::Vector3d b = X.linear().transpose().col(2);
    const std::array<double, 4> key = {rounded(b.x()), rounded(b.y()), rounded(b.z()),
                                       X.translation().z()};
    Eigen::Isometry3d X_c = Eigen::Isometry3d::Identity();
    X_c.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(key[0], key[1], key[2]),
                                                      Eigen::Vector3d::UnitZ())
                       .toRotationMatrix();
    X_c.translation().z() = key[3];
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, atCanonical(payload, surface, X_c)).first;
    const Eigen::Isometry3d T = X * X_c.inverse();
    volume::ContactPatches c = it->second;
    c.aggregate = moved(c.aggregate, T);
    for (volume::ContactVolume& p : c.patches) p = moved(p, T);
    return c;
  }

 private:
  // Plane-normal resolution of the key: a tilt of 1e-15 rad moves a 10 mm part by 1e-17 m,
  // far below any penetration a rig measures.
  static constexpr double kKeyResolution = 1e-15;
  static double rounded(double x) { return std::round(x / kKeyResolution) * kKeyResolution; }

  // On the recovered surface (the method table's `recovered` row: its closed form where one
  // applies, else the exact clip), or on the shape as it is by the default method.
  static volume::ContactPatches atCanonical(const geometry::Shape& payload,
                                            const volume::RecoveredSurface* surface,
                                            const Eigen::Isometry3d& X_c) {
    volume::QueryOptions query;
    if (surface) query.method = volume::Method::kRecovered;
    const geometry::Shape halfspace = geometry::HalfSpace{};
    return volume::computeContact(payload, X_c, halfspace, Eigen::Isometry3d::Identity(), query);
  }

  static Eigen::Isometry3d symmetryReduced(const geometry::Shape& payload, Eigen::Isometry3d X) {
    if (std::holds_alternative<geometry::Sphere>(payload)) {
      X.linear().setIdentity();
    } else if (std::holds_alternative<geometry::Cylinder>(payload)) {
      const Eigen::Vector3d b = X.linear().transpose().col(2);
      X.linear() =
          X.linear() * Eigen::AngleAxisd(std::atan2(b.y(), b.x()), Eigen::Vector3d::UnitZ());
    }
    return X;
  }

 private:
  static volume::ContactVolume moved(volume::ContactVolume cv, const Eigen::Isometry3d& T) {
    if (!cv.inContact()) return cv;
    const Eigen::Matrix3d R = T.linear();
    cv.p_WC = T * cv.p_WC;
    cv.n_W = R * cv.n_W;
    cv.J_v = R * cv.J_v * R.transpose();
    cv.J_s = R * cv.J_s * R.transpose();
    return cv;
  }

  std::map<std::array<double, 4>, volume::ContactPatches> cache_;
};

// The payload's motion at one sample. Its origin stands in for the centre of mass: the velocity
// field v(p) = v_o + ω × (p − p_o) of a rigid body is the same from any of its points.
dynamics::BodyKinematics payloadKinematics(const Sample& s, const Eigen::Isometry3d& X_BA) {
  dynamics::BodyKinematics k;
  k.t = s.t;
  k.X_WB = X_BA;
  k.p_WBcm = X_BA.translation();
  k.v_WBcm = s.v_BA;
  k.w_WB = s.w_BA;
  return k;
}

PatchGeometry patchGeometry(const volume::ContactVolume& cv, const Sample& s,
                            const Eigen::Isometry3d& X_BA) {
  PatchGeometry p;
  p.cv = cv;
  if (!cv.inContact()) return p;
  p.p_AoC_B = cv.p_WC - X_BA.translation();
  p.motion = dynamics::relativeMotion(payloadKinematics(s, X_BA), dynamics::BodyKinematics{},
                                      cv.p_WC);  // the plate does not move
  return p;
}

SampleGeometry sampleGeometry(const Dataset& d, const Sample& s, const Model& model,
                              HalfspaceVolumes& halfspace) {
  const Eigen::Isometry3d X_BB = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d X_BA = model.adjustPayloadPose(s.X_BA, X_BB);
  // The regimes report d and the direct estimates fit V against it (direct_estimates.cpp), so
  // a mesh plate's query asks for the exact depth (`fast` leaves it NaN otherwise).
  volume::QueryOptions query;
  query.depth = volume::DepthMode::kDeepest;
  const volume::ContactPatches c =
      std::holds_alternative<geometry::HalfSpace>(d.plate)
          ? halfspace.at(d.payload, d.payload_surface.get(), X_BA)
          : volume::computeContact(d.payload, X_BA, d.plate, X_BB, query);
  SampleGeometry g;
  static_cast<PatchGeometry&>(g) = patchGeometry(c.aggregate, s, X_BA);
  g.X_BA = X_BA;
  if (c.patches.size() > 1) {
    for (const volume::ContactVolume& cv : c.patches)
      g.patches.push_back(patchGeometry(cv, s, X_BA));
  }
  return g;
}

RegimeSample regimeOf(const SampleGeometry& g, const Sample& s, double load, double v_eps) {
  RegimeSample r;
  r.load = load;
  r.approach_rate = -s.v_BA.z();
  if (!g.cv.inContact()) return r;
  const dynamics::ContactKinematics k = dynamics::resolve(g.motion, g.cv.n_W);
  r.in_contact = true;
  r.volume = g.cv.volume;
  r.depth = g.cv.depth;
  r.speed = k.v_t_W.norm();
  r.spin_speed = g.cv.r_gyr * std::abs(k.omega_n);
  r.spin_ratio = r.spin_speed / std::max(r.speed, v_eps);
  r.roll_speed = k.omega_t_W.norm() * g.p_AoC_B.norm();
  r.penetration_rate = k.delta_dot;
  return r;
}

// Time at rest and the length of the rest before the current motion (stop–dwell–restart).
struct RestClock {
  double since = 0.0, lastRest = 0.0;
  bool resting = false;

  void update(double t, const SampleGeometry& g, RegimeSample& r) {
    if (!g.cv.inContact()) {
      resting = false;
      lastRest = 0.0;
      return;
    }
    const double spin = g.cv.r_gyr * std::abs(dynamics::resolve(g.motion, g.cv.n_W).omega_n);
    const bool atRest = std::hypot(r.speed, spin) < kRestSpeed;
    if (atRest && !resting) since = t;
    if (!atRest && resting) lastRest = t - since;
    resting = atRest;
    r.time_at_rest = atRest ? t - since : 0.0;
    r.preceding_rest = atRest ? 0.0 : lastRest;
  }
};

// One exponential Euler step of the pair state over dt (see the header).
void advance(const Model& model, const volume::ContactVolume& cv,
             const dynamics::RelativeMotion& motion, const dynamics::ContactResult& at, double dt,
             PairState& state) {
  const int size = model.stateLayout().size();
  double x[PairState::kCapacity], rate[PairState::kCapacity];
  state.pack(x, size);
  at.rates.pack(rate, size);
  if (std::all_of(rate, rate + size, [](double r) { return r == 0.0; })) return;
  double h[PairState::kCapacity], xp[PairState::kCapacity];
  for (int j = 0; j < size; ++j) {
    h[j] = kStatePerturbation * std::max(std::abs(x[j]), kStatePerturbationFloor);
    xp[j] = x[j] - h[j];
  }
  double ratep[PairState::kCapacity];
  model.evaluate(cv, motion, PairState::unpack(xp, size)).rates.pack(ratep, size);
  for (int j = 0; j < size; ++j) {
    const double d = std::min(0.0, (rate[j] - ratep[j]) / h[j]);  // decay rate, 1/s
    x[j] += rate[j] * phi(d * dt) * dt;
  }
  state = PairState::unpack(x, size);
}

// Records the first sample whose evaluation is not finite, and the effect responsible.
void noteNonFinite(const Model& model, const dynamics::ContactResult& r, std::size_t sample,
                   Prediction& p) {
  if (p.nonFinite || (r.wrench.f_W.allFinite() && r.wrench.tau_W.allFinite())) return;
  NonFinitePrediction bad{sample, "the model"};
  for (std::size_t e = 0; e < r.shares.size(); ++e) {
    if (r.shares[e].f_W.allFinite() && r.shares[e].tau_W.allFinite()) continue;
    bad.effect = std::string(model.effect(e).id());
    break;
  }
  p.nonFinite = bad;
}

}  // namespace

int wrenchIndex(const std::string& output) {
  const auto it = std::find(kWrenchColumns.begin(), kWrenchColumns.end(), output);
  assert(it != kWrenchColumns.end());
  return static_cast<int>(it - kWrenchColumns.begin());
}

Eigen::VectorXd Prediction::column(const std::string& output) const {
  return wrench.col(wrenchIndex(output));
}

Replayer::Replayer(const Dataset& dataset) : dataset_(dataset) {}

const std::vector<SampleGeometry>& Replayer::geometryFor(const Model& model) {
  std::vector<double> key = geometryKey(model);
  if (cached_ && key == cachedKey_) return *geometry_;
  auto geometry = std::make_shared<std::vector<SampleGeometry>>();
  geometry->reserve(dataset_.size());
  HalfspaceVolumes halfspace;
  for (const auto& s : dataset_.samples) {
    geometry->push_back(sampleGeometry(dataset_, s, model, halfspace));
  }
  geometry_ = std::move(geometry);  // a new vector: copies sharing the old one keep it
  cachedKey_ = std::move(key);
  cached_ = true;
  return *geometry_;
}

Prediction Replayer::run(const Model& model, bool regime) {
  const auto& geometry = geometryFor(model);
  std::size_t most = 1;
  for (const SampleGeometry& g : geometry) most = std::max(most, g.patches.size());
  return most > 1 ? runPatches(model, static_cast<int>(most), regime) : runWhole(model, regime);
}

// Every sample's contact is one region: one set of friction states.
Prediction Replayer::runWhole(const Model& model, bool regime) {
  const auto& geometry = *geometry_;
  const auto& samples = dataset_.samples;
  const std::size_t n = samples.size();
  Prediction p;
  p.wrench.setZero(static_cast<Eigen::Index>(n), 6);
  p.regime.resize(n);
  PairState state;
  RestClock rest;
  for (std::size_t i = 0; i < n; ++i) {
    const SampleGeometry& g = geometry[i];
    model.settle(g.cv, g.motion, state);  // projection, dwell jump, reset out of contact
    const dynamics::ContactResult r = model.evaluate(g.cv, g.motion, state);
    noteNonFinite(model, r, i, p);
    const Eigen::Vector3d tau_Ao = r.wrench.tau_W + g.p_AoC_B.cross(r.wrench.f_W);
    p.wrench.row(static_cast<Eigen::Index>(i)) << r.wrench.f_W.transpose(), tau_Ao.transpose();
    if (regime) {
      p.regime[i] = regimeOf(g, samples[i], r.f_n, model.settings.v_eps);
      rest.update(samples[i].t, g, p.regime[i]);
    }
    if (i + 1 < n) advance(model, g.cv, g.motion, r, samples[i + 1].t - samples[i].t, state);
  }
  return p;
}

// Some sample touches in several regions: one set of friction states per tracked patch
// (dynamics/trackers/patch_tracker.hpp), with as many slots as the most patches of any sample, so
// every patch has its own. A sample of one region is its own single patch.
Prediction Replayer::runPatches(const Model& model, int slots, bool regime) {
  const auto& geometry = *geometry_;
  const auto& samples = dataset_.samples;
  const std::size_t n = samples.size();
  Prediction p;
  p.wrench.setZero(static_cast<Eigen::Index>(n), 6);
  p.regime.resize(n);
  dynamics::PatchTracker tracker(slots);
  std::vector<PairState> states(static_cast<std::size_t>(slots));
  std::vector<volume::ContactVolume> volumes;
  dynamics::PatchMatch match;
  const Eigen::Isometry3d X_BB = Eigen::Isometry3d::Identity();
  RestClock rest;
  for (std::size_t i = 0; i < n; ++i) {
    const SampleGeometry& g = geometry[i];
    // A sample of one region is its own single patch (none out of contact).
    const bool whole = g.patches.empty();
    const PatchGeometry* patches = whole ? &g : g.patches.data();
    const std::size_t count = whole ? (g.cv.inContact() ? 1 : 0) : g.patches.size();
    volumes.clear();
    for (std::size_t j = 0; j < count; ++j) volumes.push_back(patches[j].cv);
    tracker.match(volumes, g.X_BA, X_BB, match);
    std::vector<bool> held(states.size(), false);
    Eigen::Vector3d f = Eigen::Vector3d::Zero(), tau = Eigen::Vector3d::Zero();
    double f_n = 0.0;
    const double dt = i + 1 < n ? samples[i + 1].t - samples[i].t : 0.0;
    for (std::size_t j = 0; j < count; ++j) {
      const PatchGeometry& q = patches[j];
      const int own = match.slot[j];
      PairState& state = states[static_cast<std::size_t>(match.host[j])];
      if (own >= 0) model.settle(q.cv, q.motion, state);
      const dynamics::ContactResult r = model.evaluate(q.cv, q.motion, state);
      noteNonFinite(model, r, i, p);
      f += r.wrench.f_W;
      tau += r.wrench.tau_W + q.p_AoC_B.cross(r.wrench.f_W);
      f_n += r.f_n;
      if (own < 0) continue;  // reads its nearest slot's states and integrates none
      held[static_cast<std::size_t>(own)] = true;
      if (i + 1 < n) advance(model, q.cv, q.motion, r, dt, state);
    }
    for (std::size_t k = 0; k < states.size(); ++k) {
      if (!held[k]) states[k] = PairState{};  // a vanished patch is dropped
    }
    tracker.update(volumes, match, g.X_BA, X_BB);
    p.wrench.row(static_cast<Eigen::Index>(i)) << f.transpose(), tau.transpose();
    if (regime) {
      p.regime[i] = regimeOf(g, samples[i], f_n, model.settings.v_eps);
      rest.update(samples[i].t, g, p.regime[i]);
    }
  }
  return p;
}

}  // namespace vcontact::validation
