#include "dynamics/effects/expression.hpp"

#include <muParser.h>

#include <array>
#include <cctype>
#include <optional>
#include <set>

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

bool isNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The names muparser defines before ours: its functions and its constants (_pi, _e).
const std::set<std::string>& muparserNames() {
  static const std::set<std::string> names = [] {
    const mu::Parser p;
    std::set<std::string> n;
    for (const auto& [name, callback] : p.GetFunDef()) n.insert(name);
    for (const auto& [name, value] : p.GetConst()) n.insert(name);
    return n;
  }();
  return names;
}

// The end of the number starting at `i`: digits, an optional point and digits, an optional
// exponent (muparser's own reading). A number of two or more integer digits starting with 0 is
// refused: "max(0,001*f_n, 1)" would otherwise read as max(0, 1*f_n, 1).
std::size_t scanNumber(Term term, const std::string& text, std::size_t i) {
  const std::size_t start = i;
  while (i < text.size() && isDigit(text[i])) ++i;
  if (i - start > 1 && text[start] == '0') {
    throw ExpressionSyntaxError(kTermNames[term], static_cast<int>(start),
                                "a number starts with 0 followed by a digit; write decimals "
                                "with a point (0.001, not 0,001)");
  }
  if (i < text.size() && text[i] == '.') ++i;
  while (i < text.size() && isDigit(text[i])) ++i;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
    if (j < text.size() && isDigit(text[j])) {
      i = j;
      while (i < text.size() && isDigit(text[i])) ++i;
    }
  }
  return i;
}

// muparser reads more than docs/EXTENDING.md's grammar, and two of its extras change what a
// formula means without an error: ',' outside a function's arguments separates results (the
// last one is kept: "0,001*f_n" is 1*f_n) and '=' assigns to a variable ("0*(f_n=1e3)" changes
// the f_n the next term reads). Both are refused here, with their place; '==', '<=', '>=' and
// '!=' are comparisons.
void checkGrammar(Term term, const std::string& text) {
  if (text.size() > kMaxFormulaLength) {
    throw ExpressionSyntaxError(kTermNames[term], -1,
                                "a formula of " + std::to_string(text.size()) +
                                    " characters; at most " + std::to_string(kMaxFormulaLength) +
                                    " (give a long sub-term its own parameter or effect)");
  }
  std::vector<bool> call;  // each open parenthesis: does it hold a function's arguments?
  bool after_name = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const int at = static_cast<int>(i);
    if (isNameStart(c)) {
      while (i < text.size() && isNameChar(text[i])) ++i;
      after_name = true;
      continue;
    }
    if (isDigit(c) || (c == '.' && i + 1 < text.size() && isDigit(text[i + 1]))) {
      i = scanNumber(term, text, i);
      after_name = false;
      continue;
    }
    if (std::string("<>!=").find(c) != std::string::npos && i + 1 < text.size() &&
        text[i + 1] == '=') {
      i += 2;
      after_name = false;
      continue;
    }
    if (c == '=') {
      throw ExpressionSyntaxError(kTermNames[term], at,
                                  "'=' would assign to a variable, which a formula may not do; "
                                  "compare with '=='");
    }
    if (c == ',' && (call.empty() || !call.back())) {
      throw ExpressionSyntaxError(kTermNames[term], at,
                                  "',' separates a function's arguments only; write decimals "
                                  "with a point (0.001, not 0,001)");
    }
    if (c == '(') call.push_back(after_name);
    if (c == ')' && !call.empty()) call.pop_back();
    if (!std::isspace(static_cast<unsigned char>(c))) after_name = false;
    ++i;
  }
}

// What checkGrammar guarantees, asked of the compiled bytecode: one result, and no assignment
// (a formula never writes a variable).
void checkBytecode(Term term, const mu::Parser& p) {
  const mu::ParserByteCode& code = p.GetByteCode();
  for (std::size_t i = 0; i < code.GetSize(); ++i) {
    if (code.GetBase()[i].Cmd == mu::cmASSIGN)
      throw ExpressionSyntaxError(kTermNames[term], -1, "the formula assigns to a variable");
  }
  if (p.GetNumResults() != 1)
    throw ExpressionSyntaxError(kTermNames[term], -1, "the formula has more than one result");
}

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

  // muparser would silently rebind a parameter named like a variable, or a repeated name, and
  // refuse one named like its functions or constants with a message that does not name it.
  static void checkNames(const ExpressionDefinition& def) {
    for (std::size_t i = 0; i < def.parameters.size(); ++i) {
      const std::string& name = def.parameters[i].name;
      if (!isExpressionName(name)) {
        throw ExpressionSyntaxError("", -1,
                                    "parameter '" + name +
                                        "': expected a name of letters, digits and '_' that "
                                        "does not start with a digit");
      }
      if (muparserNames().count(name) != 0) {
        throw ExpressionSyntaxError(
            "", -1, "parameter '" + name + "' is named like a function or constant of muparser");
      }
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
    checkGrammar(term, text);
    auto& p = terms_[term].emplace();
    for (int v = 0; v < kVariableCount; ++v) p.DefineVar(variableTable()[v].name, &vars_[v]);
    for (std::size_t i = 0; i < params_.size(); ++i) {
      const std::string& name = def_->parameters[i].name;
      try {
        p.DefineVar(name, &params_[i]);
      } catch (const mu::Parser::exception_type& e) {
        throw ExpressionSyntaxError("", -1, "parameter '" + name + "': muparser: " + e.GetMsg());
      }
    }
    try {
      p.SetExpr(text);
      p.Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw ExpressionSyntaxError(kTermNames[term], e.GetPos(), "muparser: " + shortened(e));
    }
    checkBytecode(term, p);
  }

  // muparser's message quotes the token it stopped at, which can be most of the formula.
  static std::string shortened(const mu::Parser::exception_type& e) {
    constexpr std::size_t kLongest = 40;
    std::string msg = e.GetMsg();
    const std::string& token = e.GetToken();
    const std::size_t at = token.size() > kLongest ? msg.find(token) : std::string::npos;
    if (at != std::string::npos) msg.replace(at, token.size(), token.substr(0, kLongest) + "...");
    return msg.size() > 4 * kLongest ? msg.substr(0, 4 * kLongest) + "..." : msg;
  }

  std::shared_ptr<const ExpressionDefinition> def_;
  mutable std::array<double, kVariableCount> vars_{};
  mutable std::vector<double> params_;  // sized once: the parsers hold pointers into it
  std::array<std::optional<mu::Parser>, kTermCount> terms_;
};

}  // namespace

bool isExpressionName(const std::string& name) {
  if (name.empty() || !isNameStart(name[0])) return false;
  for (const char c : name) {
    if (!isNameChar(c)) return false;
  }
  return true;
}

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
