// The discrete stepper's linearisation (dynamics/steppers/discrete_jacobian.hpp, docs/DISCRETE.md
// §2) against central finite differences of the model's wrench: in the twist at a fixed contact,
// and in the pose (through the geometry) at a fixed twist. Friction laws are linearised with
// their magnitudes frozen (a secant): where that equals the derivative (the regularised core,
// across the slip) the columns are compared; along the slip the secant must give the force.

#include "dynamics/steppers/discrete_jacobian.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "volume/contact.hpp"

namespace vcontact::test {
namespace {

using dynamics::ContactJacobians;
using dynamics::Matrix6d;
using dynamics::Model;
using dynamics::PairState;
using dynamics::RelativeMotion;
using dynamics::Vector6d;
using Eigen::Isometry3d;
using Eigen::Vector3d;

constexpr double kSide = 0.02;  // m, cube edge

// A cube pressed `depth` into the half-space z ≤ 0, turned by `tilt` about x and `yaw` about z.
volume::ContactVolume cubeContact(const Isometry3d& X_WA) {
  const volume::ContactPatches c =
      volume::computeContact(geometry::Box{Vector3d::Constant(kSide)}, X_WA, geometry::HalfSpace{},
                             Isometry3d::Identity());
  return c.aggregate;
}

Isometry3d cubePose(double depth, double tilt, double yaw) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() =
      (Eigen::AngleAxisd(tilt, Vector3d::UnitX()) * Eigen::AngleAxisd(yaw, Vector3d::UnitZ()))
          .toRotationMatrix();
  X.translation() = Vector3d(0.003, -0.002, kSide / 2 - depth);
  return X;
}

Vector6d asVector(const dynamics::Wrench& w) {
  Vector6d v;
  v << w.f_W, w.tau_W;
  return v;
}

RelativeMotion motionOf(const Vector6d& xi) { return {xi.head<3>(), xi.tail<3>(), 0.0}; }

// Central differences of the wrench in the twist, at a fixed contact and state.
Matrix6d twistDifferences(const Model& m, const volume::ContactVolume& cv, const Vector6d& xi,
                          const PairState& state, double eps) {
  Matrix6d J;
  for (int j = 0; j < 6; ++j) {
    Vector6d up = xi, down = xi;
    up(j) += eps;
    down(j) -= eps;
    J.col(j) = (asVector(m.evaluate(cv, motionOf(up), state).wrench) -
                asVector(m.evaluate(cv, motionOf(down), state).wrench)) /
               (2.0 * eps);
  }
  return J;
}

// Central differences in the displacement (du, dθ) of body A about the contact's centroid, the
// wrench moved back to that centroid, at a fixed twist.
Matrix6d poseDifferences(const Model& m, const Isometry3d& X_WA, const Vector6d& xi, double eps) {
  const Vector3d p0 = cubeContact(X_WA).p_WC;
  auto wrenchAt = [&](const Vector6d& d) {
    Isometry3d step = Isometry3d::Identity();
    step.translate(p0 + d.head<3>());
    if (d.tail<3>().norm() > 0.0)
      step.rotate(Eigen::AngleAxisd(d.tail<3>().norm(), d.tail<3>().normalized()));
    step.translate(-p0);
    const volume::ContactVolume cv = cubeContact(step * X_WA);
    const dynamics::Wrench w = m.evaluate(cv, motionOf(xi), PairState{}).wrench;
    Vector6d out;
    out << w.f_W, w.tau_W + (cv.p_WC - p0).cross(w.f_W);
    return out;
  };
  Matrix6d J;
  for (int j = 0; j < 6; ++j) {
    Vector6d d = Vector6d::Zero();
    d(j) = eps;
    J.col(j) = (wrenchAt(d) - wrenchAt(-d)) / (2.0 * eps);
  }
  return J;
}

Model soft(std::vector<std::string> effects) {
  Model m = Model::withEffects(effects);
  m.setParameter("stiffness.kv", 1e9);
  if (m.has("damping")) m.setParameter("damping.a", 20.0);
  if (m.has("coulomb")) m.setParameter("coulomb.mu", 0.3);
  return m;
}

// |A − B| ≤ tol · max|B| entrywise
void expectClose(const Matrix6d& analytic, const Matrix6d& numeric, double tol) {
  const double scale = numeric.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LE((analytic - numeric).cwiseAbs().maxCoeff(), tol * scale) << "analytic\n"
                                                                     << analytic << "\nnumeric\n"
                                                                     << numeric;
}

const Vector6d kTwist = (Vector6d() << 0.003, -0.002, -0.01, 0.1, -0.2, 0.3).finished();

// Normal damping and rolling resistance are linear in the twist (while the clamp is off): the
// Jacobian is exact, so the differences agree to round-off (1e-7 of the largest entry).
TEST(DiscreteJacobian, DampingAndRollingMatchDifferences) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.002, 0.3));
  for (const auto& effects : {std::vector<std::string>{"stiffness", "damping"},
                              {"stiffness", "damping", "rolling_resistance"},
                              {"stiffness", "viscous"}}) {
    Model m = soft(effects);
    if (m.has("viscous")) m.setParameter("viscous.sigma2", 2.0);
    const ContactJacobians J = contactJacobians(m, cv, motionOf(kTwist), PairState{});
    expectClose(J.D, twistDifferences(m, cv, kTwist, PairState{}, 1e-6), 1e-7);
  }
}

