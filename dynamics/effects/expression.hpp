#pragma once
// expression: an effect written by the user as formulas (muparser), with named parameters that
// simulation, replay, fit and diagnose treat like those of a built-in effect. It applies in
// Stage::kFriction and so reads the context as the friction effects do (f_n after damping,
// μ_max after stribeck). Its wrench share on body A at p_c is
//
//   F = N n + T dir_ε(v_t),   τ = S sgn_ε(ω_n) n
//
// with N (normal, N), T (tangential, N) and S (spin, N·m) the three terms, each a formula in
// the parameters and the variables of expressionVariables() (MODEL.md §2 quantities); a term
// left empty is zero. A friction term is negative (it opposes the slip). A term linear in the
// slip is written with max(v_t, v_eps), since dir_ε(v_t) max(|v_t|, v_ε) = v_t exactly (and
// max(abs(omega_n), v_eps/r_gyr) for spin). docs/EXTENDING.md documents the model-file form.
//
// An instance owns its compiled formulas and the variables they read: evaluating it writes
// them, so one Model holding it must not be evaluated from two threads at once (each fit and
// each diagnose candidate works on its own copy of the model).

#include <memory>
#include <string>
#include <vector>

#include "dynamics/effect.hpp"

namespace vcontact::dynamics {

/// What the user writes: an id, parameters and the three terms.
struct ExpressionDefinition {
  std::string id;                          ///< the effect's name in the model, e.g. "mu_load"
  std::vector<ParameterSpec> parameters;   ///< names usable in the terms
  std::string normal;                      ///< N along n; empty: 0
  std::string tangential;                  ///< N along dir_ε(v_t); empty: 0
  std::string spin;                        ///< N·m along sgn_ε(ω_n) n; empty: 0
  std::vector<std::string> requires_list;  ///< effects it needs in the same model
};

/// One variable a term can read, its unit and meaning (for messages and docs).
struct ExpressionVariable {
  const char* name;
  const char* unit;
  const char* meaning;
};
const std::vector<ExpressionVariable>& expressionVariables();

/// The longest formula a term may be (characters): a formula longer than a page is not one a
/// reader can check, and muparser's own limit (10,000 in 2.3) refuses it by quoting all of it.
inline constexpr std::size_t kMaxFormulaLength = 5000;

/// Whether `name` can name an expression effect or parameter: letters, digits and '_', not
/// starting with a digit (the characters of a muparser name, and of the CSV column ID.NAME).
bool isExpressionName(const std::string& name);

/// A term that does not compile: which term, where in it (0-based character), and why.
class ExpressionSyntaxError : public std::runtime_error {
 public:
  ExpressionSyntaxError(std::string term, int position, std::string reason);
  const std::string& term() const { return term_; }  ///< "normal", "tangential", "spin", ""
  int position() const { return position_; }         ///< −1 when not about one place
  /// "muparser: ..." when muparser refused the term, else the engine's own check
  const std::string& reason() const { return reason_; }

 private:
  std::string term_;
  int position_;
  std::string reason_;
};

/// Compiles the definition into an effect with the parameters at their defaults.
/// @throws ExpressionSyntaxError on a bad parameter name, a term that does not parse, an
///         unknown name in a term
std::unique_ptr<Effect> makeExpressionEffect(std::shared_ptr<const ExpressionDefinition> def);

/// The definition of an expression effect, or null for any other effect.
const ExpressionDefinition* expressionDefinition(const Effect& effect);

}  // namespace vcontact::dynamics
