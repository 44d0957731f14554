#include "dynamics/recovered_pairs.hpp"

#include <algorithm>

#include "dynamics/scenario.hpp"
#include "volume/recovered/recovered_surface.hpp"

namespace vcontact::dynamics {
namespace {

bool isHalfspace(const geometry::Shape& s) {
  return std::holds_alternative<geometry::HalfSpace>(s);
}

SurfaceBodyUse bodyUse(const RigidBody& body) {
  const geometry::SurfaceRecognition& r = body.surface->recognition;
  SurfaceBodyUse u;
  u.body = body.name;
  u.recognition_seconds = body.surface->recognition_seconds;
  for (const geometry::RecognisedSurface& s : r.surfaces) {
    ++u.kinds[std::string(s.convex ? "" : "concave ") + geometry::surfaceKindName(s.kind)];
    u.max_residual = std::max(u.max_residual, s.max_residual);
  }
  u.free_form_faces = r.free_form_faces;
  u.description = volume::recognisedKinds(r);
  return u;
}

// Why a pair with a recovered body uses the polyhedra for every query; "" when it need not:
// a recovered mesh against a half-space, queried by the half-space clip it replaces.
std::string polyhedralReason(const Scenario& s, const ContactPair& p) {
  const RigidBody& a = s.bodies[p.a];
  const RigidBody& b = s.bodies[p.b];
  const bool onPlane = (a.surface && isHalfspace(b.shape)) || (b.surface && isHalfspace(a.shape));
  if (!onPlane) {
    const RigidBody& other = a.surface ? b : a;
    return "the partner '" + other.name + "' is a " + geometry::shapeKind(other.shape) +
           "; a recovered surface has closed forms against a half-space only (a recovered "
           "surface against another body needs the local refinement, not built)";
  }
  if (p.friction == FrictionMode::kDistributed) {
    return "distributed friction integrates over the columns of the polyhedron";
  }
  if (p.method && *p.method != volume::Method::kHalfspace) {
    return "the pair asks for method '" + volume::methodName(*p.method) +
           "'; the recovered surface replaces the half-space clip only";
  }
  return "";
}

}  // namespace

RecoveredPairs::RecoveredPairs(const Scenario& scenario) {
  for (const RigidBody& b : scenario.bodies) {
    if (b.surface) bodies_.push_back(bodyUse(b));
  }
  for (const ContactPair& p : scenario.pairs) {
    PairPlan plan;
    const RigidBody& a = scenario.bodies[p.a];
    const RigidBody& b = scenario.bodies[p.b];
    if (a.surface || b.surface) {
      plan.use = static_cast<int>(uses_.size());
      uses_.push_back(SurfacePairUse{p.name, polyhedralReason(scenario, p), {}, {}});
      plan.on_surface = uses_.back().polyhedral_reason.empty();
      plan.swapped = !a.surface;
      if (plan.on_surface) plan.surface = plan.swapped ? b.surface : a.surface;
    }
    plans_.push_back(plan);
  }
}

void RecoveredPairs::resetCounts() {
  for (SurfacePairUse& u : uses_) {
    u.evaluations.clear();
    u.mesh_reasons.clear();
  }
}

volume::ContactPatches RecoveredPairs::contact(
    std::size_t k, const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB,
    const std::function<volume::ContactPatches()>& polyhedral) {
  const PairPlan& plan = plans_[k];
  if (plan.use < 0) return polyhedral();
  SurfacePairUse& use = uses_[static_cast<std::size_t>(plan.use)];
  if (plan.on_surface) {
    std::string reason;
    const Eigen::Isometry3d& X_WM = plan.swapped ? X_WB : X_WA;
    const Eigen::Isometry3d& X_WH = plan.swapped ? X_WA : X_WB;
    if (auto r = plan.surface->body->closedFormContact(X_WM, X_WH, reason)) {
      ++use.evaluations[r->representation];
      // n points out of B into A: out of the plane into the mesh, or the reverse when swapped
      if (plan.swapped) r->cv.n_W = -r->cv.n_W;
      return volume::singlePatch(r->cv);
    }
    use.mesh_reasons.insert(reason);
  }
  ++use.evaluations["mesh"];
  return polyhedral();
}

}  // namespace vcontact::dynamics
