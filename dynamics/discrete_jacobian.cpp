// The linearised contact wrench of the discrete stepper; the derivation is docs/DISCRETE.md
// §2 (each term below cites its equation there).
#include "dynamics/discrete_jacobian.hpp"

#include <algorithm>
#include <cmath>

namespace vcontact::dynamics {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d planeProjector(const Vector3d& n) { return Matrix3d::Identity() - n * n.transpose(); }

bool hasDamping(const Model& m) { return m.has("damping"); }

// kv' = ∂f_n/∂V = k_n (1 + a δ̇_c), zero when the damping clamp holds f_n at 0 (DISCRETE.md
// (2.1)); k_n is the normal law's ∂f_n/∂V at fixed states (kv, p f_n/V with power_law, times
// r with viscoelastic, whose Maxwell force q is a state advanced explicitly).
double effectiveStiffness(const Model& m, const ContactContext& ctx) {
  if (!hasDamping(m)) return ctx.k_n;
  return std::max(0.0, ctx.k_n * (1.0 + ctx.a * ctx.delta_dot));
}

// The tilt stiffness's factor: a tilt about p_c moves the centroid (where f_n acts) by
// J_s θ / V at an unchanged V, so the torque is (f_n/V) J_s θ: the secant f_n/V, which is kv'
// for the volumetric law (kept as kv' there, to the bit) and f_n/V for a non-linear normal law
// (power_law: kv'/p; viscoelastic: its r f_e + q over V).
double tiltStiffness(const Model& m, const ContactContext& ctx, double kv) {
  if (!m.has("power_law") && !m.has("viscoelastic")) return kv;
  const double f =
      hasDamping(m) ? std::max(0.0, ctx.f_spring * (1.0 + ctx.a * ctx.delta_dot)) : ctx.f_spring;
  return f / ctx.cv->volume;
}

// Normal stiffness and tilt stiffness about p_c (DISCRETE.md (2.2), (2.3)).
void positionTerms(const Model& m, const ContactContext& ctx, Matrix6d& K) {
  const volume::ContactVolume& cv = *ctx.cv;
  const double kv = effectiveStiffness(m, ctx);
  const double area = contactArea(cv);
  if (kv <= 0.0 || area <= 0.0) return;
  const Vector3d& n = ctx.n;
  const Matrix3d P = planeProjector(n);
  const double mean_depth = cv.volume / area;
  K.topLeftCorner<3, 3>() -= kv * area * n * n.transpose();
  K.bottomRightCorner<3, 3>() -= (tiltStiffness(m, ctx, kv) / mean_depth) * P * cv.J_s * P;
}

// The velocity terms of damping, rolling resistance, viscous friction, Coulomb friction and
// the Coulomb spin torque (DISCRETE.md (2.4)–(2.8)).
void velocityTerms(const Model& m, const ContactContext& ctx, Matrix6d& D) {
  const Vector3d& n = ctx.n;
  const Matrix3d nn = n * n.transpose();
  const Matrix3d P = planeProjector(n);
  const double r = ctx.r_gyr, v_eps = ctx.settings.v_eps;
  auto Dff = D.topLeftCorner<3, 3>();
  auto Dtw = D.bottomRightCorner<3, 3>();
  if (hasDamping(m) && 1.0 + ctx.a * ctx.delta_dot > 0.0) {
    Dff -= ctx.f_spring * ctx.a * nn;  // f_n = f_spring (1 + a δ̇), δ̇ = −n·v_c
  }
  if (m.has("rolling_resistance")) Dtw -= ctx.kv * ctx.a * ctx.cv->J_s * P;
  if (m.has("viscous")) {
    Dff -= ctx.f_n * ctx.sigma2 * P;
    Dtw -= r * r * ctx.f_n * ctx.sigma2 * nn;
  }
  if (ctx.law != FrictionLaw::kCoulomb) return;
  if (m.has("coulomb")) {
    Dff -= (ctx.mu_max * ctx.C_v * ctx.f_n / std::max(ctx.v_t.norm(), v_eps)) * P;
  }
  if (m.has("spin") && r > 0.0) {
    const double w_eps = v_eps / r;
    Dtw -= (ctx.mu_max * ctx.C_w * r * ctx.f_n / std::max(std::abs(ctx.omega_n), w_eps)) * nn;
  }
}

// The bristle law made affine in ξ⁺ over a step h (DISCRETE.md (2.9)–(2.11)); h = 0 gives the
// instantaneous Jacobian at fixed states. Writes the force (c + L ξ) and the states' update.
struct BristleAffine {
  Vector6d c = Vector6d::Zero();
  Matrix6d L = Matrix6d::Zero();
  Vector3d z_c = Vector3d::Zero();
  Matrix3d z_v = Matrix3d::Zero();  ///< ∂z⁺/∂v_c
  double theta_c = 0.0, theta_w = 0.0;
};

// What the affine forms for every h share: the bristle law at the step's start, with its
// secants and saturation scales (computed once for the step's form and the instantaneous one).
struct BristleStart {
  Vector3d n, z;
  Matrix3d P;
  double s, s0, s1, r, f_n, e_v, e_w, theta, scale_v, scale_w;
  bool spin;
};

BristleStart bristleStart(const Model& m, const ContactContext& ctx, int offset) {
  BristleStart b;
  b.n = ctx.n;
  b.P = planeProjector(b.n);
  const double s = ctx.s, s0 = ctx.sigma0, s1 = ctx.sigma1, r = ctx.r_gyr;
  const double v_eps = ctx.settings.v_eps;
  // the pull terms' secants: (C_v μ_C / σ1) dir_ε(v_t) = g_v v_t, likewise g_θ ω_n
  const double g_v = ctx.C_v * ctx.mu_C / (s1 * std::max(ctx.v_t.norm(), v_eps));
  const double g_w =
      r > 0.0 ? ctx.C_w * ctx.mu_C / (s1 * r * std::max(std::abs(ctx.omega_n), v_eps / r)) : 0.0;
  const double e_v = s + (1.0 - s) * g_v, e_w = s + (1.0 - s) * g_w;
  b.z = ctx.state.vector(offset);
  b.theta = ctx.state[offset + 3];
  // saturation at the step's start, kept as a fixed scale over the step
  const Vector3d x0 = s * s0 * b.z + s1 * e_v * ctx.v_t;
  b.scale_v = x0.norm() > ctx.mu_max ? ctx.mu_max / x0.norm() : 1.0;
  const double m0 = s * s0 * b.theta + s1 * e_w * ctx.omega_n;
  const double limit_w = r > 0.0 ? ctx.mu_max / r : 0.0;
  b.scale_w = std::abs(m0) > limit_w && m0 != 0.0 ? limit_w / std::abs(m0) : 1.0;
  b.s = s, b.s0 = s0, b.s1 = s1, b.r = r, b.f_n = ctx.f_n, b.e_v = e_v, b.e_w = e_w;
  b.spin = m.has("spin") && r > 0.0;
  return b;
}

BristleAffine bristleAffine(const BristleStart& b, double h) {
  BristleAffine out;
  const Vector3d& n = b.n;
  const double s = b.s, s0 = b.s0, s1 = b.s1, r = b.r;
  const double beta = 1.0 / (1.0 + h * (1.0 - s) * s0 / s1);
  const double k = b.f_n * beta;
  out.c.head<3>() = -b.scale_v * k * s * s0 * b.z;
  out.L.topLeftCorner<3, 3>() = -b.scale_v * k * (h * s0 + s1) * b.e_v * b.P;
  if (b.spin) {
    out.c.tail<3>() = -b.scale_w * r * r * k * s * s0 * b.theta * n;
    out.L.bottomRightCorner<3, 3>() =
        -b.scale_w * r * r * k * (h * s0 + s1) * b.e_w * n * n.transpose();
  }
  out.z_c = beta * b.z;
  out.z_v = beta * h * b.e_v * b.P;
  out.theta_c = beta * b.theta;
  out.theta_w = beta * h * b.e_w;
  return out;
}

Vector6d twist(const RelativeMotion& motion) {
  Vector6d xi;
  xi << motion.v_c_W, motion.w_W;
  return xi;
}

}  // namespace

