// A free payload against its record (validation/trajectory_compare.hpp, free_flight.hpp):
// free flight against closed forms, the initial-state estimate, the record's phases.
#include "validation/trajectory_compare.hpp"

#include <gtest/gtest.h>

#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>

#include "toss_fixtures.hpp"
#include "validation/free_flight.hpp"

namespace vcontact::validation {
namespace {

using testing::TossSpec;

// Tolerances of the integration when a closed form is the reference: per-step bounds of 1e-13
// keep the global error of half a second of flight near 1e-11, below the 1e-9 asserted.
TrajectorySettings tight() {
  TrajectorySettings s;
  s.integrator = dynamics::Integrator::kDopri5;
  s.absTol = 1e-13;
  s.relTol = 1e-13;
  return s;
}

dynamics::Model contactModel() { return testing::tossModel(); }

// A toss far above the plate: never in contact over its duration.
TossSpec highFlight() {
  TossSpec spec;
  spec.X0.translation() = Eigen::Vector3d(0.1, -0.2, 5.0);
  spec.X0.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  spec.v0 = Eigen::Vector3d(0.7, -0.3, 1.5);
  spec.duration = 0.5;
  return spec;
}

TEST(FreeFlight, CentreOfMassFollowsTheParabola) {
  const TossSpec spec = highFlight();
  Trial t;
  t.data = testing::tossTemplate(spec, "parabola");
  t.start = initialState(t.data);
  const SimulatedPath path = simulateTrial(t, contactModel(), tight());
  ASSERT_TRUE(path.stopped.empty()) << path.stopped;
  const Eigen::Vector3d g = t.data.gravity_B;
  for (std::size_t i = 0; i < t.data.size(); ++i) {
    const double tau = t.data.samples[i].t;
    const Eigen::Vector3d exact = spec.X0.translation() + spec.v0 * tau + 0.5 * g * tau * tau;
    EXPECT_LT((path.X_BA[i].translation() - exact).norm(), 1e-9) << "t = " << tau;
    EXPECT_LT((path.v_BA[i] - (spec.v0 + g * tau)).norm(), 1e-9) << "t = " << tau;
  }
}

// Euler's equations of a body with I1 < I2 < I3 and L² > 2T I2, from ω = (ω1m, 0, ω3m):
// ω1 = ω1m cn(λt, k), ω2 = ω2m sn(λt, k), ω3 = ω3m dn(λt, k) (Landau & Lifshitz §37).
TEST(FreeFlight, AsymmetricBodyPrecessesAsTheJacobiSolution) {
  TossSpec spec = highFlight();
  spec.inertia = Eigen::Vector3d(1e-3, 2e-3, 3e-3);
  spec.w0 = spec.X0.linear() * Eigen::Vector3d(3.0, 0.0, 5.0);  // body rates (3, 0, 5) rad/s
  Trial t;
  t.data = testing::tossTemplate(spec, "precession");
  t.start = initialState(t.data);
  const SimulatedPath path = simulateTrial(t, contactModel(), tight());
  ASSERT_TRUE(path.stopped.empty()) << path.stopped;
  const double I1 = 1e-3, I2 = 2e-3, I3 = 3e-3;
  const Eigen::Vector3d I(I1, I2, I3), w0(3.0, 0.0, 5.0);
  const double T2 = I.dot(w0.cwiseProduct(w0));
  const double L2 = I.cwiseProduct(I).dot(w0.cwiseProduct(w0));
  const double w1m = std::sqrt((T2 * I3 - L2) / (I1 * (I3 - I1)));
  const double w2m = std::sqrt((T2 * I3 - L2) / (I2 * (I3 - I2)));
  const double w3m = std::sqrt((L2 - T2 * I1) / (I3 * (I3 - I1)));
  const double lambda = std::sqrt((L2 - T2 * I1) * (I3 - I2) / (I1 * I2 * I3));
  const double k = std::sqrt((I2 - I1) * (T2 * I3 - L2) / ((I3 - I2) * (L2 - T2 * I1)));
  const Eigen::Vector3d L_B = spec.X0.linear() * I.cwiseProduct(w0);  // conserved, plate frame
  for (std::size_t i = 0; i < t.data.size(); ++i) {
    double cn = 0.0, dn = 0.0;
    const double sn = boost::math::jacobi_elliptic(k, lambda * t.data.samples[i].t, &cn, &dn);
    const Eigen::Vector3d exact(w1m * cn, w2m * sn, w3m * dn);
    const Eigen::Matrix3d R = path.X_BA[i].linear();
    EXPECT_LT((R.transpose() * path.w_BA[i] - exact).norm(), 1e-9) << "t = " << t.data.samples[i].t;
    EXPECT_LT((R * I.cwiseProduct(R.transpose() * path.w_BA[i]) - L_B).norm(), 1e-9 * L_B.norm());
  }
}

// A record without velocity columns: the state comes from the samples before the first
// contact only. On a noiseless engine record the parabola is exact and the torque-free fit
// meets the simulated rotation to the RK4 and interpolation error of the estimate (~1e-10).
TEST(FreeFlight, EstimatesTheStateFromTheFlightBeforeTheFirstContact) {
  TossSpec spec;
  spec.X0.translation() = Eigen::Vector3d(0, 0, 0.25);
  spec.X0.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  spec.v0 = Eigen::Vector3d(0.5, 0.1, 0.5);
  spec.w0 = Eigen::Vector3d(2.0, -1.0, 4.0);
  spec.inertia = Eigen::Vector3d(6e-4, 7e-4, 8e-4);
  const Trial toss = testing::makeToss(spec, contactModel(), 0.0, 0.0, 0.0, 1, "estimate",
                                       dynamics::Integrator::kDopri5);
  Dataset d = toss.data;
  d.velocityFromPositions = d.omegaFromAttitude = true;
  const std::size_t first = firstContact(d);
  ASSERT_GE(first, 10u);
  ASSERT_LT(first, d.size());
  // samples after the first contact are scrambled: the estimate must not read them
  for (std::size_t i = first + 1; i < d.size(); ++i) d.samples[i].X_BA.translation().z() += 1.0;
  const FlightState f = initialState(d);
  EXPECT_TRUE(f.estimated);
  EXPECT_EQ(f.samplesUsed, first);
  EXPECT_LT((f.v_BAcm - spec.v0).norm(), 1e-9);
  EXPECT_LT((f.X_BA.translation() - spec.X0.translation()).norm(), 1e-9);
  EXPECT_LT((f.w_BA - spec.w0).norm(), 1e-6);
  EXPECT_LT(Eigen::AngleAxisd(f.X_BA.linear() * spec.X0.linear().transpose()).angle(), 1e-8);
}

// A box released flat 2 mm above the plate with a sideways speed: it flies, lands, slides
// (6 cm at μ = 0.3) and stops, in that order.
TEST(TrajectoryCompare, PhasesOfADropThatSlidesToRest) {
  TossSpec spec;
  spec.X0.translation() = Eigen::Vector3d(0, 0, 0.065);
  spec.v0 = Eigen::Vector3d(0.6, 0, 0);
  spec.duration = 0.8;
  const Trial t = testing::makeToss(spec, contactModel(), 0.0, 0.0, 0.0, 1, "slide");
  std::vector<TrajectoryPhase> order;
  for (TrajectoryPhase p : t.phases)
    if (order.empty() || order.back() != p) order.push_back(p);
  const std::vector<TrajectoryPhase> expected = {TrajectoryPhase::kFlight, TrajectoryPhase::kImpact,
                                                 TrajectoryPhase::kSliding, TrajectoryPhase::kRest};
  EXPECT_EQ(order, expected);
}

// The model that made a record meets it: e_q is zero to the integration tolerance, and a
// model with another friction coefficient misses it (the loss measures something).
TEST(TrajectoryCompare, TheTrueModelMeetsItsOwnRecord) {
  TossSpec spec;
  spec.X0.translation() = Eigen::Vector3d(0, 0, 0.09);
  spec.v0 = Eigen::Vector3d(0.6, 0, 0);
  const Trial t = testing::makeToss(spec, contactModel(), 0.0, 0.0, 0.0, 1, "self");
  const TrajectorySettings s;  // the settings the record was made with
  const TrialEvaluation same = evaluateTrial(contactModel(), t, s);
  EXPECT_LT(same.loss, 1e-12);
  dynamics::Model other = contactModel();
  other.setParameter("coulomb.mu", 0.15);
  const TrialEvaluation e = evaluateTrial(other, t, s);
  EXPECT_GT(e.loss, 1e-4);
  EXPECT_EQ(e.residuals.size(), static_cast<Eigen::Index>(2 * t.data.size()));
  EXPECT_NEAR(e.residuals.squaredNorm() / static_cast<double>(t.data.size()), e.loss, 1e-12);
  EXPECT_FALSE(std::isnan(e.errors.partTime));
}

}  // namespace
}  // namespace vcontact::validation
