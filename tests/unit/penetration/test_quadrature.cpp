// Adaptive Simpson quadrature (penetration/quadrature.hpp): accuracy on a known integral, and the
// guards added after issue 11 (a NaN tolerance or integrand made it recurse 2^50 times).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "penetration/quadrature.hpp"

namespace test_quadrature {

namespace bp = ballista::penetration;

TEST(Quadrature, IntegratesExpToTolerance) {
  // int_0^1 e^x dx = e - 1; Simpson's error is O(h^4), the adaptive rule meets the requested
  // absolute tolerance (1e-12) with Richardson's correction to spare.
  const double v = bp::integrate_adaptive_simpson([](double x) { return std::exp(x); }, 0.0, 1.0, 1e-12);
  EXPECT_NEAR(v, std::exp(1.0) - 1.0, 1e-12);
}

TEST(Quadrature, NonFiniteIntegrandIsAnError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(bp::integrate_adaptive_simpson([&](double x) { return x < 0.3 ? 1.0 : nan; }, 0.0, 1.0, 1e-10),
               ballista::Error);
  EXPECT_THROW(bp::integrate_adaptive_simpson([](double x) { return 1.0 / x; }, 0.0, 1.0, 1e-10), ballista::Error);
}

TEST(Quadrature, NonFiniteToleranceIsAnError) {
  EXPECT_THROW(bp::integrate_adaptive_simpson([](double x) { return x; }, 0.0, 1.0, std::nan("")), ballista::Error);
  EXPECT_THROW(bp::integrate_adaptive_simpson([](double x) { return x; }, 0.0, std::numeric_limits<double>::infinity(),
                                              1e-10),
               ballista::Error);
}

TEST(Quadrature, EvaluationBudgetStopsAnUnreachableTolerance) {
  // sqrt(x) has an infinite derivative at 0; a zero tolerance can never be met, so the budget
  // (here 1000 evaluations) must end the recursion with an error instead of 2^50 intervals.
  EXPECT_THROW(bp::integrate_adaptive_simpson([](double x) { return std::sqrt(x); }, 0.0, 1.0, 0.0, 1000),
               ballista::Error);
}

}  // namespace test_quadrature
