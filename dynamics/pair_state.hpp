#pragma once
// Internal state of one contact pair (MODEL.md §3 "State handling").
//
// The bristle deflection z is a 2-vector in the contact plane. It is stored in world
// coordinates (a 3-vector with z·n = 0) so that it needs no tangent basis that would have to
// turn with the normal: when the normal turns, z is projected onto the new plane
// (Model::settle), and every effect reads the projected value.

#include <Eigen/Core>
#include <array>

namespace vcontact::dynamics {

struct PairState {
  Eigen::Vector3d z_W = Eigen::Vector3d::Zero();  ///< bristle deflection, m, in the contact plane
  double theta_n = 0.0;                           ///< torsional bristle deflection, rad
  double s_dw = 0.0;                              ///< dwell stick state, – (0..1)

  static constexpr int kSize = 5;  ///< number of scalars in the integrator's state vector

  /// Writes the state to `out[0..kSize)` in the order z_W(0..2), theta_n, s_dw.
  void pack(double* out) const {
    out[0] = z_W.x();
    out[1] = z_W.y();
    out[2] = z_W.z();
    out[3] = theta_n;
    out[4] = s_dw;
  }
  static PairState unpack(const double* in) {
    PairState s;
    s.z_W = Eigen::Vector3d(in[0], in[1], in[2]);
    s.theta_n = in[3];
    s.s_dw = in[4];
    return s;
  }
};

/// Time derivatives of a PairState, in the same layout (m/s, rad/s, 1/s).
using PairStateRates = PairState;

}  // namespace vcontact::dynamics