// Below v_eps the regularised Coulomb force and spin torque are linear: exact columns
// (v_t = 5 µm/s < v_eps = 10 µm/s; r_gyr ω_n = 8 µm/s likewise).
TEST(DiscreteJacobian, CoulombAndSpinInTheRegularisedCoreMatchDifferences) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.0, 0.3));
  const Model m = soft({"stiffness", "coulomb", "spin"});
  Vector6d xi = Vector6d::Zero();
  xi << 3e-6, -4e-6, 0.0, 0.0, 0.0, 8e-6 / cv.r_gyr;
  const ContactJacobians J = contactJacobians(m, cv, motionOf(xi), PairState{});
  expectClose(J.D, twistDifferences(m, cv, xi, PairState{}, 1e-8), 1e-6);
}

// Sliding and spinning (with Contensou's sharing): across the slip the secant is the
// derivative; along it, the secant times the twist is the friction wrench itself.
TEST(DiscreteJacobian, SlidingFrictionSecantIsExactAcrossAndReproducesTheForce) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.0, 0.0));
  for (const auto& effects : {std::vector<std::string>{"stiffness", "coulomb", "spin"},
                              {"stiffness", "coulomb", "spin", "contensou"},
                              {"stiffness", "coulomb", "spin", "stribeck", "contensou"}}) {
    const Model m = soft(effects);
    Vector6d xi = Vector6d::Zero();
    xi << 0.03, 0.04, 0.0, 0.0, 0.0, 5.0;
    const ContactJacobians J = contactJacobians(m, cv, motionOf(xi), PairState{});
    const Vector3d across = Vector3d::UnitZ().cross(Vector3d(0.6, 0.8, 0.0));
    Vector6d dxi = Vector6d::Zero();
    dxi.head<3>() = across;
    const double eps = 1e-6;
    const Vector6d numeric = (asVector(m.evaluate(cv, motionOf(xi + eps * dxi), {}).wrench) -
                              asVector(m.evaluate(cv, motionOf(xi - eps * dxi), {}).wrench)) /
                             (2.0 * eps);
    // the difference quotient's truncation error is (ε/|v_t|)² ≈ 4e-10 of the entry
    EXPECT_LE((J.D * dxi - numeric).norm(), 1e-6 * numeric.norm()) << effects.size();
    Vector6d friction = asVector(m.evaluate(cv, motionOf(xi), {}).wrench);
    friction.head<3>() -= m.parameter("stiffness.kv") * cv.volume * cv.n_W;
    EXPECT_LE((J.D * xi - friction).norm(), 1e-12 * friction.norm()) << effects.size();
  }
}

