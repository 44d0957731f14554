#include "dynamics/steppers/bdf_integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace vcontact::dynamics {
namespace {

// CVODE's return value of a right-hand side: 0 fine, > 0 recoverable (retry with a shorter
// step), < 0 unrecoverable.
constexpr int kRhsOk = 0, kRhsRecoverable = 1, kRhsUnrecoverable = -1;

// BDF1 and BDF2 are A-stable; BDF3–5 are unstable in a sector around the imaginary axis. A hard
// contact's normal vibration is barely damped (ζ ≈ 1e-3 for a steel ball with a = 1 s/m), so at
// higher orders the integrator feeds it from its own local errors and then has to resolve it:
// ball_roll took 9,038 steps a second at orders up to 5, 19,366 at 3, 1,255 at 2 (measured,
// CVODE's stability-limit detection on).
constexpr int kMaxOrder = 2;

// The error norm of CVODE's error and convergence tests: max_i |x_i w_i| with the error weights
// w_i = 1/(abs + rel |y_i|), in place of the weighted RMS norm. The local error is then bounded
// in every component, as by odeint's controller and as docs/SCENARIO.md states, instead of
// on average over the states (one component could take √n times its tolerance).
realtype maxNorm(N_Vector x, N_Vector w) {
  const realtype* xd = N_VGetArrayPointer(x);
  const realtype* wd = N_VGetArrayPointer(w);
  const sunindextype n = N_VGetLength(x);
  realtype norm = 0.0;
  for (sunindextype i = 0; i < n; ++i) norm = std::max(norm, std::abs(xd[i] * wd[i]));
  return norm;
}

// The dense direct solver of the Newton iteration, M = I − γJ, by Eigen's partial-pivoting LU
// on SUNDIALS' column-major dense matrix. It replaces SUNLinSol_Dense, whose triangular solves
// took a quarter of ball_roll's instructions (9,000 per 18-state solve, measured by callgrind).
struct EigenLu {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;

  static EigenLu& of(SUNLinearSolver S) { return *static_cast<EigenLu*>(S->content); }
  static SUNLinearSolver_Type type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
  static int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }
  static int setup(SUNLinearSolver S, SUNMatrix A) {
    const auto n = static_cast<Eigen::Index>(SM_COLUMNS_D(A));
    of(S).lu.compute(Eigen::Map<const Eigen::MatrixXd>(SM_DATA_D(A), n, n));
    // A singular M leaves a zero pivot: CVODE treats a positive flag as recoverable and retries
    // with a shorter step, which makes M closer to I.
    const Eigen::VectorXd pivots = of(S).lu.matrixLU().diagonal();
    return pivots.cwiseAbs().minCoeff() > 0.0 ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
  }
  static int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    const auto n = static_cast<Eigen::Index>(N_VGetLength(b));
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(x), n) =
        of(S).lu.solve(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), n));
    return SUNLS_SUCCESS;
  }
  static int free(SUNLinearSolver S) {
    if (S == nullptr) return SUNLS_SUCCESS;
    delete static_cast<EigenLu*>(S->content);
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return SUNLS_SUCCESS;
  }
};

SUNLinearSolver makeEigenLu(SUNContext context) {
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  if (S == nullptr) return nullptr;
  S->content = new EigenLu;
  S->ops->gettype = &EigenLu::type;
  S->ops->initialize = &EigenLu::initialize;
  S->ops->setup = &EigenLu::setup;
  S->ops->solve = &EigenLu::solve;
  S->ops->free = &EigenLu::free;
  return S;
}

// Throws std::runtime_error when a SUNDIALS set-up call fails (an internal error: every input
// has been checked by the scenario reader).
void require(int flag, const char* call) {
  if (flag >= 0) return;
  std::ostringstream s;
  s << "CVODE: " << call << " failed with flag " << flag;
  throw std::runtime_error(s.str());
}

template <typename T>
T* require(T* p, const char* call) {
  if (p == nullptr) throw std::runtime_error(std::string("CVODE: ") + call + " failed");
  return p;
}

std::string describe(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_ACC:
      return "the tolerances are below what double precision can reach";
    case CV_ERR_FAILURE:
      return "the local error test failed repeatedly";
    case CV_CONV_FAILURE:
      return "the Newton iteration failed to converge repeatedly";
    case CV_LSETUP_FAIL:
      return "the Jacobian or its LU factorisation failed";
    case CV_LSOLVE_FAIL:
      return "the linear solve failed";
    case CV_FIRST_RHSFUNC_ERR:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_RHSFUNC_FAIL:
      return "the derivative was repeatedly not finite";
    default: {
      std::ostringstream s;
      s << "CVODE failed with flag " << flag;
      return s.str();
    }
  }
}

}  // namespace

struct BdfIntegrator::Impl {
  Rhs f;
  Settings settings;
  std::size_t n = 0;
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver solver = nullptr;
  void* cvode = nullptr;
  std::exception_ptr pending;  // thrown by f inside CVODE, rethrown by step()
  Counts before_restart;       // CVodeReInit zeroes CVODE's counters

  static int rhs(realtype t, N_Vector x, N_Vector dxdt, void* user) {
    auto* self = static_cast<Impl*>(user);
    try {
      return self->f(t, N_VGetArrayPointer(x), N_VGetArrayPointer(dxdt)) ? kRhsOk : kRhsRecoverable;
    } catch (...) {
      self->pending = std::current_exception();
      return kRhsUnrecoverable;
    }
  }

  // CVODE's own messages are replaced by BdfError (errors) or dropped (warnings such as
  // "t + h = t", which the step-size check reports in its own words).
  static void silence(int, const char*, const char*, char*, void*) {}

