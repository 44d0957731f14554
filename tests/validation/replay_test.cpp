// Replay: wrench at the payload origin from the analytic volumes, friction states, noise σ̂.

#include "validation/replay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "geometry/tessellate.hpp"
#include "validation/residuals.hpp"
#include "validation/synthetic.hpp"

namespace vcontact::validation {
namespace {

// The sphere cap formulas are exact; the analytic backend is accurate to 1e-9
// (analytic/primitive_on_plane.hpp).
constexpr double kAnalyticTolerance = 1e-8;

Dataset slidingBall(double R, double d, double v, std::size_t n) {
  Dataset ds;
  ds.payload = geometry::Sphere{R};
  ds.plate = geometry::HalfSpace{};
  ds.outputs = {"fx", "fz", "ty"};
  for (std::size_t i = 0; i < n; ++i) {
    Sample s;
    s.t = 0.01 * static_cast<double>(i);
    s.X_BA.translation() = Eigen::Vector3d(v * s.t, 0.0, R - d);
    s.v_BA = Eigen::Vector3d(v, 0.0, 0.0);
    ds.samples.push_back(s);
  }
  return ds;
}

TEST(Replay, SlidingBallWrenchAboutTheOriginMatchesTheCapFormulas) {
  const double R = 0.0123, d = 3.7e-6, v = 2.3e-3, kv = 4.1e12, mu = 0.17;
  const Dataset ds = slidingBall(R, d, v, 5);
  dynamics::Model m = dynamics::Model::withEffects({"stiffness", "coulomb"});
  m.setParameter("stiffness.kv", kv);
  m.setParameter("coulomb.mu", mu);
  Replayer replayer(ds);
  const Prediction p = replayer.run(m);
  // MODEL.md §5: V = π d² (3R − d)/3, centroid 3(2R − d)²/(4(3R − d)) below the centre.
  const double V = M_PI * d * d * (3 * R - d) / 3;
  const double c = 3 * (2 * R - d) * (2 * R - d) / (4 * (3 * R - d));
  const double fz = kv * V, fx = -mu * fz;  // v ≫ v_ε: full sliding friction against +x
  for (Eigen::Index i = 0; i < p.wrench.rows(); ++i) {
    EXPECT_NEAR(p.wrench(i, 2) / fz, 1.0, kAnalyticTolerance);
    EXPECT_NEAR(p.wrench(i, 0) / fx, 1.0, kAnalyticTolerance);
    // τ_Bo = τ_c + p_BoC × f with p_BoC = (0, 0, −c): τ_y = −c f_x.
    EXPECT_NEAR(p.wrench(i, 4) / (-c * fx), 1.0, kAnalyticTolerance);
    EXPECT_NEAR(p.regime[static_cast<std::size_t>(i)].speed, v, 1e-15);
  }
}

geometry::Shape meshShape(geometry::TriangleMesh m, const std::string& name) {
  return geometry::Mesh{std::make_shared<const geometry::TriangleMesh>(std::move(m)), name};
}

// A mesh plate takes `fast`, whose exact depth a query leaves out by default (volume/contact.hpp,
// QueryOptions::depth): the replay asks for it, since the regimes report it and the direct
// estimates fit V against it. A brick pressed d into a plate mesh, sliding: d is the slab's
// thickness (exact methods on one polyhedron: rounding, 1e-9 of d with room).
TEST(Replay, RegimeDepthOnAMeshPlateIsTheExactDepth) {
  const Eigen::Vector3d size(0.0213, 0.0171, 0.0103);
  const double d = 1e-4, kv = 4.1e12;
  geometry::TriangleMesh plate = geometry::tessellateBox(Eigen::Vector3d(0.2, 0.2, 0.05));
  plate.vertices.col(2).array() -= 0.025;  // its top face at z = 0
  Dataset ds;
  ds.payload = meshShape(geometry::tessellateBox(size), "brick");
  ds.plate = meshShape(std::move(plate), "plate");
  ds.outputs = {"fz"};
  for (int i = 0; i < 3; ++i) {
    Sample s;
    s.t = 0.01 * i;
    s.X_BA.translation() = Eigen::Vector3d(0.001 * i, 0.0003, 0.5 * size.z() - d);
    s.v_BA = Eigen::Vector3d(0.1, 0.0, 0.0);
    ds.samples.push_back(s);
  }
  dynamics::Model m = dynamics::Model::withEffects({"stiffness"});
  m.setParameter("stiffness.kv", kv);
  Replayer replayer(ds);
  const Prediction p = replayer.run(m);
  ASSERT_EQ(p.regime.size(), 3u);
  const double V = size.x() * size.y() * d;
  for (const RegimeSample& r : p.regime) {
    EXPECT_TRUE(r.in_contact);
    EXPECT_NEAR(r.volume, V, 1e-9 * V);
    EXPECT_NEAR(r.depth, d, 1e-9 * d);
  }
  EXPECT_NEAR(p.wrench(0, 2), kv * V, 1e-9 * kv * V);
}

TEST(Replay, BristleStateReachesTheSteadySlidingForceForAnySampleSpacing) {
  // Steady sliding (s → 0): z → μ_C dir(v)/σ0 and f_t → −μ_C f_n, whatever σ0/σ1 (stiff when
  // σ1 is small); the exponential step must get there without oscillating at coarse spacing.
  const double R = 0.01, d = 5e-6, v = 5e-3;
  dynamics::Model m = dynamics::Model::withEffects({"stiffness", "coulomb", "bristle"});
  m.setParameter("bristle.sigma1", 0.5);  // σ0/σ1 = 9000 1/s: stiff at 10 ms spacing
  for (std::size_t n : {20u, 200u}) {
    const Dataset ds = slidingBall(R, d, v, n);
    Replayer replayer(ds);
    const Prediction p = replayer.run(m);
    const double ratio = -p.wrench(p.wrench.rows() - 1, 0) / p.wrench(p.wrench.rows() - 1, 2);
    // 1e-6: the relative size of what is left, at the last sample, of the bristle transient
    // and of the stick measure s = exp(−(v/v_s)²) = exp(−25).
    EXPECT_NEAR(ratio, 0.2, 1e-6) << n << " samples";
    for (Eigen::Index i = 0; i < p.wrench.rows(); ++i) {  // 1e-12: round-off of the ratio
      EXPECT_LE(-p.wrench(i, 0), 0.2 * p.wrench(i, 2) * (1 + 1e-12)) << "overshoot at " << i;
    }
  }
}

TEST(Residuals, NoiseEstimateRecoversSigmaOnASmoothSignal) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double sigma = 0.037;
  Eigen::VectorXd y(4000);
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    y[i] = 5.0 * std::sin(0.003 * static_cast<double>(i)) + sigma * normal(rng);
  }
  // 4000 samples: the MAD estimate has a relative standard error of about 2 %.
  EXPECT_NEAR(estimateNoise(y) / sigma, 1.0, 0.08);
}

TEST(Synthetic, NoiselessReplayOfTheTrueModelHasZeroResiduals) {
  Dataset d = rigMotion("slide-spin", 200);
  const auto truth = dynamics::Model::withEffects({"stiffness", "coulomb", "spin", "contensou"});
  d.noise.clear();
  for (const auto& o : d.outputs) d.noise[o] = 0.0;
  synthesizeMeasurement(d, truth, 1);
  Replayer replayer(d);
  const Prediction p = replayer.run(truth);
  for (const auto& o : d.outputs)
    EXPECT_EQ((d.measured(o) - p.column(o)).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace vcontact::validation
