#include "dynamics/model.hpp"

#include <algorithm>
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
  if (has("stribeck") && parameter("stribeck.mu_s") < parameter("coulomb.mu")) {
    std::ostringstream s;
    s << "stribeck.mu_s = " << parameter("stribeck.mu_s")
      << " must be >= coulomb.mu = " << parameter("coulomb.mu") << " (MODEL.md section 3)";
    throw InputError(kSource, s.str());
  }
}

bool Model::has(std::string_view id) const {
  return std::any_of(effects_.begin(), effects_.end(),
                     [&](const auto& e) { return e->id() == id; });
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

Eigen::Isometry3d Model::adjustPayloadPose(const Eigen::Isometry3d& X_W1,
                                           const Eigen::Isometry3d& X_W2) const {
  Eigen::Isometry3d X = X_W1;
  if (!adjusts_pose_) return X;
  for (const auto& e : effects_) X = e->adjustPayloadPose(X, X_W2);
  return X;
}

// Pass 1 (configure) and the shared derivations of MODEL.md §2–3.
ContactContext Model::makeContext(const volume::ContactVolume& cv, const RelativeMotion& motion,
                                  const PairState& state) const {
  ContactContext ctx;
  ctx.cv = &cv;
  ctx.settings = settings;
  ctx.n = cv.n_W;
  ctx.state = state;
  ctx.state.z_W -= ctx.n * ctx.n.dot(state.z_W);  // z lives in the contact plane
  const Eigen::Vector3d& v_c = motion.v_c_W;
  ctx.delta_dot = -v_c.dot(ctx.n);
  ctx.v_t = v_c - v_c.dot(ctx.n) * ctx.n;
  ctx.omega_n = motion.w_W.dot(ctx.n);
  ctx.omega_t = motion.w_W - ctx.omega_n * ctx.n;
  ctx.r_gyr = cv.r_gyr;
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
  if (!has("coulomb")) {
    throw InputError(kSource,
                     "distributed friction integrates coulomb's friction pointwise; "
                     "add the coulomb effect");
  }
  if (has("bristle")) {
    throw InputError(kSource,
                     "distributed friction is pointwise Coulomb friction and cannot "
                     "replace the bristle law; remove bristle or use lumped friction");
  }
}

void Model::evaluate(const volume::ContactVolume& cv, const RelativeMotion& motion,
                     const PairState& state, ContactResult& r,
                     const volume::DepthField* field) const {
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
}

bool Model::settle(const volume::ContactVolume& cv, const RelativeMotion& motion,
                   PairState& state) const {
  const PairState before = state;
  if (!cv.inContact()) {
    state = PairState{};
  } else {
    const ContactContext ctx = makeContext(cv, motion, state);
    state.z_W = ctx.state.z_W;
    for (const auto& e : effects_) e->settle(ctx, state);
  }
  const double change = (state.z_W - before.z_W).norm() /
                            std::max(before.z_W.norm(), std::numeric_limits<double>::min()) +
                        std::abs(state.theta_n - before.theta_n) +
                        std::abs(state.s_dw - before.s_dw);
  return change > kSettleChangeTolerance;
}

}  // namespace vcontact::dynamics