// Bristles stuck (v_t = 0, ω_n = 0: s = 1 and ∂s/∂v = 0 there): f = −f_n (σ0 z + σ1 v_t),
// τ = −r² f_n (σ0 θ + σ1 ω_n) n; exact columns.
TEST(DiscreteJacobian, StuckBristlesMatchDifferences) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.0, 0.3));
  const Model m = soft({"stiffness", "coulomb", "bristle", "spin"});
  PairState state;
  const int z = m.stateLayout().offsetOf("bristle");
  state.vector(z) = Vector3d(1e-5, -2e-5, 0.0);
  state[z + 3] = 1e-4;
  const Vector6d xi = Vector6d::Zero();
  const ContactJacobians J = contactJacobians(m, cv, motionOf(xi), state);
  // ε = 1e-7 m/s: s = 1 − ε²/v_s² = 1 − 1e-8 on either side, symmetric
  expectClose(J.D, twistDifferences(m, cv, xi, state, 1e-7), 1e-6);
}

// The implicit bristle step: the end state satisfies z⁺ = z + h ż(ξ⁺, z⁺) and the force
// c + L ξ⁺ is the model's force at (ξ⁺, z⁺), while stuck. The step freezes s = 1; the model at
// ξ⁺ has 1 − s = (v/v_s)², whose relaxation term (1 − s)(σ0/σ1) z changes ż relatively by
// v (σ0/σ1) |z| / v_s² ≈ 4e-6 at v = 1e-8 m/s (6e-6 with the spin's share of v_avg): hence
// bounds of 2e-5. The force, dominated by the unchanged σ0 z, is held to 1e-6.
TEST(DiscreteJacobian, ImplicitBristleStepIsBackwardEuler) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.0, 0.0));
  const Model m = soft({"stiffness", "coulomb", "bristle", "spin"});
  PairState state;
  const int z = m.stateLayout().offsetOf("bristle");
  state.vector(z) = Vector3d(1e-5, -2e-5, 0.0);
  state[z + 3] = 1e-4;
  const double h = 1e-3;
  dynamics::PatchStep step;
  linearisePatch(m, cv, motionOf(Vector6d::Zero()), state, h, step);
  Vector6d xi = Vector6d::Zero();
  xi << 1e-8, 0.5e-8, 0.0, 0.0, 0.0, 1e-6;  // no normal or tilt motion: no K term
  PairState next = state;
  ASSERT_EQ(step.implicit.offset, z);
  next.vector(z) = step.implicit.z_c + step.implicit.Z * xi;
  next[z + 3] = step.implicit.theta_c + (step.implicit.Theta * xi)(0);
  const dynamics::ContactResult r = m.evaluate(cv, motionOf(xi), next);
  const Vector3d dz = next.vector(z) - state.vector(z);
  EXPECT_LE((dz - h * r.rates.vector(z)).norm(), 2e-5 * dz.norm());
  EXPECT_NEAR(next[z + 3] - state[z + 3], h * r.rates[z + 3], 2e-5 * std::abs(h * r.rates[z + 3]));
  const Vector6d predicted = step.c + step.L * xi;
  EXPECT_LE((predicted - asVector(r.wrench)).norm(), 1e-6 * asVector(r.wrench).norm());
}

// Normal and tilt stiffness of a flat face (uniform depth: the Winkler form is exact) and of
// a slightly tilted one (depth varies by 1.7e-5 m over the face; the area's second moment
// is taken as Σ_s / d̄, off by (variation / depth)² ≈ 3 %... measured below 1e-3 here).
TEST(DiscreteJacobian, FlatFaceStiffnessMatchesDifferences) {
  for (const double tilt : {0.0, 0.0005}) {
    for (const auto& effects : {std::vector<std::string>{"stiffness"}, {"stiffness", "damping"}}) {
      const Model m = soft(effects);
      const Isometry3d X = cubePose(1e-4, tilt, 0.3);
      const Vector6d xi = (Vector6d() << 0, 0, -0.01, 0, 0, 0).finished();  // δ̇ = 1 cm/s
      const ContactJacobians J = contactJacobians(m, cubeContact(X), motionOf(xi), PairState{});
      expectClose(J.K, poseDifferences(m, X, xi, 1e-7), 1e-3);
    }
  }
}

