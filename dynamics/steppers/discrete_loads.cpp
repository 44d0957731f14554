// The loads and springs in the discrete stepper's system (discrete_stepper.cpp,
// docs/DISCRETE.md §1): a drive or a spring is as stiff as a contact for a light body (the peg
// of peg_insertion turns about its axis at h k / I = 6 per millisecond under the drive's
// torsional damping), so their wrenches enter implicitly too, linearised by central
// differences of loadWrench / springWrench in each free body's twist and displacement:
//
//   w⁺ = w0 + D (V⁺ − V) + h K V⁺      (per body pair (i, j): the wrench on i, the twist of j)
//
// w0 itself is already in the equations' force and torque (MotionEquations::loadWrenches);
// this adds the rest.

#include "dynamics/steppers/discrete_stepper.hpp"

namespace vcontact::dynamics {
namespace {

// Difference steps: far below the drives' and springs' length and speed scales (mm, mm/s),
// far above round-off of their forces.
constexpr double kTwistStep = 1e-6;  // m/s, rad/s
constexpr double kPoseStep = 1e-7;   // m, rad

// Body kinematics k moved by the twist or displacement component `c` (0–2 translation,
// 3–5 rotation about the centre of mass) times `step`.
BodyKinematics perturbed(const BodyKinematics& k, const RigidBody& body, bool pose, int c,
                         double step) {
  BodyKinematics out = k;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e(c % 3) = step;
  if (!pose) {
    (c < 3 ? out.v_WBcm : out.w_WB) += e;
    return out;
  }
  if (c < 3) {
    out.p_WBcm += e;
  } else {
    out.X_WB.linear() = Eigen::AngleAxisd(step, e / step).toRotationMatrix() * k.X_WB.linear();
  }
  out.X_WB.translation() = out.p_WBcm - out.X_WB.linear() * body.p_BBcm;
  return out;
}

// The wrench about the centre of mass of a body at kinematics k, of a force f at p and a couple.
Vector6d aboutCentre(const Wrench& w, const Eigen::Vector3d& p, const BodyKinematics& k) {
  Vector6d out;
  out << w.f_W, w.tau_W + (p - k.p_WBcm).cross(w.f_W);
  return out;
}

}  // namespace

// Load or spring j (loads first, then springs) at kinematics kin: the wrenches about the
// centres of mass of its bodies (one for a load, a and b for a spring).
void DiscreteStepper::loadTerms(std::size_t j, const std::vector<BodyKinematics>& kin, double t,
                                Vector6d out[2]) const {
  if (j < scenario_.loads.size()) {
    const ExternalLoad& l = scenario_.loads[j];
    const LoadOutput o = loadWrench(l, kin[l.body], t);
    out[0] = aboutCentre(o.wrench, o.p_W, kin[l.body]);
    return;
  }
  const BodySpring& s = scenario_.springs[j - scenario_.loads.size()];
  const LoadOutput o = springWrench(s, kin[s.a], kin[s.b]);
  out[0] = aboutCentre(o.wrench, o.p_W, kin[s.a]);
  out[1] = -aboutCentre(o.wrench, o.q_W, kin[s.b]);
}

// The implicit part of every load and spring on the free bodies into the step's system.
void DiscreteStepper::assembleLoads(double t, double h) {
  const std::size_t loads = scenario_.loads.size(), total = loads + scenario_.springs.size();
  for (std::size_t j = 0; j < total; ++j) {
    std::size_t body[2] = {0, 0};
    int count = 1;
    if (j < loads) {
      body[0] = scenario_.loads[j].body;
    } else {
      body[0] = scenario_.springs[j - loads].a;
      body[1] = scenario_.springs[j - loads].b;
      count = 2;
    }
    load_kin_ = kin_;
    for (int c = 0; c < count; ++c) {  // the columns of body c
      const int col = column_[body[c]];
      if (col < 0) continue;
      Vector6d V;
      V << kin_[body[c]].v_WBcm, kin_[body[c]].w_WB;
      for (int k = 0; k < 12; ++k) {
        const bool pose = k >= 6;
        const double step = pose ? kPoseStep : kTwistStep;
        Vector6d up[2], down[2];
        load_kin_[body[c]] = perturbed(kin_[body[c]], scenario_.bodies[body[c]], pose, k % 6, step);
        loadTerms(j, load_kin_, t, up);
        load_kin_[body[c]] =
            perturbed(kin_[body[c]], scenario_.bodies[body[c]], pose, k % 6, -step);
        loadTerms(j, load_kin_, t, down);
        load_kin_[body[c]] = kin_[body[c]];
        for (int r = 0; r < count; ++r) {  // the wrench on body r
          const int row = column_[body[r]];
          if (row < 0) continue;
          const Vector6d column = (up[r] - down[r]) / (2.0 * step);
          // M (V⁺ − V) = h [w0 + D (V⁺ − V) + h K V⁺]
          step_matrix_.block<6, 1>(row, col + k % 6) -= (pose ? h * h : h) * column;
          if (!pose) step_rhs_.segment<6>(row) -= h * column * V(k);
        }
      }
    }
  }
}

}  // namespace vcontact::dynamics
