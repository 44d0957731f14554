// The friction map as a library call (validation/friction_map.hpp): the sweep it runs, the
// closed form it carries for the punch, and errors that name quantities, not command options.

#include "validation/friction_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/error.hpp"

namespace vcontact::validation {
namespace {

/// The source of the InputError frictionMap throws for `options`, or "" when it throws none.
std::string errorSource(const FrictionMapOptions& options) {
  try {
    frictionMap(options);
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    return e.source();
  }
  return "";
}

TEST(FrictionMap, PunchSweepRunsFromPureSpinToPureSlidingWithTheClosedForm) {
  FrictionMapOptions o;
  o.eps_min = 0.1;
  o.eps_max = 10.0;
  o.per_decade = 1;
  const FrictionMap map = frictionMap(o);
  // ε = 0, then 0.1, 1, 10, then ε = ∞.
  ASSERT_EQ(map.rows.size(), 5u);
  EXPECT_EQ(map.rows.front().eps, 0.0);
  EXPECT_TRUE(std::isinf(map.rows.back().eps));
  EXPECT_EQ(map.R, o.radius);
  // f_n = kv V: the punch is pressed to carry the load, within the 512-gon's area (2.5e-5)
  // and the column grid's volume error (1e-3).
  EXPECT_NEAR(map.f_n / o.load, 1.0, 2e-3);
  for (const FrictionMapRow& r : map.rows) {
    ASSERT_TRUE(r.exact.has_value()) << r.eps;
    EXPECT_EQ(r.exact->force, flatPunchFriction(r.eps).force) << r.eps;
    EXPECT_EQ(r.exact->torque, flatPunchFriction(r.eps).torque) << r.eps;
  }
}

TEST(FrictionMap, ErrorsNameTheQuantity) {
  FrictionMapOptions o;
  o.radius = -1.0;
  EXPECT_EQ(errorSource(o), "radius");
  o = {};
  o.eps_min = 10.0;
  o.eps_max = 1.0;
  EXPECT_EQ(errorSource(o), "epsilon range");
  o = {};
  o.shape = geometry::HalfSpace{};
  EXPECT_EQ(errorSource(o), "shape");
}

}  // namespace
}  // namespace vcontact::validation