  void configure() {
    require(CVodeSStolerances(cvode, settings.rel_tol, settings.abs_tol), "CVodeSStolerances");
    require(CVodeSetUserData(cvode, this), "CVodeSetUserData");
    require(CVodeSetErrHandlerFn(cvode, &Impl::silence, nullptr), "CVodeSetErrHandlerFn");
    require(CVodeSetMaxStep(cvode, settings.max_step), "CVodeSetMaxStep");
    require(CVodeSetMinStep(cvode, settings.min_step), "CVodeSetMinStep");
    require(CVodeSetStopTime(cvode, settings.t_stop), "CVodeSetStopTime");
    // Orders 3–5 are unstable near the imaginary axis; an undamped contact oscillation that the
    // step does not resolve would grow. Stability-limit detection lowers the order there.
    require(CVodeSetStabLimDet(cvode, SUNTRUE), "CVodeSetStabLimDet");
    require(CVodeSetMaxOrd(cvode, kMaxOrder), "CVodeSetMaxOrd");
  }

  Counts current() const {
    long steps = 0, etf = 0, ncf = 0, nje = 0, nfeLS = 0;
    CVodeGetNumSteps(cvode, &steps);
    CVodeGetNumErrTestFails(cvode, &etf);
    CVodeGetNumNonlinSolvConvFails(cvode, &ncf);
    CVodeGetNumJacEvals(cvode, &nje);
    CVodeGetNumLinRhsEvals(cvode, &nfeLS);
    Counts c = before_restart;
    c.steps += steps;
    c.rejected += etf + ncf;
    c.jacobians += nje;
    c.jacobian_rhs += nfeLS;
    return c;
  }

  ~Impl() {
    if (cvode != nullptr) CVodeFree(&cvode);
    if (solver != nullptr) SUNLinSolFree(solver);
    if (A != nullptr) SUNMatDestroy(A);
    if (y != nullptr) N_VDestroy(y);
    if (context != nullptr) SUNContext_Free(&context);
  }
};

BdfIntegrator::BdfIntegrator(std::size_t n, Rhs f, const Settings& settings, double t0,
                             const double* x0)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.f = std::move(f);
  m.settings = settings;
  m.n = n;
  const auto len = static_cast<sunindextype>(n);
  require(SUNContext_Create(nullptr, &m.context), "SUNContext_Create");
  m.y = require(N_VNew_Serial(len, m.context), "N_VNew_Serial");
  m.y->ops->nvwrmsnorm = &maxNorm;  // inherited by every vector CVODE clones from y
  // One call per linear combination of the Nordsieck history instead of one per term.
  require(N_VEnableFusedOps_Serial(m.y, SUNTRUE), "N_VEnableFusedOps_Serial");
  std::copy(x0, x0 + n, N_VGetArrayPointer(m.y));
  m.A = require(SUNDenseMatrix(len, len, m.context), "SUNDenseMatrix");
  m.solver = require(makeEigenLu(m.context), "makeEigenLu");
  m.cvode = require(CVodeCreate(CV_BDF, m.context), "CVodeCreate");
  require(CVodeInit(m.cvode, &Impl::rhs, t0, m.y), "CVodeInit");
  // No Jacobian function: CVODE forms it by difference quotients, one column per state.
  require(CVodeSetLinearSolver(m.cvode, m.solver, m.A), "CVodeSetLinearSolver");
  require(CVodeSetInitStep(m.cvode, settings.initial_step), "CVodeSetInitStep");
  m.configure();
}

BdfIntegrator::~BdfIntegrator() = default;

double BdfIntegrator::step() {
  Impl& m = *impl_;
  double t = 0.0;
  const int flag = CVode(m.cvode, m.settings.t_stop, m.y, &t, CV_ONE_STEP);
  if (m.pending) std::rethrow_exception(std::exchange(m.pending, nullptr));
  if (flag >= 0) return t;
  double t_now = t, h = 0.0;
  CVodeGetCurrentTime(m.cvode, &t_now);
  CVodeGetCurrentStep(m.cvode, &h);
  // CVODE clamps h at min_step and then fails the step: a collapse, whatever the test failing.
  const bool collapse = std::abs(h) <= m.settings.min_step * (1.0 + 1e-9) &&
                        (flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE);
  const bool rhs_failed =
      flag == CV_FIRST_RHSFUNC_ERR || flag == CV_REPTD_RHSFUNC_ERR || flag == CV_RHSFUNC_FAIL;
  throw BdfError(t_now, h, collapse, rhs_failed, describe(flag));
}

const double* BdfIntegrator::state() const { return N_VGetArrayPointer(impl_->y); }

void BdfIntegrator::interpolate(double t, double* x) const {
  Impl& m = *impl_;
  N_Vector out = N_VMake_Serial(static_cast<sunindextype>(m.n), x, m.context);
  const int flag = CVodeGetDky(m.cvode, t, 0, out);
  N_VDestroy(out);
  require(flag, "CVodeGetDky");
}

void BdfIntegrator::restart(double t, const double* x) {
  Impl& m = *impl_;
  double h = 0.0;
  CVodeGetLastStep(m.cvode, &h);
  m.before_restart = m.current();
  std::copy(x, x + m.n, N_VGetArrayPointer(m.y));
  require(CVodeReInit(m.cvode, t, m.y), "CVodeReInit");
  if (h > 0.0) require(CVodeSetInitStep(m.cvode, h), "CVodeSetInitStep");
  m.configure();
}

BdfIntegrator::Counts BdfIntegrator::counts() const { return impl_->current(); }

}  // namespace vcontact::dynamics
