// The bundled bin of ten parts (assets/scenarios/bin_of_ten.json, issue 18): the file reads to
// the bodies and the 55 pairs it describes, and the first 50 ms of its discrete run (the lower
// layer lands on the floor) keep every part above the floor within a stated depth and gain no
// mechanical energy beyond a stated bound; the whole run, with sleep, ends with every part asleep.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <variant>

#include "dynamics/simulator.hpp"
#include "formats/scenario_file.hpp"

namespace vcontact::formats {
namespace {

using dynamics::BodyKinematics;
using dynamics::BodyMotion;
using dynamics::RigidBody;
using dynamics::Scenario;
using dynamics::Snapshot;

const std::string kBin = std::string(VCONTACT_ASSETS_DIR) + "/scenarios/bin_of_ten.json";
constexpr double kG = 9.81;

const geometry::TriangleMesh& meshOf(const RigidBody& body) {
  return *std::get<geometry::Mesh>(body.shape).mesh;
}

// Height of the body's lowest vertex in the world frame (m).
double lowestZ(const RigidBody& body, const BodyKinematics& k) {
  const geometry::TriangleMesh& m = meshOf(body);
  double z = INFINITY;
  for (Eigen::Index i = 0; i < m.vertexCount(); ++i) z = std::min(z, (k.X_WB * m.vertex(i)).z());
  return z;
}

// Kinetic plus gravitational energy of the free bodies (J), the floor z = 0 as datum.
double mechanicalEnergy(const Scenario& s, const Snapshot& snap) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const RigidBody& b = s.bodies[i];
    if (b.motion != BodyMotion::kFree) continue;
    const BodyKinematics& k = snap.bodies[i];
    const Eigen::Matrix3d R = k.X_WB.linear();
    const Eigen::Matrix3d I_W = R * b.I_BBcm_B * R.transpose();
    e += 0.5 * b.mass * k.v_WBcm.squaredNorm() + 0.5 * k.w_WB.dot(I_W * k.w_WB) +
         b.mass * kG * k.p_WBcm.z();
  }
  return e;
}

TEST(BinOfTen, PairsAreEveryPartAgainstTheBinAndEachOther) {
  const Scenario s = readScenarioFile(kBin).scenario;
  ASSERT_EQ(s.bodies.size(), 11u);
  EXPECT_EQ(s.bodies[0].name, "bin");
  EXPECT_EQ(s.bodies[0].motion, BodyMotion::kFixed);
  for (std::size_t i = 1; i < s.bodies.size(); ++i) {
    EXPECT_EQ(s.bodies[i].motion, BodyMotion::kFree) << s.bodies[i].name;
    // "about 2,000 triangles each" (scripts/bin_parts.py prints the counts: 1,840 to 2,016)
    const Eigen::Index n = meshOf(s.bodies[i]).triangleCount();
    EXPECT_GE(n, 1800) << s.bodies[i].name;
    EXPECT_LE(n, 2100) << s.bodies[i].name;
  }
  // "contacts" gives every two bodies one pair: C(11, 2) = 55, each once, with the file's
  // model (kv = 1e11 N/m³) and method, named <a>-<b> with the free body as a.
  ASSERT_EQ(s.pairs.size(), 55u);
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (const dynamics::ContactPair& p : s.pairs) {
    EXPECT_TRUE(seen.insert(std::minmax(p.a, p.b)).second) << p.name;
    EXPECT_NE(p.a, 0u) << p.name;  // the bin is fixed, so never the payload
    EXPECT_EQ(p.name, s.bodies[p.a].name + "-" + s.bodies[p.b].name);
    ASSERT_TRUE(p.method.has_value()) << p.name;
    EXPECT_EQ(*p.method, volume::Method::kFast) << p.name;
    EXPECT_EQ(p.model.parameter("stiffness.kv"), 1e11) << p.name;
  }
  EXPECT_EQ(s.settings.integrator, dynamics::Integrator::kDiscrete);
  EXPECT_EQ(s.settings.step, 1e-3);
}

// What a run did at its output times: the largest rise of the free bodies' mechanical energy
// above its value at t = 0, the deepest vertex of a part below the floor z = 0 (which part,
// when), and the last snapshot.
struct LandingRecord {
  double e0 = NAN;
  double worst_gain = -INFINITY;  // J
  double worst_depth = 0.0;       // m
  std::string deepest_part;
  double deepest_at = 0.0;  // s
  Snapshot last;
  double simulated = 0.0;  // s
};

LandingRecord runAndRecord(const Scenario& s, dynamics::SimulationSummary* out = nullptr) {
  LandingRecord r;
  dynamics::Simulator sim(s);
  dynamics::SimulationSummary local;
  dynamics::SimulationSummary& summary = out ? *out : local;
  auto record = [&](const Snapshot& snap) {
    const double e = mechanicalEnergy(s, snap);
    if (std::isnan(r.e0)) r.e0 = e;
    r.worst_gain = std::max(r.worst_gain, e - r.e0);
    for (std::size_t i = 1; i < s.bodies.size(); ++i) {
      const double depth = -lowestZ(s.bodies[i], snap.bodies[i]);
      if (depth <= r.worst_depth) continue;
      r.worst_depth = depth;
      r.deepest_part = s.bodies[i].name;
      r.deepest_at = snap.t;
    }
    r.last = snap;
  };
  sim.run(
      record, [](double) {}, summary);
  r.simulated = summary.simulated_time;
  return r;
}

