#include "dynamics/model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <sstream>

#include "dynamics/effects/registry.hpp"
#include "geometry/error.hpp"

namespace vcontact::dynamics {
namespace {

const std::string kSource = "model";

// A state jump below this (relative to the state's own scale) is round-off of the projection,
// not a change the integrator needs to know about.
constexpr double kSettleChangeTolerance = 1e-12;

// The size of a settle jump: a plane vector's change relative to its length, a scalar's
// absolute change, summed over the slots.
double stateChange(const StateLayout& layout, const PairState& before, const PairState& after) {
  double change = 0.0;
  for (const StateLayout::Entry& e : layout.entries()) {
    if (e.slot.kind == StateSlot::Kind::kPlaneVector) {
      change += (after.vector(e.offset) - before.vector(e.offset)).norm() /
                std::max(before.vector(e.offset).norm(), std::numeric_limits<double>::min());
    } else {
      change += std::abs(after[e.offset] - before[e.offset]);
    }
  }
  return change;
}

// The registered effects that integrate distributed friction, as "a or b" (coulomb).
std::string distributedFrictionIntegrators() {
  std::string ids;
  for (const auto& id : registeredEffectIds()) {
    if (!createEffect(id)->integratesDistributedFriction()) continue;
    ids += (ids.empty() ? "" : " or ") + id;
  }
  return ids;
}

std::string qualified(const Effect& e, const ParameterSpec& p) {
  std::ostringstream s;
  s << e.id() << '.' << p.name;
  return s.str();
}

void checkValue(const std::string& name, const ParameterSpec& spec, double value) {
  if (std::isfinite(value) && value >= spec.lower && value <= spec.upper) return;
  std::ostringstream s;
  s << name << " = " << value << " is outside its physical range [" << spec.lower << ", "
    << spec.upper << "] " << spec.unit;
  throw InputError(kSource, s.str());
}

}  // namespace

Model::Model(const Model& other)
    : settings(other.settings), fixed_(other.fixed_), adjusts_pose_(other.adjusts_pose_) {
  for (const auto& e : other.effects_) effects_.push_back(e->clone());
}

Model& Model::operator=(const Model& other) {
  if (this != &other) *this = Model(other);
  return *this;
}

Model Model::withEffects(const std::vector<std::string>& ids) {
  Model m;
  for (const auto& id : ids) {
    auto e = createEffect(id);
    if (!e) throw InputError(kSource, "unknown effect '" + id + "'");
    m.add(std::move(e));
  }
  m.validate();
  return m;
}

void Model::add(std::unique_ptr<Effect> effect) {
  if (has(effect->id())) {
    throw InputError(kSource, "effect '" + std::string(effect->id()) + "' appears twice");
  }
  effect->setStateOffset(stateLayout().offsetOf(std::string(effect->id())));
  assert(effect->stateSlots().empty() || effect->stateOffset() >= 0);
  const auto after =
      std::upper_bound(effects_.begin(), effects_.end(), effect->stage(),
                       [](Stage s, const std::unique_ptr<Effect>& e) { return s < e->stage(); });
  adjusts_pose_ = adjusts_pose_ || effect->stage() == Stage::kGeometryOnly;
  effects_.insert(after, std::move(effect));
}

void Model::validate() const {
  for (const auto& e : effects_) {
    for (auto req : e->requiredEffects()) {
      if (has(req)) continue;
      std::ostringstream s;
      s << "effect '" << e->id() << "' needs effect '" << req << "' in the same model";
      throw InputError(kSource, s.str());
    }
  }
  for (const auto& e : effects_) {
    const std::string broken = e->brokenRelation(*this);
    if (!broken.empty()) throw InputError(kSource, broken);
  }
}

bool Model::has(std::string_view id) const {
  return std::any_of(effects_.begin(), effects_.end(),
                     [&](const auto& e) { return e->id() == id; });
}

bool Model::hasStage(Stage stage) const {
  return std::any_of(effects_.begin(), effects_.end(),
                     [&](const auto& e) { return e->stage() == stage; });
}

std::vector<std::string> Model::effectIds() const {
  std::vector<std::string> ids;
  for (const auto& e : effects_) ids.emplace_back(e->id());
  return ids;
}

std::vector<std::string> Model::parameterNames() const {
  std::vector<std::string> names;
  for (const auto& e : effects_) {
    for (const auto& p : e->parameterSpecs()) names.push_back(qualified(*e, p));
  }
  return names;
}

std::vector<ParameterSpec> Model::parameterSpecs() const {
  std::vector<ParameterSpec> specs;
  for (const auto& e : effects_) {
    for (ParameterSpec p : e->parameterSpecs()) {
      p.name = qualified(*e, p);
      specs.push_back(std::move(p));
    }
  }
  return specs;
}

std::vector<double> Model::parameters() const {
  std::vector<double> values;
  for (const auto& e : effects_) {
    const auto v = e->parameters();
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

void Model::setParameters(std::span<const double> values) {
  const auto specs = parameterSpecs();
  if (values.size() != specs.size()) {
    std::ostringstream s;
    s << "expected " << specs.size() << " parameter values, got " << values.size();
    throw InputError(kSource, s.str());
  }
  for (std::size_t i = 0; i < specs.size(); ++i) checkValue(specs[i].name, specs[i], values[i]);
  std::size_t k = 0;
  for (auto& e : effects_) {
    for (std::size_t i = 0; i < e->parameterSpecs().size(); ++i) e->setParameter(i, values[k++]);
  }
}

std::pair<std::size_t, std::size_t> Model::locate(const std::string& name) const {
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    const auto& specs = effects_[i]->parameterSpecs();
    for (std::size_t j = 0; j < specs.size(); ++j) {
      if (qualified(*effects_[i], specs[j]) == name) return {i, j};
    }
  }
  throw InputError(kSource, "no parameter '" + name + "' in this model");
}

void Model::setParameter(const std::string& name, double value) {
  const auto [i, j] = locate(name);
  checkValue(name, effects_[i]->parameterSpecs()[j], value);
  effects_[i]->setParameter(j, value);
}

double Model::parameter(const std::string& name) const {
  const auto [i, j] = locate(name);
  return effects_[i]->parameter(j);
}

void Model::setFixed(std::vector<std::string> names) {
  for (const auto& n : names) locate(n);
  fixed_ = std::move(names);
}

const StateLayout& Model::stateLayout() const { return registeredStateLayout(); }

Eigen::Isometry3d Model::adjustPayloadPose(const Eigen::Isometry3d& X_WA,
                                           const Eigen::Isometry3d& X_WB) const {
  Eigen::Isometry3d X_WA_adjusted = X_WA;
  if (!adjusts_pose_) return X_WA_adjusted;
  for (const auto& e : effects_) X_WA_adjusted = e->adjustPayloadPose(X_WA_adjusted, X_WB);
  return X_WA_adjusted;
}

// Pass 1 (configure) and the shared derivations of MODEL.md §2–3.
ContactContext Model::makeContext(const volume::ContactVolume& cv, const RelativeMotion& motion,
                                  const PairState& state) const {
  ContactContext ctx;
  ctx.cv = &cv;
  ctx.settings = settings;
  ctx.n = cv.n_W;
  ctx.state = state;
  for (const StateLayout::Entry& e : stateLayout().entries()) {
    if (e.slot.kind != StateSlot::Kind::kPlaneVector) continue;
    ctx.state.vector(e.offset) -= ctx.n * ctx.n.dot(state.vector(e.offset));  // in the plane
  }
  const ContactKinematics k = resolve(motion, ctx.n);
  ctx.delta_dot = k.delta_dot;
  ctx.v_t = k.v_t_W;
  ctx.omega_n = k.omega_n;
  ctx.omega_t = k.omega_t_W;
  ctx.r_gyr = cv.r_gyr;
  ctx.t = motion.t;
  for (const auto& e : effects_) e->configure(ctx);
  // v_avg² = |v_t|² + (r_gyr ω_n)²,  s = exp(−v_avg²/v_s²)
  const double spin_speed = ctx.r_gyr * ctx.omega_n;
  ctx.v_avg = std::sqrt(ctx.v_t.squaredNorm() + spin_speed * spin_speed);
  ctx.s = std::exp(-(ctx.v_avg * ctx.v_avg) / (ctx.v_s * ctx.v_s));
  ctx.s_mu = ctx.s;
  ctx.mu_max = ctx.mu_C;
  return ctx;
}

ContactResult Model::evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                              const PairState& state, const volume::DepthField* field) const {
  ContactResult r;
  evaluate(cv, motion, state, r, field);
  return r;
}

void Model::checkDistributedFriction() const {
  if (std::none_of(effects_.begin(), effects_.end(),
                   [](const auto& e) { return e->integratesDistributedFriction(); })) {
    const std::string id = distributedFrictionIntegrators();
    throw InputError(kSource, "distributed friction integrates " + id +
                                  "'s friction pointwise; add the " + id + " effect");
  }
  for (const auto& e : effects_) {
    const std::string_view conflict = e->distributedFrictionConflict();
    if (!conflict.empty()) throw InputError(kSource, std::string(conflict));
  }
}

void Model::evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                     const PairState& state, ContactResult& r, const volume::DepthField* field,
                     ContactContext* context) const {
  r.shares.assign(effects_.size(), Wrench{});
  r.wrench = Wrench{};
  r.rates = PairStateRates{};
  r.f_n = r.s = r.mu_max = 0.0;
  if (!cv.inContact()) return;
  ContactContext ctx = makeContext(cv, motion, state);
  ctx.field = field;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    r.shares[i] = effects_[i]->apply(ctx);  // pass 2, in Stage order
    r.wrench += r.shares[i];
  }
  r.rates = ctx.rates;
  r.f_n = ctx.f_n;
  r.s = ctx.s;
  r.mu_max = ctx.mu_max;
  if (context) *context = ctx;
}

