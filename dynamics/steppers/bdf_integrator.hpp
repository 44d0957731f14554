#pragma once
// Variable-order BDF for stiff contact: SUNDIALS CVODE (orders 1–2 here, see kMaxOrder in the
// .cpp; Newton iteration with a dense direct solver and a difference-quotient Jacobian,
// Hindmarsh et al., ACM TOMS 31, 2005), driven one step at a time with dense output. SUNDIALS
// types stay in bdf_integrator.cpp.
//
//   BdfIntegrator bdf(n, f, settings, t0, x0);
//   double t = bdf.step();          // one accepted step; throws BdfError when CVODE gives up
//   bdf.interpolate(t_out, x_out);  // the step's interpolating polynomial, t_out in the step
//   bdf.restart(t, x);              // after a discrete jump of the state (order 1 again)

#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace vcontact::dynamics {

/// CVODE stopped: `reason` says why in words, `step_collapse` when the step size reached the
/// minimum.
class BdfError : public std::runtime_error {
 public:
  BdfError(double t, double h, bool step_collapse, bool rhs_failed, const std::string& reason)
      : std::runtime_error(reason),
        t_(t),
        h_(h),
        step_collapse_(step_collapse),
        rhs_failed_(rhs_failed) {}
  double time() const { return t_; }      ///< s, the last time reached
  double stepSize() const { return h_; }  ///< s, the step size being tried
  bool stepCollapse() const { return step_collapse_; }
  bool rhsFailed() const { return rhs_failed_; }  ///< the derivative was repeatedly not finite

 private:
  double t_, h_;
  bool step_collapse_, rhs_failed_;
};

class BdfIntegrator {
 public:
  /// ẋ = f(t, x) into dxdt; returns false when the derivative is not finite (CVODE retries
  /// with a shorter step). Exceptions thrown by f are rethrown by step().
  using Rhs = std::function<bool(double t, const double* x, double* dxdt)>;

  struct Settings {
    double abs_tol = 1e-9;  ///< |local error_i| ≤ abs_tol + rel_tol |x_i|
    double rel_tol = 1e-6;
    double initial_step = 1e-6;  ///< s
    double max_step = 1e-3;      ///< s
    double min_step = 1e-13;     ///< s
    double t_stop = 1.0;         ///< s; no step goes past it
  };

  struct Counts {
    long steps = 0;
    long rejected = 0;      ///< error-test and Newton-convergence failures
    long jacobians = 0;     ///< difference-quotient Jacobians formed
    long jacobian_rhs = 0;  ///< right-hand-side evaluations spent on them
  };

  BdfIntegrator(std::size_t n, Rhs f, const Settings& settings, double t0, const double* x0);
  ~BdfIntegrator();
  BdfIntegrator(const BdfIntegrator&) = delete;
  BdfIntegrator& operator=(const BdfIntegrator&) = delete;

  /// Takes one accepted step and returns the time reached (≤ t_stop).
  /// @throws BdfError when CVODE fails; whatever f threw
  double step();
  /// The state at the time step() returned.
  const double* state() const;
  /// The state at t from the last step's interpolating polynomial; t in [t − h_last, t].
  void interpolate(double t, double* x) const;
  /// Restarts at (t, x) after a discrete change of the state; the first step tries the last
  /// step size.
  void restart(double t, const double* x);
  Counts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vcontact::dynamics
