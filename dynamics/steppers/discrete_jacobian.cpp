// The linearised contact wrench of the discrete stepper; the derivation is docs/DISCRETE.md
// §2. Each effect writes its own terms (Effect::linearise, in dynamics/effects/); this file
// puts them together for one patch and one step.
#include "dynamics/steppers/discrete_jacobian.hpp"

namespace vcontact::dynamics {
namespace {

Vector6d twist(const RelativeMotion& motion) {
  Vector6d xi;
  xi << motion.v_c_W, motion.w_W;
  return xi;
}

}  // namespace

ContactJacobians contactJacobians(const Model& model, const volume::ContactVolume& cv,
                                  const RelativeMotion& motion, const PairState& state) {
  StepTerms terms;  // h = 0: the instantaneous forms
  model.linearise(model.context(cv, motion, state), terms);
  ContactJacobians J;
  J.K = terms.K;
  J.D = terms.D + terms.L_now;
  return J;
}

void linearisePatch(const Model& model, const volume::ContactVolume& cv,
                    const RelativeMotion& motion, const PairState& state, double h, PatchStep& out,
                    bool about_end) {
  ContactContext ctx;
  model.evaluate(cv, motion, state, out.start, nullptr, &ctx);
  linearisePatch(model, ctx, motion, h, out, about_end);
}

void linearisePatch(const Model& model, const ContactContext& ctx, const RelativeMotion& motion,
                    double h, PatchStep& out, bool about_end) {
  StepTerms terms;
  terms.h = h;
  model.linearise(ctx, terms);
  const Vector6d xi0 = twist(motion);
  Vector6d w0;
  w0 << out.start.wrench.f_W, out.start.wrench.tau_W;
  out.c = w0 - terms.D * xi0;
  out.L = terms.D + h * terms.K;
  if (about_end) out.c -= h * (terms.K * xi0);
  out.implicit = terms.implicit;
  if (!out.implicit.any()) return;
  // the shares of the implicit states at the start (c_now + L_now ξ0: exactly the bristle and
  // bristle-spin shares) are replaced by their form over the step
  out.c += terms.c_step - (terms.c_now + terms.L_now * xi0);
  out.L += terms.L_step;
}

}  // namespace vcontact::dynamics