ContactJacobians contactJacobians(const Model& model, const volume::ContactVolume& cv,
                                  const RelativeMotion& motion, const PairState& state) {
  ContactJacobians J;
  const ContactContext ctx = model.context(cv, motion, state);
  positionTerms(model, ctx, J.K);
  velocityTerms(model, ctx, J.D);
  if (ctx.law == FrictionLaw::kBristle) {
    J.D += bristleAffine(bristleStart(model, ctx, model.stateLayout().offsetOf("bristle")), 0.0).L;
  }
  return J;
}

void linearisePatch(const Model& model, const volume::ContactVolume& cv,
                    const RelativeMotion& motion, const PairState& state, double h,
                    PatchStep& out) {
  ContactContext ctx;
  model.evaluate(cv, motion, state, out.start, nullptr, &ctx);
  linearisePatch(model, ctx, motion, h, out);
}

void linearisePatch(const Model& model, const ContactContext& ctx, const RelativeMotion& motion,
                    double h, PatchStep& out) {
  Matrix6d D = Matrix6d::Zero(), K = Matrix6d::Zero();
  positionTerms(model, ctx, K);
  velocityTerms(model, ctx, D);
  const Vector6d xi0 = twist(motion);
  Vector6d w0;
  w0 << out.start.wrench.f_W, out.start.wrench.tau_W;
  out.c = w0 - D * xi0;
  out.L = D + h * K;
  out.bristle = ctx.law == FrictionLaw::kBristle;
  if (!out.bristle) return;
  out.bristle_offset = model.stateLayout().offsetOf("bristle");
  // the bristle force at the start (exactly the bristle and bristle-spin shares) is replaced
  // by its implicit form
  const BristleStart start = bristleStart(model, ctx, out.bristle_offset);
  const BristleAffine now = bristleAffine(start, 0.0);
  const BristleAffine step = bristleAffine(start, h);
  out.c += step.c - (now.c + now.L * xi0);
  out.L += step.L;
  out.z_c = step.z_c;
  out.Z.setZero();
  out.Z.leftCols<3>() = step.z_v;
  out.theta_c = step.theta_c;
  out.Theta.setZero();
  out.Theta.rightCols<3>() = step.theta_w * ctx.n.transpose();
}

}  // namespace vcontact::dynamics