// A Newton iteration of the step linearises about a guess of its end, reached from the start by
// h ξ0: its wrench over the step is w0 + D (ξ⁺ − ξ0) + h K (ξ⁺ − ξ0), so that at ξ⁺ = ξ0 (the
// iteration's fixed point) it is the wrench at the guess itself, and it differs from the
// start's form (whose displacement is h ξ⁺) by −h K ξ0 alone.
TEST(DiscreteJacobian, AboutTheEndTheStepIsTheWrenchAtItsFixedPoint) {
  const Model m = soft({"stiffness", "damping", "coulomb"});
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.0005, 0.3));
  const Vector6d xi = (Vector6d() << 0.002, -0.001, -0.01, 0.05, 0.02, 0.1).finished();
  const double h = 1e-3;
  dynamics::PatchStep start, end;
  linearisePatch(m, cv, motionOf(xi), PairState{}, h, start);
  linearisePatch(m, cv, motionOf(xi), PairState{}, h, end, true);
  const Vector6d w0 = asVector(end.start.wrench);
  EXPECT_LE((end.c + end.L * xi - w0).norm(), 1e-12 * w0.norm());
  EXPECT_EQ(end.L, start.L);
  const ContactJacobians J = contactJacobians(m, cv, motionOf(xi), PairState{});
  EXPECT_LE((start.c - end.c - h * J.K * xi).norm(), 1e-12 * w0.norm());
}

// A sphere: ∂V/∂δ = A exactly, but rotating a curved face about p_c slides its depth profile
// rather than tilting it. The true tilt stiffness is R f_n = kv π a⁴/4 (small depth); the
// flat-face form gives kv Σ_s/d̄ = kv π a⁴/6: 2/3 of it (docs/DISCRETE.md §2).
TEST(DiscreteJacobian, SphereNormalStiffnessIsExactAndTiltIsTwoThirds) {
  const Model m = soft({"stiffness"});
  const double R = 0.01, d = 1e-5;
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.0, 0.0, R - d);
  auto contact = [&](const Isometry3d& X_WA) {
    return volume::computeContact(geometry::Sphere{R}, X_WA, geometry::HalfSpace{},
                                  Isometry3d::Identity())
        .aggregate;
  };
  const volume::ContactVolume cv = contact(X);
  const ContactJacobians J = contactJacobians(m, cv, motionOf(Vector6d::Zero()), PairState{});
  const double kv = m.parameter("stiffness.kv");
  // V(d) = π d² (3R − d)/3 ⇒ dV/dd = π (2Rd − d²) = area
  EXPECT_NEAR(J.K(2, 2), -kv * std::numbers::pi * (2 * R * d - d * d), 1e-9 * kv * R * d);
  const double true_tilt = -R * kv * cv.volume;
  EXPECT_NEAR(J.K(3, 3) / true_tilt, 2.0 / 3.0, 0.01);  // 1 %: the d/R corrections
  EXPECT_NEAR(J.K(4, 4) / true_tilt, 2.0 / 3.0, 0.01);
}

// The normal-law effects (MODEL.md §3 "Normal law") on a flat face, where A is constant in the
// depth: power_law's normal stiffness p f_n/V and tilt stiffness (secant) f_n/V · J_s/d̄,
// viscoelastic's r k at a fixed Maxwell force q (the state, which the stepper advances
// explicitly), adhesion's −σ_a A (constant in the depth: no stiffness), each with damping's
// f_spring a n nᵀ in the twist. Tolerance 1e-3 as the flat-face test above (pose step 1e-7 m
// against a depth of 1e-4 m; f ∝ d² has no third derivative, so the difference is exact up to
// round-off); the twist column is linear: 1e-7.
TEST(DiscreteJacobian, NormalLawEffectsMatchDifferences) {
  const Isometry3d X = cubePose(1e-4, 0.0, 0.3);
  const volume::ContactVolume cv = cubeContact(X);
  const Vector6d press = (Vector6d() << 0, 0, -0.01, 0, 0, 0).finished();  // δ̇ = 1 cm/s
  for (const auto& law : {"power_law", "viscoelastic", "adhesion"}) {
    Model m = soft({"stiffness", law, "damping"});
    if (m.has("power_law")) m.setParameter("power_law.p", 2.0);
    if (m.has("viscoelastic")) m.setParameter("viscoelastic.ratio", 0.3);
    if (m.has("adhesion")) m.setParameter("adhesion.sigma_a", 1e3);
    PairState state;
    if (m.has("viscoelastic")) state[m.stateLayout().offsetOf("viscoelastic")] = 0.5;  // N
    const ContactJacobians J = contactJacobians(m, cv, motionOf(press), state);
    SCOPED_TRACE(law);
    expectClose(J.K, poseDifferences(m, X, press, 1e-7), 1e-3);
    const Matrix6d D = twistDifferences(m, cv, press, state, 1e-6);
    EXPECT_NEAR(J.D(2, 2), D(2, 2), 1e-7 * std::abs(D(2, 2)));
  }
}

}  // namespace
}  // namespace vcontact::test

