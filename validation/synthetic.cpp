#include "validation/synthetic.hpp"

#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "geometry/error.hpp"
#include "validation/replay.hpp"

namespace vcontact::validation {
namespace {

constexpr double kPunchRadius = 0.01, kPunchLength = 0.02;  // m
constexpr double kBallRadius = 0.01;                        // m
constexpr double kSlideDepth = 20e-9;  // m: about 30 N on the punch at kv = 5.17e12 N/m³
// Noise σ of a good six-axis load cell at these loads.
constexpr double kForceNoise = 0.03;        // N
constexpr double kTorqueNoise = 2e-4;       // N·m
constexpr double kSmallTorqueNoise = 2e-5;  // N·m, ball rolling (mN·m torques)

// The prescribed motion at time t (s): depth of the lowest point below the plate surface,
// its rate, the in-plane velocity of the payload origin, spin about z and roll about x.
struct RigState {
  double depth = 0.0, depthRate = 0.0;  // m, m/s
  double vx = 0.0, vy = 0.0;            // m/s
  double wz = 0.0, wx = 0.0;            // rad/s
};

struct Profile {
  std::string name;
  double duration;  // s
  bool ball;        // else punch
  std::vector<std::string> outputs;
  std::function<RigState(double)> at;
};

// Smooth step 0 → 1 over [t0, t0 + w] (half cosine).
double smoothStep(double t, double t0, double w) {
  if (t <= t0) return 0.0;
  if (t >= t0 + w) return 1.0;
  return 0.5 - 0.5 * std::cos(M_PI * (t - t0) / w);
}

RigState loading(double t) {
  constexpr double T = 2.0, dMax = 55e-9, dOff = 5e-9;  // s, m, m
  const double s = std::sin(M_PI * t / T);
  return {dMax * s * s - dOff, dMax * 2.0 * s * std::cos(M_PI * t / T) * M_PI / T};
}

RigState impacts(double t) {
  constexpr double period = 0.25, dMax = 10e-6, lift = 2e-6;  // s, m, m
  constexpr double contact[4] = {0.04, 0.06, 0.1, 0.15};      // s in contact per impact
  const int k = std::min(3, static_cast<int>(t / period));
  const double s = t - k * period, tc = contact[k];
  if (s < tc) return {dMax * std::sin(M_PI * s / tc), dMax * M_PI / tc * std::cos(M_PI * s / tc)};
  const double w = period - tc;
  return {-lift * std::sin(M_PI * (s - tc) / w), -lift * M_PI / w * std::cos(M_PI * (s - tc) / w)};
}

RigState frictionRamp(double t) {
  constexpr double T = 2.0, vMax = 4e-3;  // s, m/s
  const double s = std::sin(2.0 * M_PI * t / T);
  return {kSlideDepth, 0.0, vMax * s * s * s};
}

RigState drive(double t) {
  constexpr double T = 3.0, ramp = 0.05;                                   // s
  constexpr double level[6] = {0.5e-3, 2e-3, 6e-3, 15e-3, -3e-3, -10e-3};  // m/s
  double v = level[0];
  for (int k = 1; k < 6; ++k) v += (level[k] - level[k - 1]) * smoothStep(t, k * T / 6, ramp);
  return {kSlideDepth, 0.0, v};
}

RigState dwell(double t) {
  constexpr double v0 = 2e-3, ramp = 0.1;  // m/s, s
  // Slide 0.4 s, stop 0.1 s, slide 0.4 s, stop 0.5 s, slide 0.4 s, stop 1.5 s, slide.
  constexpr double stops[3][2] = {{0.4, 0.1}, {0.9, 0.5}, {1.8, 1.5}};
  double v = v0 * smoothStep(t, 0.0, ramp);
  for (const auto& s : stops)
    v -= v0 * (smoothStep(t, s[0], ramp) - smoothStep(t, s[0] + s[1], ramp));
  return {kSlideDepth, 0.0, v};
}

RigState slideSpin(double t) {
  constexpr double T = 3.0, v0 = 3e-3, w0 = 1.2;  // s, m/s, rad/s
  return {kSlideDepth, 0.0, v0 * std::cos(0.5 * M_PI * t / T), 0.3 * v0 * std::sin(M_PI * t / T),
          w0 * std::sin(0.5 * M_PI * t / T)};
}

RigState rolling(double t) {
  constexpr double T = 2.0, d0 = 5e-6, w0 = 2.0;  // s, m, rad/s
  const double f = 3.0 * 2.0 * M_PI / T;          // depth wobble, rad/s
  RigState r{d0 * (1.0 + 0.2 * std::sin(f * t)), d0 * 0.2 * f * std::cos(f * t)};
  r.wx = w0 * std::sin(2.0 * M_PI * t / T);
  r.vy = r.wx * kBallRadius;  // rolling without slip: v_c = v + ω × (0, 0, −R) = 0
  return r;
}

// Piecewise-linear indentation: approach, loading at a constant rate, hold, unloading at the
// same rate, separated. The depth of the sphere's lowest point below the surface.
RigState indentation(double t) {
  constexpr double dMax = 8e-6, lift = 2e-6;                // m
  constexpr double tTouch = 0.3, tLoad = 1.2, tHold = 1.0;  // s
  constexpr double rate = dMax / tLoad;                     // m/s: 6.7 µm/s
  const double tUnload = tTouch + tLoad + tHold, tOff = tUnload + tLoad;
  if (t < tTouch) return {-lift + lift * t / tTouch, lift / tTouch};
  if (t < tTouch + tLoad) return {rate * (t - tTouch), rate};
  if (t < tUnload) return {dMax, 0.0};
  if (t < tOff) return {dMax - rate * (t - tUnload), -rate};
  return {-lift * std::min(1.0, (t - tOff) / tTouch), -lift / tTouch};
}

const std::vector<Profile>& profiles() {
  static const std::vector<Profile> p = {
      {"loading", 2.0, false, {"fz", "tx", "ty"}, loading},
      {"impacts", 1.0, true, {"fz"}, impacts},
      {"friction-ramp", 2.0, false, {"fx", "fz"}, frictionRamp},
      {"drive", 3.0, false, {"fx", "fz"}, drive},
      {"dwell", 4.0, false, {"fx", "fz"}, dwell},
      {"slide-spin", 3.0, false, {"fx", "fy", "fz", "tz"}, slideSpin},
      {"rolling", 2.0, true, {"fz", "tx"}, rolling},
      {"indentation", 4.0, true, {"fz"}, indentation},
  };
  return p;
}

const Profile& profileNamed(const std::string& name) {
  for (const auto& p : profiles()) {
    if (p.name == name) return p;
  }
  std::ostringstream s;
  s << "unknown rig profile '" << name << "'; expected one of:";
  for (const auto& p : profiles()) s << ' ' << p.name;
  throw InputError("rig profile", s.str());
}

void setColumn(Dataset& d, const std::string& name, std::size_t i, double v) {
  auto& c = d.columns[name];
  if (c.size() == 0) c.setZero(static_cast<Eigen::Index>(d.samples.size()));
  c[static_cast<Eigen::Index>(i)] = v;
}

}  // namespace

Dataset rigMotion(const std::string& name, std::size_t n) {
  const Profile& profile = profileNamed(name);
  if (n < 3) throw InputError("sample count", "a record needs at least 3 samples");
  Dataset d;
  d.name = profile.name;
  d.notes = "synthetic: rig profile '" + profile.name +
            "' replayed through a known model by vcontact synth, Gaussian noise added";
  d.payload = profile.ball ? geometry::Shape(geometry::Sphere{kBallRadius})
                           : geometry::Shape(geometry::Cylinder{kPunchRadius, kPunchLength});
  d.plate = geometry::HalfSpace{};
  d.outputs = profile.outputs;
  const double lowest = profile.ball ? kBallRadius : 0.5 * kPunchLength;  // origin height at touch
  d.samples.resize(n);
  Eigen::Vector2d p_xy = Eigen::Vector2d::Zero();
  double spin = 0.0, roll = 0.0;  // rad
  RigState prev = profile.at(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = profile.duration * static_cast<double>(i) / static_cast<double>(n - 1);
    const RigState r = profile.at(t);
    if (i > 0) {  // trapezoidal integration of the in-plane motion and the angles
      const double dt = t - d.samples[i - 1].t;
      p_xy += 0.5 * dt * Eigen::Vector2d(prev.vx + r.vx, prev.vy + r.vy);
      spin += 0.5 * dt * (prev.wz + r.wz);
      roll += 0.5 * dt * (prev.wx + r.wx);
    }
    prev = r;
    Sample& s = d.samples[i];
    s.t = t;
    s.X_BA.linear() = (Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
    s.X_BA.translation() = Eigen::Vector3d(p_xy.x(), p_xy.y(), lowest - r.depth);
    s.v_BA = Eigen::Vector3d(r.vx, r.vy, -r.depthRate);
    // Only one of spin and roll is non-zero in every profile, so ω is the plain sum.
    s.w_BA = Eigen::Vector3d(r.wx, 0.0, r.wz);
    const Eigen::Quaterniond q(s.X_BA.linear());
    const double values[] = {t,
                             s.X_BA.translation().x(),
                             s.X_BA.translation().y(),
                             s.X_BA.translation().z(),
                             q.w(),
                             q.x(),
                             q.y(),
                             q.z(),
                             s.v_BA.x(),
                             s.v_BA.y(),
                             s.v_BA.z(),
                             s.w_BA.x(),
                             s.w_BA.y(),
                             s.w_BA.z()};
    const char* names[] = {"t",  "x",  "y",  "z",  "qw", "qx", "qy",
                           "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
    for (std::size_t c = 0; c < std::size(names); ++c) setColumn(d, names[c], i, values[c]);
  }
  for (const auto& o : d.outputs)
    d.noise[o] = o[0] == 'f' ? kForceNoise : profile.ball ? kSmallTorqueNoise : kTorqueNoise;
  return d;
}

void synthesizeMeasurement(Dataset& d, const dynamics::Model& truth, unsigned seed) {
  Replayer replayer(d);
  const Prediction p = replayer.run(truth);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& o : d.outputs) {
    Eigen::VectorXd y = p.column(o);
    const auto sigma = d.noise.find(o);  // none: an exact record (synth --noise-scale 0)
    if (sigma != d.noise.end()) {
      for (Eigen::Index i = 0; i < y.size(); ++i) y[i] += sigma->second * normal(rng);
    }
    d.columns[o] = y;
  }
}

}  // namespace vcontact::validation
