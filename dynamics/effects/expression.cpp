#include "dynamics/effects/expression.hpp"

#include <muParser.h>

#include <array>
#include <optional>

namespace vcontact::dynamics {
namespace {

// The variables, in the order of Expression::vars_ (kVariableCount entries).
enum Variable {
  kV,
  kFn,
  kDeltaDot,
  kVt,
  kOmegaN,
  kOmegaT,
  kRGyr,
  kS,
  kSMu,
  kVAvg,
  kMuMax,
  kMuC,
  kKv,
  kCv,
  kCw,
  kVEps,
  kTime,
  kVariableCount
};

const std::array<ExpressionVariable, kVariableCount>& variableTable() {
  static const std::array<ExpressionVariable, kVariableCount> t = {{
      {"V", "m^3", "contact volume"},
      {"f_n", "N", "normal force magnitude (after damping)"},
      {"ddot", "m/s", "penetration rate delta_dot_c, positive while closing in"},
      {"v_t", "m/s", "tangential slip speed |v_t|"},
      {"omega_n", "rad/s", "spin about the normal, signed"},
      {"omega_t", "rad/s", "rolling speed |omega_t|"},
      {"r_gyr", "m", "radius of gyration of the contact patch"},
      {"s", "-", "stick-slip state exp(-v_avg^2/v_s^2)"},
      {"s_mu", "-", "stick measure in mu_max (s, or s_dw with dwell)"},
      {"v_avg", "m/s", "sqrt(|v_t|^2 + (r_gyr omega_n)^2)"},
      {"mu_max", "-", "friction limit after stribeck/dwell"},
      {"mu_C", "-", "Coulomb coefficient of the coulomb effect (0 without it)"},
      {"kv", "N/m^3", "volumetric stiffness (0 without stiffness)"},
      {"C_v", "-", "Contensou factor on translation"},
      {"C_w", "-", "Contensou factor on spin"},
      {"v_eps", "m/s", "regularisation speed of dir_eps and sgn_eps"},
      {"t", "s", "time: of the simulation, or of the record's sample in a replay"},
  }};
  return t;
}

enum Term { kNormal, kTangential, kSpin, kTermCount };
constexpr const char* kTermNames[kTermCount] = {"normal", "tangential", "spin"};

class Expression final : public Effect {
 public:
  explicit Expression(std::shared_ptr<const ExpressionDefinition> def) : def_(std::move(def)) {
    checkNames(*def_);
    initialiseParameters(def_->parameters);
    params_.resize(def_->parameters.size(), 0.0);
    compile(kNormal, def_->normal);
    compile(kTangential, def_->tangential);
    compile(kSpin, def_->spin);
  }
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;

  std::string_view id() const override { return def_->id; }
  const std::vector<ParameterSpec>& parameterSpecs() const override { return def_->parameters; }
  Stage stage() const override { return Stage::kFriction; }
  std::vector<std::string_view> requiredEffects() const override {
    return {def_->requires_list.begin(), def_->requires_list.end()};
  }
  std::unique_ptr<Effect> clone() const override {
    auto copy = std::make_unique<Expression>(def_);
    for (std::size_t i = 0; i < def_->parameters.size(); ++i) copy->setParameter(i, parameter(i));
    return copy;
  }
  const ExpressionDefinition& definition() const { return *def_; }

  // F = N n + T dir_ε(v_t), τ = S sgn_ε(ω_n) n  (see the header)
  Wrench apply(ContactContext& ctx) const override {
    load(ctx);
    Wrench w;
    if (terms_[kNormal]) w.f_W += terms_[kNormal]->Eval() * ctx.n;
    if (terms_[kTangential])
      w.f_W += terms_[kTangential]->Eval() * dirEps(ctx.v_t, ctx.settings.v_eps);
    if (terms_[kSpin])
      w.tau_W = terms_[kSpin]->Eval() * sgnEps(ctx.omega_n, ctx.settings.v_eps, ctx.r_gyr) * ctx.n;
    return w;
  }

 private:
  void load(const ContactContext& ctx) const {
    vars_[kV] = ctx.cv->volume;
    vars_[kFn] = ctx.f_n;
    vars_[kDeltaDot] = ctx.delta_dot;
    vars_[kVt] = ctx.v_t.norm();
    vars_[kOmegaN] = ctx.omega_n;
    vars_[kOmegaT] = ctx.omega_t.norm();
    vars_[kRGyr] = ctx.r_gyr;
    vars_[kS] = ctx.s;
    vars_[kSMu] = ctx.s_mu;
    vars_[kVAvg] = ctx.v_avg;
    vars_[kMuMax] = ctx.mu_max;
    vars_[kMuC] = ctx.mu_C;
    vars_[kKv] = ctx.kv;
    vars_[kCv] = ctx.C_v;
    vars_[kCw] = ctx.C_w;
    vars_[kVEps] = ctx.settings.v_eps;
    vars_[kTime] = ctx.t;
    for (std::size_t i = 0; i < params_.size(); ++i) params_[i] = parameter(i);
  }

  // muparser would silently rebind a parameter named like a variable, or a repeated name.
  static void checkNames(const ExpressionDefinition& def) {
    for (std::size_t i = 0; i < def.parameters.size(); ++i) {
      const std::string& name = def.parameters[i].name;
      for (const auto& v : variableTable()) {
        if (name == v.name)
          throw ExpressionSyntaxError("", -1, "parameter '" + name + "' is named like a variable");
      }
      for (std::size_t k = 0; k < i; ++k) {
        if (def.parameters[k].name == name)
          throw ExpressionSyntaxError("", -1, "parameter '" + name + "' appears twice");
      }
    }
  }

  // Binds every variable and parameter, then parses (muparser parses on the first Eval; its
  // value at zero inputs is discarded: 0/0 is not an error there).
  void compile(Term term, const std::string& text) {
    if (text.empty()) return;
    auto& p = terms_[term].emplace();
    try {
      for (int v = 0; v < kVariableCount; ++v) p.DefineVar(variableTable()[v].name, &vars_[v]);
      for (std::size_t i = 0; i < params_.size(); ++i)
        p.DefineVar(def_->parameters[i].name, &params_[i]);
    } catch (const mu::Parser::exception_type& e) {
      throw ExpressionSyntaxError("", -1, "parameter name '" + e.GetToken() + "': " + e.GetMsg());
    }
    try {
      p.SetExpr(text);
      p.Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw ExpressionSyntaxError(kTermNames[term], e.GetPos(), e.GetMsg());
    }
  }

  std::shared_ptr<const ExpressionDefinition> def_;
  mutable std::array<double, kVariableCount> vars_{};
  mutable std::vector<double> params_;  // sized once: the parsers hold pointers into it
  std::array<std::optional<mu::Parser>, kTermCount> terms_;
};

}  // namespace

ExpressionSyntaxError::ExpressionSyntaxError(std::string term, int position, std::string reason)
    : std::runtime_error(reason),
      term_(std::move(term)),
      position_(position),
      reason_(std::move(reason)) {}

const std::vector<ExpressionVariable>& expressionVariables() {
  static const std::vector<ExpressionVariable> v(variableTable().begin(), variableTable().end());
  return v;
}

std::unique_ptr<Effect> makeExpressionEffect(std::shared_ptr<const ExpressionDefinition> def) {
  return std::make_unique<Expression>(std::move(def));
}

const ExpressionDefinition* expressionDefinition(const Effect& effect) {
  const auto* e = dynamic_cast<const Expression*>(&effect);
  return e ? &e->definition() : nullptr;
}

}  // namespace vcontact::dynamics
