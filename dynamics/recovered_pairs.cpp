#include "dynamics/recovered_pairs.hpp"

#include <algorithm>

#include "dynamics/scenario.hpp"
#include "volume/contact.hpp"

namespace vcontact::dynamics {
namespace {

bool isHalfspace(const geometry::Shape& s) {
  return std::holds_alternative<geometry::HalfSpace>(s);
}

SurfaceBodyUse bodyUse(const RigidBody& body) {
  const geometry::SurfaceRecognition& r = volume::recognition(*body.surface);
  SurfaceBodyUse u;
  u.body = body.name;
  u.recognition_seconds = volume::recognitionSeconds(*body.surface);
  for (const geometry::RecognisedSurface& s : r.surfaces) {
    ++u.kinds[std::string(s.convex ? "" : "concave ") + geometry::surfaceKindName(s.kind)];
    u.max_residual = std::max(u.max_residual, s.max_residual);
  }
  u.free_form_faces = r.free_form_faces;
  u.description = volume::recognisedKinds(r);
  return u;
}

// Why a pair with a recovered body uses the polyhedra for every query; "" when it need not: a
// recovered mesh against a half-space or another mesh, queried by the method the recovered
// surfaces replace (the default, or the exact polyhedral method it falls back to).
std::string polyhedralReason(const Scenario& s, const ContactPair& p) {
  const RigidBody& a = s.bodies[p.a];
  const RigidBody& b = s.bodies[p.b];
  const RigidBody& other = a.surface ? b : a;
  const bool meshPartner = std::holds_alternative<geometry::Mesh>(other.shape);
  if (!meshPartner && !isHalfspace(other.shape)) {
    return "the partner '" + other.name + "' is a " + geometry::shapeKind(other.shape) +
           "; a recovered surface is computed against a half-space or another mesh";
  }
  if (p.friction == FrictionMode::kDistributed) {
    return "distributed friction integrates over the columns of the polyhedron";
  }
  const volume::Method replaced = meshPartner ? volume::Method::kFast : volume::Method::kHalfspace;
  if (p.method && *p.method != replaced && *p.method != volume::Method::kRecovered) {
    return "the pair asks for method '" + volume::methodName(*p.method) +
           "'; the recovered surface replaces " + volume::methodName(replaced) + " only";
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
    if (scenario.bodies[p.a].surface || scenario.bodies[p.b].surface) {
      plan.use = static_cast<int>(uses_.size());
      uses_.push_back(SurfacePairUse{p.name, polyhedralReason(scenario, p), {}, {}});
      plan.on_surface = uses_.back().polyhedral_reason.empty();
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

void RecoveredPairs::count(std::size_t k, const volume::ContactPatches& contact) {
  const PairPlan& plan = plans_[k];
  if (plan.use < 0) return;
  SurfacePairUse& use = uses_[static_cast<std::size_t>(plan.use)];
  if (!plan.on_surface) {
    ++use.evaluations["mesh"];
    return;
  }
  ++use.evaluations[volume::representationName(contact.surface.representation)];
  if (!contact.surface.reason.empty()) use.mesh_reasons.insert(contact.surface.reason);
}

}  // namespace vcontact::dynamics