ContactContext Model::context(const volume::ContactVolume& cv, const RelativeMotion& motion,
                              const PairState& state) const {
  ContactContext ctx = makeContext(cv, motion, state);
  for (const auto& e : effects_) e->apply(ctx);
  return ctx;
}

void Model::linearise(const ContactContext& ctx, StepTerms& terms) const {
  for (const auto& e : effects_) e->linearise(ctx, terms);  // a no-op unless kLinearised
}

std::vector<std::string> Model::explicitEffects() const {
  std::vector<std::string> ids;
  for (const auto& e : effects_) {
    if (e->stepForm() == StepForm::kExplicit) ids.emplace_back(e->id());
  }
  return ids;
}

double Model::impactRestitution(double approach) const {
  double e = 1.0;
  for (const auto& effect : effects_) e = std::min(e, effect->restitution(approach));
  return e;
}

bool Model::settle(const volume::ContactVolume& cv, const RelativeMotion& motion,
                   PairState& state) const {
  const PairState before = state;
  if (!cv.inContact()) {
    state = PairState{};
  } else {
    const ContactContext ctx = makeContext(cv, motion, state);
    state = ctx.state;  // plane vectors projected
    for (const auto& e : effects_) e->settle(ctx, state);
  }
  return stateChange(stateLayout(), before, state) > kSettleChangeTolerance;
}

}  // namespace vcontact::dynamics
