#include "dynamics/rigid_body.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/mass_properties.hpp"

namespace vcontact::dynamics {
namespace {

struct SizeOf {
  double operator()(const geometry::Sphere& s) const { return 2.0 * s.radius; }
  double operator()(const geometry::Cylinder& c) const {
    return std::min(2.0 * c.radius, c.length);
  }
  double operator()(const geometry::Box& b) const { return b.size.minCoeff(); }
  double operator()(const geometry::HalfSpace&) const {
    return std::numeric_limits<double>::infinity();
  }
  double operator()(const geometry::Mesh& m) const {
    const geometry::Aabb box = geometry::bounds(*m.mesh);
    return (box.max - box.min).minCoeff();
  }
};

}  // namespace

PathPoint prescribedPath(const Eigen::Isometry3d& X_W0, const PrescribedMotion& m, double t) {
  if (m.trajectory) return m.trajectory->at(t);
  PathPoint out;
  out.X_WB = X_W0;
  const double angle = m.w_W.norm() * t;
  if (angle > 0.0) {
    out.X_WB.linear() =
        Eigen::AngleAxisd(angle, m.w_W.normalized()).toRotationMatrix() * X_W0.linear();
  }
  const double phase = 2.0 * std::numbers::pi * m.frequency_hz * t;
  out.X_WB.translation() = X_W0.translation() + m.v_W * t + m.amplitude_W * std::sin(phase);
  out.v_WBo = m.v_W + m.amplitude_W * (2.0 * std::numbers::pi * m.frequency_hz * std::cos(phase));
  out.w_WB = m.w_W;
  return out;
}

BodyKinematics scheduledKinematics(const RigidBody& body, double t) {
  BodyKinematics k;
  k.t = t;
  k.X_WB = body.X_WB0;
  if (body.motion == BodyMotion::kPrescribed) {
    const PathPoint path = prescribedPath(body.X_WB0, body.prescribed, t);
    k.X_WB = path.X_WB;
    // Velocity of the frame origin Bo; Bcm moves with the rotation about Bo.
    k.w_WB = path.w_WB;
    k.p_WBcm = k.X_WB * body.p_BBcm;
    k.v_WBcm = path.v_WBo + path.w_WB.cross(k.p_WBcm - k.X_WB.translation());
    return k;
  }
  k.p_WBcm = k.X_WB * body.p_BBcm;
  return k;
}

double characteristicSize(const geometry::Shape& shape) { return std::visit(SizeOf{}, shape); }

void setMassFromDensity(RigidBody& body, double density) {
  const geometry::MassProperties mp =
      geometry::massProperties(geometry::solidMoments(body.shape), density);
  body.mass = mp.mass;
  body.p_BBcm = mp.com;
  body.I_BBcm_B = mp.inertia;
}

}  // namespace vcontact::dynamics
