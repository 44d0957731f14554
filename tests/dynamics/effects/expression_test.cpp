// expression (dynamics/effects/expression.hpp): F = N n + T dir_ε(v_t), τ = S sgn_ε(ω_n) n with
// the three terms compiled by muparser. Written to equal a built-in effect, it must give that
// effect's wrench to round-off, at any speed (above and below the regularisation speed).

#include "dynamics/effects/expression.hpp"

#include <gtest/gtest.h>

#include "dynamics/effects/effect_base.hpp"
#include "effect_fixtures.hpp"

namespace vcontact::dynamics::test {
namespace {

std::shared_ptr<const ExpressionDefinition> definition(std::string tangential, std::string spin,
                                                       std::vector<ParameterSpec> params) {
  auto d = std::make_shared<ExpressionDefinition>();
  d->id = "user";
  d->parameters = std::move(params);
  d->tangential = std::move(tangential);
  d->spin = std::move(spin);
  d->requires_list = {"stiffness"};
  return d;
}

const ParameterSpec kMu{"mu", "-", 0.2, 0.0, 10.0, "friction coefficient"};

// Motions at the sphere contact: fast sliding, creep below v_ε, spin only, and both.
std::vector<RelativeMotion> motions(const volume::ContactVolume& cv, double v_eps) {
  const Eigen::Vector3d t = tangent(cv.n_W);
  std::vector<RelativeMotion> m(4);
  m[0].v_c_W = 0.5 * t;
  m[1].v_c_W = 0.25 * v_eps * t.cross(cv.n_W);
  m[2].w_W = 2.0 * cv.n_W;
  m[3].v_c_W = 0.01 * t;
  m[3].w_W = -0.3 * cv.n_W + 0.7 * t;
  return m;
}

void expectSameWrench(const Model& a, const Model& b) {
  const volume::ContactVolume cv = sphereContact();
  const double N = a.parameter("stiffness.kv") * cv.volume;
  for (const RelativeMotion& mo : motions(cv, a.settings.v_eps)) {
    const Wrench wa = a.evaluate(cv, mo, PairState{}).wrench;
    const Wrench wb = b.evaluate(cv, mo, PairState{}).wrench;
    EXPECT_LT((wa.f_W - wb.f_W).norm(), kRoundOff * N);
    EXPECT_LT((wa.tau_W - wb.tau_W).norm(), kRoundOff * N * cv.r_gyr);
  }
}

TEST(Expression, WrittenAsCoulombAndSpinGivesTheirWrench) {
  Model builtin = Model::withEffects({"stiffness", "coulomb", "spin"});
  builtin.setParameter("coulomb.mu", 0.3);
  Model user = Model::withEffects({"stiffness"});
  user.add(makeExpressionEffect(definition("-mu*f_n", "-mu*r_gyr*f_n", {kMu})));
  user.validate();
  user.setParameter("user.mu", 0.3);
  expectSameWrench(builtin, user);
}

TEST(Expression, ALinearSlipTermWrittenWithMaxGivesViscousEvenBelowVEps) {
  Model builtin = Model::withEffects({"stiffness", "viscous"});
  builtin.setParameter("viscous.sigma2", 4.0);
  Model user = Model::withEffects({"stiffness"});
  user.add(makeExpressionEffect(definition("-sigma2*f_n*max(v_t, v_eps)",
                                           "-sigma2*r_gyr^2*f_n*max(abs(omega_n), v_eps/r_gyr)",
                                           {{"sigma2", "s/m", 0.0, 0.0, 1e9, "viscous"}})));
  user.setParameter("user.sigma2", 4.0);
  expectSameWrench(builtin, user);
}

TEST(Expression, ACopiedModelKeepsItsValuesAndEvaluatesOnItsOwn) {
  Model a = Model::withEffects({"stiffness"});
  a.add(makeExpressionEffect(definition("-mu*f_n", "", {kMu})));
  a.setParameter("user.mu", 0.5);
  Model b = a;
  b.setParameter("user.mu", 0.1);
  const volume::ContactVolume cv = sphereContact();
  const double N = a.parameter("stiffness.kv") * cv.volume;
  RelativeMotion mo;
  mo.v_c_W = tangent(cv.n_W);
  // Share 1 is the expression's: −μ N t, with each model's own μ.
  EXPECT_LT((a.evaluate(cv, mo, PairState{}).shares[1].f_W + 0.5 * N * mo.v_c_W).norm(),
            kRoundOff * N);
  EXPECT_LT((b.evaluate(cv, mo, PairState{}).shares[1].f_W + 0.1 * N * mo.v_c_W).norm(),
            kRoundOff * N);
  EXPECT_EQ(a.parameterNames(), (std::vector<std::string>{"stiffness.kv", "user.mu"}));
}

// t reads the time the motion carries (the simulation's, or the record's sample in a replay).
TEST(Expression, TheVariableTIsTheTimeOfTheMotion) {
  auto d = std::make_shared<ExpressionDefinition>();
  d->id = "ramp";
  d->parameters = {{"c", "N/s", 0.0, 0.0, 1e3, "force growth per second"}};
  d->normal = "c*t";
  Model m = Model::withEffects({"stiffness"});
  m.add(makeExpressionEffect(d));
  m.setParameter("ramp.c", 4.0);
  const volume::ContactVolume cv = sphereContact();
  const double N = m.parameter("stiffness.kv") * cv.volume;
  RelativeMotion mo;
  for (double t : {0.0, 0.5, 2.5}) {
    mo.t = t;
    const Wrench share = m.evaluate(cv, mo, PairState{}).shares[1];
    EXPECT_LT((share.f_W - 4.0 * t * cv.n_W).norm(), kRoundOff * N) << "t = " << t;
  }
}

TEST(Expression, AFormulaThatDoesNotParseNamesItsTermAndPosition) {
  try {
    makeExpressionEffect(definition("-mu*f_n*", "", {kMu}));
    FAIL() << "a dangling operator must not compile";
  } catch (const ExpressionSyntaxError& e) {
    EXPECT_EQ(e.term(), "tangential");
    EXPECT_GE(e.position(), 7);  // at or after the '*' at index 7
    EXPECT_FALSE(e.reason().empty());
  }
  try {
    makeExpressionEffect(definition("", "-mu*f_n*grip", {kMu}));
    FAIL() << "an unknown name must not compile";
  } catch (const ExpressionSyntaxError& e) {
    EXPECT_EQ(e.term(), "spin");
    EXPECT_EQ(e.position(), 8);  // "grip" starts at index 8
  }
}

TEST(Expression, AParameterNamedLikeAVariableOrTwiceIsRefused) {
  EXPECT_THROW(makeExpressionEffect(definition("-f_n", "", {{"s", "-", 0, 0, 1, ""}})),
               ExpressionSyntaxError);
  EXPECT_THROW(makeExpressionEffect(definition("-mu*f_n", "", {kMu, kMu})), ExpressionSyntaxError);
}

// ---- The C++ path (docs/EXTENDING.md): the same load-dependent friction as one class ----------

// load_friction: f_t = −b f_n² dir_ε(v_t), a friction coefficient b f_n that grows with the load.
class LoadFriction final : public EffectBase<LoadFriction> {
 public:
  static constexpr std::string_view kId = "load_friction";
  static constexpr Stage kStage = Stage::kFriction;
  static const std::vector<ParameterSpec>& specs() {
    static const std::vector<ParameterSpec> s = {
        {"b", "1/N", 0.0, 0.0, 1e3, "growth of the friction coefficient with the load"}};
    return s;
  }
  std::vector<std::string_view> requiredEffects() const override { return {"stiffness"}; }
  Wrench apply(ContactContext& ctx) const override {
    return {-parameter(0) * ctx.f_n * ctx.f_n * dirEps(ctx.v_t, ctx.settings.v_eps),
            Eigen::Vector3d::Zero()};
  }
};

TEST(Expression, TheCompiledLoadFrictionExampleEqualsItsExpression) {
  Model compiled = Model::withEffects({"stiffness", "coulomb"});
  compiled.add(std::make_unique<LoadFriction>());
  compiled.setParameter("load_friction.b", 0.04);
  Model user = Model::withEffects({"stiffness", "coulomb"});
  user.add(makeExpressionEffect(definition("-b*f_n^2", "", {{"b", "1/N", 0, 0, 1e3, ""}})));
  user.setParameter("user.b", 0.04);
  expectSameWrench(compiled, user);
}

}  // namespace
}  // namespace vcontact::dynamics::test
