// The safeguarded Newton iteration of the radial return (j2_solve_increment, j2_return.hpp),
// called directly on scalar consistency equations q_tr - c Delta - sigma_y(Delta) = 0 whose roots
// are known independently (closed form, or bisection in long double), with the number of flow
// evaluations counted.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <functional>

#include "materials/j2_return.hpp"

namespace test_j2_return {

using namespace ballista;

namespace {

struct Counted {
  std::function<FlowStress(double)> f;
  mutable int calls = 0;
  FlowStress operator()(double d) const {
    ++calls;
    return f(d);
  }
};

/// Root of q - c x - value(x) by bisection in long double (the reference).
long double reference_root(double q, double c, const std::function<FlowStress(double)>& f, double hi) {
  long double lo = 0.0L, h = hi;
  for (int it = 0; it < 2000; ++it) {
    const long double mid = 0.5L * (lo + h);
    if (mid == lo || mid == h) break;
    (q - c * mid - f(static_cast<double>(mid)).value > 0 ? lo : h) = mid;
  }
  return 0.5L * (lo + h);
}

constexpr double kC = 3 * 80e9;  // 3G

}  // namespace

// Linear hardening: Newton is exact after one step from the upper bracket end (two evaluations).
TEST(J2Return, LinearHardeningOneNewtonStep) {
  const double sy0 = 300e6, H = 2e9, q = 500e6;
  Counted f{[&](double d) { return FlowStress{sy0 + H * d, H}; }};
  double slope = 0;
  const double x = j2_solve_increment(q, q - sy0, kC, f, slope);
  EXPECT_NEAR(x, (q - sy0) / (kC + H), 1e-15 * x);
  EXPECT_EQ(slope, H);
  EXPECT_LE(f.calls, 3);
}

// Perfect plasticity: the upper end f/c is the root (one evaluation).
TEST(J2Return, PerfectPlasticityIsTheUpperEnd) {
  Counted f{[](double) { return FlowStress{300e6, 0.0}; }};
  double slope = -1;
  EXPECT_EQ(j2_solve_increment(400e6, 100e6, kC, f, slope), 100e6 / kC);
  EXPECT_EQ(f.calls, 1);
  EXPECT_EQ(slope, 0.0);
}

// Nonlinear laws: the result equals the long-double root to 1e-12 relative (or to the conditioning
// limit of double precision, see below), within a handful of
// evaluations for smooth laws (Newton is quadratic; measured 2-5) and a few dozen for the power law
// with a root 100 decades below the bracket (geometric bisection first, then monotone Newton from
// the left; measured 36).
TEST(J2Return, NonlinearLawsConverge) {
  struct Case {
    const char* name;
    double q, sy_n;
    std::function<FlowStress(double)> f;
    int max_calls;
  };
  const double e0 = 0.02;
  const Case cases[] = {
      {"voce", 900e6, 300e6 + 200e6 * (1 - std::exp(-20 * e0)),
       [=](double d) {
         const double e = e0 + d;
         return FlowStress{300e6 + 200e6 * (1 - std::exp(-20 * e)), 200e6 * 20 * std::exp(-20 * e)};
       },
       5},
      {"power n=0.3 from 0", 700e6, 300e6,
       [](double d) { return FlowStress{300e6 + 500e6 * std::pow(d, 0.3), 150e6 * std::pow(d, -0.7)}; }, 8},
      {"power n=0.1 from 0, tiny overshoot", 300e6 + 1e-2, 300e6,
       [](double d) { return FlowStress{300e6 + 800e6 * std::pow(d, 0.1), 80e6 * std::pow(d, -0.9)}; }, 50},
      {"power n=3", 2e9, 300e6,
       [](double d) { return FlowStress{300e6 + 5e9 * d * d * d, 15e9 * d * d}; }, 5},
      {"rate log term (JC-like), kink at d = 1e-9", 800e6, 300e6,
       [](double d) {
         const double x = d / 1e-9;  // dt eps_dot_0 = 1e-9
         const double R = x > 1 ? 1 + 0.05 * std::log(x) : 1.0, dR = x > 1 ? 0.05 / d : 0.0;
         return FlowStress{300e6 * R, 300e6 * dR};
       },
       8},
  };
  for (const Case& c : cases) {
    Counted f{c.f};
    double slope = 0;
    const double x = j2_solve_increment(c.q, c.q - c.sy_n, kC, f, slope);
    const long double ref = reference_root(c.q, kC, c.f, (c.q - c.sy_n) / kC);
    // 1e-12 relative, or the conditioning limit where that is not representable: the residual is
    // known to round-off of q only (~eps q), which fixes x to eps q/(c + slope) (the tiny-overshoot
    // case: f_tr = 0.01 Pa against q = 3e8 Pa leaves x ~1e-110 determined to ~1e-4 relative, while
    // the stress itself is on the surface to round-off).
    const double cond = 16 * DBL_EPSILON * c.q / (kC + c.f(x).slope);
    EXPECT_NEAR(x, static_cast<double>(ref), 1e-12 * static_cast<double>(ref) + cond) << c.name;
    EXPECT_LE(f.calls, c.max_calls) << c.name;
    EXPECT_NEAR(slope, c.f(x).slope, 1e-9 * std::abs(c.f(x).slope)) << c.name;  // slope at the solution
    // Residual: round-off of q plus what a 1e-12 relative error in x can leave.
    EXPECT_LE(std::abs(c.q - kC * x - c.f(x).value), 1e-15 * c.q + 1e-12 * x * (kC + c.f(x).slope)) << c.name;
  }
}

}  // namespace test_j2_return