std::size_t bodyIndex(const Scenario& s, const std::string& name) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies[i].name == name) return i;
  }
  ADD_FAILURE() << "no body " << name;
  return 0;
}

TEST(BinOfTen, FirstLandingsStayAboveTheFloorAndGainNoEnergy) {
  Scenario s = readScenarioFile(kBin).scenario;
  s.settings.duration = 0.05;  // the lower layer (2–6 mm above the floor) lands by 35 ms
  s.settings.output_rate_hz = 1000.0;
  const double h = s.settings.step;
  // Depth bound: a step that starts out of contact moves a part by at most v h into the
  // floor before the contact is seen, v <= sqrt(2 g H) for the largest drop H = 6 mm of a
  // lowest point (the roller), plus the g h² of that step: 0.35 mm. The next step's implicit
  // stiffness removes it. The upper parts (lowest points 18 mm up or more) are still falling
  // at 50 ms (12.3 mm of free fall).
  const double max_depth = std::sqrt(2.0 * kG * 0.006) * h + kG * h * h;
  // Energy bound: the stepper is dissipative (symplectic Euler in flight leads the parabola
  // downward, backward Euler in contact damps), but a part pushed out of a step's penetration
  // may rise by up to g h² more than it sank (DISCRETE.md §5, the hop), m g · g h² per part;
  // twice that per part leaves room for the rounding of E (about 1e-16 · 0.05 J).
  double total_mass = 0.0;
  for (const RigidBody& b : s.bodies) total_mass += b.motion == BodyMotion::kFree ? b.mass : 0;
  const double max_gain = 2.0 * total_mass * kG * kG * h * h;

  const LandingRecord r = runAndRecord(s);
  ASSERT_EQ(r.simulated, 0.05);
  EXPECT_LE(r.worst_depth, max_depth) << r.deepest_part << " at t = " << r.deepest_at;
  EXPECT_LE(r.worst_gain, max_gain) << "E(0) = " << r.e0;
  // Not vacuous: the five parts of the lower layer are on the floor at the end (their lowest
  // vertex within the depth bound of z = 0: they landed, and are not floating above it).
  for (const char* name : {"rounded_block", "washer", "hex_nut", "bored_block", "roller"}) {
    const std::size_t i = bodyIndex(s, name);
    EXPECT_LT(std::abs(lowestZ(s.bodies[i], r.last.bodies[i])), max_depth) << name;
  }
  std::printf(
      "deepest vertex below the floor %.3g m (%s, t = %g s; bound %.3g), largest energy gain "
      "%.3g J (bound %.3g)\n",
      r.worst_depth, r.deepest_part.c_str(), r.deepest_at, max_depth, r.worst_gain, max_gain);
}

// The whole 0.5 s with the scenario's own settings, sleep on (docs/SLEEP.md): every part
// ends asleep, no part sinks below the floor by more than a step's fall allows, and the
// energy gains no more than the first landings' bound.
TEST(BinOfTen, EveryPartEndsAsleepWithinTheBounds) {
  const Scenario s = readScenarioFile(kBin).scenario;
  ASSERT_TRUE(s.settings.sleep.enabled);  // the default of the discrete stepper
  const double h = s.settings.step;
  // As above, for the highest lowest vertex H of a part at t = 0 (a part lands on the floor
  // from at most there): sqrt(2 g H) h + g h².
  double H = 0.0, total_mass = 0.0;
  for (std::size_t i = 1; i < s.bodies.size(); ++i) {
    BodyKinematics k;
    k.X_WB = s.bodies[i].X_WB0;
    H = std::max(H, lowestZ(s.bodies[i], k));
    total_mass += s.bodies[i].mass;
  }
  const double max_depth = std::sqrt(2.0 * kG * H) * h + kG * h * h;
  const double max_gain = 2.0 * total_mass * kG * kG * h * h;
  dynamics::SimulationSummary summary;
  const LandingRecord r = runAndRecord(s, &summary);
  ASSERT_EQ(r.simulated, 0.5);
  EXPECT_LE(r.worst_depth, max_depth) << r.deepest_part << " at t = " << r.deepest_at;
  EXPECT_LE(r.worst_gain, max_gain) << "E(0) = " << r.e0;
  std::set<std::string> asleep;
  for (const dynamics::SleepEvent& e : summary.sleep_events) {
    if (e.asleep) {
      asleep.insert(e.body);
    } else {
      asleep.erase(e.body);
    }
  }
  for (std::size_t i = 1; i < s.bodies.size(); ++i) {
    EXPECT_EQ(asleep.count(s.bodies[i].name), 1u) << s.bodies[i].name;
    EXPECT_EQ(r.last.bodies[i].v_WBcm.norm(), 0.0) << s.bodies[i].name;  // a sleeper is still
  }
  EXPECT_GT(summary.sleep_skipped_queries, 0);
  std::printf(
      "last part asleep at %g s; %ld queries made, %ld skipped; deepest %.3g m (bound "
      "%.3g)\n",
      summary.sleep_events.empty() ? 0.0 : summary.sleep_events.back().t,
      summary.contact_evaluations, summary.sleep_skipped_queries, r.worst_depth, max_depth);
}

}  // namespace
}  // namespace vcontact::formats