namespace vcontact::test {
namespace {

// Each effect linearises its own share (Effect::linearise): its D against central differences
// of that share alone (ContactResult::shares), in the regularised core where the friction
// laws are linear in the twist (v_t = 5 µm/s, r_gyr ω_n = 8 µm/s < v_eps) and without damping
// where a friction share reads f_n, which the linearisation freezes (1e-6 as above).
TEST(DiscreteJacobian, EachEffectsOwnTermsMatchDifferencesOfItsShare) {
  const volume::ContactVolume cv = cubeContact(cubePose(1e-4, 0.002, 0.3));
  Vector6d core = Vector6d::Zero();
  core << 3e-6, -4e-6, -0.01, 0.1, -0.2, 8e-6 / cv.r_gyr;
  struct Case {
    std::vector<std::string> effects;
    Vector6d xi;
  };
  int checked = 0;
  for (const Case& c : {Case{{"stiffness", "damping", "rolling_resistance"}, kTwist},
                        Case{{"stiffness", "coulomb", "spin", "viscous"}, core}}) {
    Model m = soft(c.effects);
    if (m.has("viscous")) m.setParameter("viscous.sigma2", 2.0);
    const dynamics::ContactContext ctx = m.context(cv, motionOf(c.xi), PairState{});
    for (std::size_t i = 0; i < m.effectCount(); ++i) {
      const dynamics::Effect& e = m.effect(i);
      ASSERT_EQ(e.stepForm(), dynamics::StepForm::kLinearised) << e.id();
      dynamics::StepTerms own;
      e.linearise(ctx, own);
      Matrix6d numeric;
      const double eps = 1e-8;
      for (int j = 0; j < 6; ++j) {
        Vector6d up = c.xi, down = c.xi;
        up(j) += eps;
        down(j) -= eps;
        numeric.col(j) = (asVector(m.evaluate(cv, motionOf(up), PairState{}).shares[i]) -
                          asVector(m.evaluate(cv, motionOf(down), PairState{}).shares[i])) /
                         (2.0 * eps);
      }
      if (e.id() == "stiffness") {  // kv V n: no twist in it; its terms are the position ones
        EXPECT_EQ(own.D.cwiseAbs().maxCoeff(), 0.0);
        EXPECT_LT(numeric.cwiseAbs().maxCoeff(), 1e-6 * own.K.cwiseAbs().maxCoeff());
        continue;
      }
      SCOPED_TRACE(std::string(e.id()));
      expectClose(own.D, numeric, 1e-6);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 5);  // damping, rolling_resistance, coulomb, spin, viscous
}

// The effects without a linearisation are named, so that the discrete stepper's user hears of
// them (vcontact simulate prints them); those that act through the context are not.
TEST(DiscreteJacobian, ExplicitEffectsAreNamed) {
  EXPECT_EQ(soft({"stiffness", "damping", "coulomb", "adhesion"}).explicitEffects(),
            std::vector<std::string>{"adhesion"});
  EXPECT_TRUE(
      soft({"stiffness", "power_law", "damping", "coulomb", "stribeck", "contensou", "spin"})
          .explicitEffects()
          .empty());
}

}  // namespace
}  // namespace vcontact::test
