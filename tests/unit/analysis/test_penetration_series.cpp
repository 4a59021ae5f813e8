// Penetration-history numerics (analysis/penetration_series.hpp) against closed-form truth:
// polynomial exactness, convergence orders, noise statistics of the least-squares derivative,
// the steady-state line of a synthetic history with known U and phase boundaries, stop times of
// histories with a known end, and channel radii of synthetic target material.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <stdexcept>

#include "analysis/penetration_series.hpp"

namespace test_penetration_series {

using namespace ballista;

namespace {

/// Strictly increasing times on [0, T] with spacings drawn from [0.5, 1.5] * T / (n - 1).
std::vector<double> random_grid(int n, double T, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  std::vector<double> t(n, 0.0);
  for (int i = 1; i < n; ++i) t[i] = t[i - 1] + u(gen);
  for (double& x : t) x *= T / t.back();
  return t;
}

/// Self-similar nonuniform grid on [0, 1]: a fixed pattern of 8 spacing ratios repeated `reps`
/// times, so halving h (doubling reps) keeps the local geometry and a clean order is observable.
std::vector<double> pattern_grid(int reps) {
  const double ratio[8] = {1.0, 0.6, 1.4, 0.9, 1.2, 0.7, 1.3, 0.8};
  std::vector<double> t{0.0};
  for (int r = 0; r < reps; ++r)
    for (double q : ratio) t.push_back(t.back() + q);
  for (double& x : t) x /= t.back();
  return t;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

// ---------------------------------------------------------------- local_polynomial_derivative

// A least-squares polynomial of degree p reproduces any polynomial of degree <= p exactly, so the
// only error is rounding. The fit uses s = (t - t_i)/L in [-1, 1] (Vandermonde condition number
// O(10-100) for p <= 3, 7 points) and divides by L ~ 3 spacings; with |y| <= ~3 and 60 samples on
// [0, 1] the rounding error is ~ eps * 100 * 3 / 0.05 ~ 1e-12 at worst, so 1e-12 relative to the
// derivative's scale (|y'| ~ 5) is a bound that still catches any truncation error.
TEST(LocalPolynomialDerivative, ExactForPolynomialsUpToDegreeOnRandomGrids) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const auto t = random_grid(60, 1.0, seed);
    for (int degree = 1; degree <= 3; ++degree) {
      for (int hw : {1, 2, 3, 5}) {
        if (2 * hw + 1 <= degree) continue;
        // y = 0.3 + 1.7 t - 2.1 t^2 + 1.3 t^3 truncated to `degree`.
        const double c[4] = {0.3, 1.7, -2.1, 1.3};
        std::vector<double> y(t.size()), exact(t.size());
        for (size_t i = 0; i < t.size(); ++i) {
          double p = 1.0, dp = 0.0;
          y[i] = 0.0;
          exact[i] = 0.0;
          for (int j = 0; j <= degree; ++j) {
            y[i] += c[j] * p;
            exact[i] += j * c[j] * dp;
            dp = p;
            p *= t[i];
          }
        }
        const auto d = local_polynomial_derivative(t, y, hw, degree);
        const double scale = max_abs(exact);
        for (size_t i = 0; i < t.size(); ++i)
          ASSERT_NEAR(d[i], exact[i], 1e-12 * scale)
              << "seed " << seed << " degree " << degree << " half_window " << hw << " i " << i;
      }
    }
  }
}

// Exactness does not depend on the units or offset of t: a quadratic in time around t0 = 1e-3 s
// sampled every ~1e-7 s (a simulation's units) is differentiated to rounding.
TEST(LocalPolynomialDerivative, ExactForQuadraticInSimulationUnits) {
  auto t = random_grid(200, 2e-5, 7);
  for (double& x : t) x += 1e-3;
  std::vector<double> y(t.size()), exact(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    const double s = t[i] - 1e-3;
    y[i] = 0.01 + 1500.0 * s - 2e7 * s * s;  // m: 1.5 km/s decelerating at 4e7 m/s^2
    exact[i] = 1500.0 - 4e7 * s;
  }
  const auto d = local_polynomial_derivative(t, y);
  // Rounding of y ~ 1e-2 m at eps over L ~ 3e-7 s: ~ 1e-11 m/s; 1e-9 relative to 1.5 km/s is safe.
  for (size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(d[i], exact[i], 1e-9 * 1500.0) << i;
}

// Truncation error of a degree-p local least-squares derivative is O(h^p) (the first neglected
// Taylor term, h^(p+1) y^(p+1), divided by the step h); the shifted end windows realise it on any
// grid, so the maximum error over all samples must converge at order p. The phase 1 keeps
// y^(p+1) away from zero at both ends (sin(3t) has y''''(0) = 0, which hides the h^3 term of
// degree 3 behind h^4 terms on coarse grids).
TEST(LocalPolynomialDerivative, ConvergesAtOrderDegreeForSine) {
  for (int degree : {2, 3}) {
    std::vector<double> err;
    for (int reps : {8, 16, 32, 64, 128}) {
      const auto t = pattern_grid(reps);
      std::vector<double> y(t.size()), e(t.size());
      for (size_t i = 0; i < t.size(); ++i) y[i] = std::sin(3.0 * t[i] + 1.0);
      const auto d = local_polynomial_derivative(t, y, 3, degree);
      for (size_t i = 0; i < t.size(); ++i) e[i] = d[i] - 3.0 * std::cos(3.0 * t[i] + 1.0);
      err.push_back(max_abs(e));
    }
    for (size_t k = 1; k < err.size(); ++k) {
      const double order = std::log2(err[k - 1] / err[k]);
      std::printf("degree %d: max error %.3e -> %.3e, observed order %.3f\n", degree, err[k - 1],
                  err[k], order);
      // Asymptotic order within 0.25 (higher-order terms at the coarsest grids).
      EXPECT_NEAR(order, degree, 0.25) << "degree " << degree << ": observed order " << order
                                       << " between errors " << err[k - 1] << " and " << err[k];
    }
  }
}

// Noisy linear data y = U t + sigma xi on a uniform grid. In the interior the window is symmetric
// and the degree-2 derivative weights are the degree-1 ones, w_k = k / (dt sum k^2), k = -3..3
// (Savitzky & Golay 1964), so the estimate is unbiased with standard deviation
// sigma / (dt sqrt(28)). Assert the 5-sigma bound at every interior sample and the empirical RMS
// error within 10 % of that (1800 samples: RMS relative sampling error ~ 1/sqrt(2*1800) ~ 2 %,
// neighbouring estimates are correlated, so 10 % is a wide but meaningful margin).
TEST(LocalPolynomialDerivative, NoisyLinearGivesSlopeWithinNoiseBound) {
  const int n = 1800;
  const double dt = 1e-7, U = 1800.0, sigma = 1e-6;  // m: 1 um depth noise
  std::mt19937 gen(42);
  std::normal_distribution<double> xi(0.0, 1.0);
  std::vector<double> t(n), y(n);
  for (int i = 0; i < n; ++i) {
    t[i] = i * dt;
    y[i] = U * t[i] + sigma * xi(gen);
  }
  const auto d = local_polynomial_derivative(t, y, 3, 2);
  const double sd = sigma / (dt * std::sqrt(28.0));
  double ss = 0.0;
  for (int i = 3; i < n - 3; ++i) {
    ASSERT_LT(std::abs(d[i] - U), 5.0 * sd) << i;
    ss += (d[i] - U) * (d[i] - U);
  }
  const double rms = std::sqrt(ss / (n - 6));
  EXPECT_NEAR(rms / sd, 1.0, 0.1) << "RMS " << rms << " m/s, predicted " << sd << " m/s";
}

TEST(LocalPolynomialDerivative, ShortSeries) {
  // Fewer samples than degree + 1: NaN everywhere.
  const auto d = local_polynomial_derivative({0.0, 1.0}, {0.0, 1.0}, 3, 2);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_TRUE(std::isnan(d[0]) && std::isnan(d[1]));
  EXPECT_TRUE(local_polynomial_derivative({}, {}).empty());
  // Between degree + 1 and 2*half_window + 1 samples: all samples are used, still exact.
  const std::vector<double> t{0.0, 0.3, 1.0, 1.1};
  std::vector<double> y;
  for (double x : t) y.push_back(2.0 - x + 0.5 * x * x);
  const auto e = local_polynomial_derivative(t, y, 3, 2);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(e[i], -1.0 + t[i], 1e-13) << i;
}

TEST(LocalPolynomialDerivative, RejectsBadInput) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7}, y(8, 1.0);
  EXPECT_THROW(local_polynomial_derivative(t, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative({0, 1, 1, 2, 3}, {0, 1, 2, 3, 4}),
               std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative({0, 2, 1, 3, 4}, {0, 1, 2, 3, 4}),
               std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative({0, NAN, 2, 3}, {0, 1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative(t, y, 3, 0), std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative(t, y, 1, 3), std::invalid_argument);
  EXPECT_THROW(local_polynomial_derivative(t, y, -1, 1), std::invalid_argument);
  EXPECT_NO_THROW(local_polynomial_derivative(t, y, 1, 2));
}

// ---------------------------------------------------------------- steady_state_fit

namespace {

/// Synthetic penetration history with known phases (sample spacing dt):
///  [0, t1]:  entry transient, rate rising linearly 0 -> U (depth quadratic);
///  [t1, t2]: steady penetration at U;
///  [t2, t3]: rate falling linearly U -> 0;
///  [t3, T]:  plateau at the final depth.
struct History {
  double dt = 1e-7, U = 2000.0;
  int i1 = 20, i2 = 220, i3 = 260, n = 301;
  std::vector<double> t, depth;
  History() {
    const double t1 = i1 * dt, t2 = i2 * dt, t3 = i3 * dt;
    const double d1 = 0.5 * U * t1, d2 = d1 + U * (t2 - t1), d3 = d2 + 0.5 * U * (t3 - t2);
    for (int i = 0; i < n; ++i) {
      const double s = i * dt;
      t.push_back(s);
      if (s <= t1)
        depth.push_back(0.5 * U * s * s / t1);
      else if (s <= t2)
        depth.push_back(d1 + U * (s - t1));
      else if (s <= t3)
        depth.push_back(d2 + U * (s - t2) - 0.5 * U * (s - t2) * (s - t2) / (t3 - t2));
      else
        depth.push_back(d3);
    }
  }
};

}  // namespace

// The run may extend into the transients only where their rate is within the tolerance of U:
// tol * (t1/dt) = 2 samples of the ramp and tol * ((t3 - t2)/dt) = 4 samples of the deceleration,
// plus ~1 sample for the shift of the mean and the derivative's smoothing of the kinks. Those few
// samples deviate from the line by at most ~0.1 U dt, so U is recovered far better than 1 %.
TEST(SteadyStateFit, RecoversRateAndIntervalOfSyntheticHistory) {
  const History h;
  const auto rate = local_polynomial_derivative(h.t, h.depth);
  const auto fit = steady_state_fit(h.t, h.depth, rate);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.slope, h.U, 0.01 * h.U);
  EXPECT_LE(std::abs(fit.first - h.i1), 3) << "first " << fit.first;
  EXPECT_LE(std::abs(fit.last - h.i2), 5) << "last " << fit.last;
  EXPECT_DOUBLE_EQ(fit.t_begin, h.t[fit.first]);
  EXPECT_DOUBLE_EQ(fit.t_end, h.t[fit.last]);
  EXPECT_EQ(fit.points, fit.last - fit.first + 1);
  EXPECT_GT(fit.r2, 0.999);
  // The line is the steady one: depth(t) = d1 + U (t - t1) gives intercept d1 - U t1 = -U t1 / 2.
  EXPECT_NEAR(fit.intercept, -0.5 * h.U * h.i1 * h.dt, 0.01 * h.U * h.i1 * h.dt);
  // Printed for the report: slope error and boundaries.
  std::printf("steady fit: U error %.3e relative, first %d (steady from %d), last %d (to %d)\n",
              fit.slope / h.U - 1.0, fit.first, h.i1, fit.last, h.i2);
}

// Same history with 0.2 um depth noise (rate noise ~ 0.2e-6/(1e-7 sqrt 28) ~ 380 m/s per sample
// would break a 10 % band, so use the derivative over a wider window, half_window 10:
// sd = 0.2e-6 / (1e-7 sqrt(770)) ~ 72 m/s, 3.6 % of U). The line fit averages the noise: U within 1
// %.
TEST(SteadyStateFit, NoisyHistoryStillGivesU) {
  History h;
  std::mt19937 gen(3);
  std::normal_distribution<double> xi(0.0, 0.2e-6);
  for (double& d : h.depth) d += xi(gen);
  const auto rate = local_polynomial_derivative(h.t, h.depth, 10, 2);
  const auto fit = steady_state_fit(h.t, h.depth, rate, 0.15);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.slope, h.U, 0.01 * h.U);
  EXPECT_GT(fit.points, 150) << "the steady part has 200 samples";
  EXPECT_GT(fit.r2, 0.999);
}

// Monotone deceleration, depth = D (1 - exp(-t/tau)): no steady part. Decision: the function still
// returns the longest run within the tolerance (ok), and its duration is set by the tolerance
// alone. For rate r(s) = r_a exp(-s/tau) on [a, a + L], with x = L/tau, the mean is
// r_a (1 - e^-x)/x, so the band conditions are x/(1 - e^-x) <= 1 + tol and
// x e^-x/(1 - e^-x) >= 1 - tol; the largest such x (bisection below) gives the run length.
TEST(SteadyStateFit, DeceleratingHistoryGivesOnlyTheToleranceLimitedRun) {
  const double tau = 5e-6, D = 0.05, dt = tau / 500.0, tol = 0.1;
  std::vector<double> t, depth;
  for (int i = 0; i <= 2500; ++i) {
    t.push_back(i * dt);
    depth.push_back(D * (1.0 - std::exp(-t.back() / tau)));
  }
  const auto rate = local_polynomial_derivative(t, depth);
  const auto fit = steady_state_fit(t, depth, rate, tol);
  auto qualifies = [&](double x) {
    const double m = (1.0 - std::exp(-x)) / x;  // mean / max
    return 1.0 <= (1.0 + tol) * m && std::exp(-x) >= (1.0 - tol) * m;
  };
  double lo = 1e-6, hi = 2.0;
  for (int k = 0; k < 100; ++k) (qualifies(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  const double expected_points = lo * tau / dt + 1.0;  // ~ 97.8
  ASSERT_TRUE(fit.ok);
  std::printf("decelerating history: run of %d points, tolerance-limited length %.2f points\n",
              fit.points, expected_points);
  // Discrete mean vs continuous mean differ by O(dt^2/tau^2): within 2 samples.
  EXPECT_NEAR(fit.points, expected_points, 2.0);
  EXPECT_LT(fit.t_end - fit.t_begin, 0.1 * (t.back() - t.front()))
      << "a decelerating history must not produce a long 'steady' interval";
  // Asking for a longer run than the tolerance allows: no steady interval.
  EXPECT_FALSE(steady_state_fit(t, depth, rate, tol, static_cast<int>(expected_points) + 5).ok);
}

// Exhaustive search is exact where a two-pointer sweep is not: rates chosen so that the full run
// qualifies although its prefix [1.1, 0.92, 0.92, 0.92] does not (mean 0.965; 1.1 > 1.1 * 0.965).
TEST(SteadyStateFit, FindsRunWhoseSubRunsFail) {
  std::vector<double> rate{1.1, 0.92, 0.92, 0.92};
  for (int k = 0; k < 30; ++k) rate.push_back(1.02);
  rate.push_back(-1.0);  // not penetrating: ends every run
  rate.push_back(1.0);
  std::vector<double> t(rate.size()), depth(rate.size(), 0.0);
  std::iota(t.begin(), t.end(), 0.0);
  for (size_t i = 1; i < t.size(); ++i) depth[i] = depth[i - 1] + rate[i];
  const auto fit = steady_state_fit(t, depth, rate, 0.1, 5);
  ASSERT_TRUE(fit.ok);
  EXPECT_EQ(fit.first, 0);
  EXPECT_EQ(fit.last, 33);
}

TEST(SteadyStateFit, NoPositiveRateMeansNoFit) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6}, depth(7, 0.0), rate(7, 0.0);
  EXPECT_FALSE(steady_state_fit(t, depth, rate).ok);
  std::vector<double> nan_rate(7, NAN);
  EXPECT_FALSE(steady_state_fit(t, depth, nan_rate).ok);
  EXPECT_FALSE(steady_state_fit({}, {}, {}).ok);
}

TEST(SteadyStateFit, RejectsBadInput) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5}, d{0, 1, 2, 3, 4, 5}, r(6, 1.0);
  EXPECT_THROW(steady_state_fit(t, {0, 1}, r), std::invalid_argument);
  EXPECT_THROW(steady_state_fit(t, d, {1, 1}), std::invalid_argument);
  EXPECT_THROW(steady_state_fit({0, 1, 1, 2, 3, 4}, d, r), std::invalid_argument);
  EXPECT_THROW(steady_state_fit(t, d, r, 0.0), std::invalid_argument);
  EXPECT_THROW(steady_state_fit(t, d, r, 1.0), std::invalid_argument);
  EXPECT_THROW(steady_state_fit(t, d, r, 0.1, 1), std::invalid_argument);
  const auto fit = steady_state_fit(t, d, r, 0.1, 2);
  ASSERT_TRUE(fit.ok);
  EXPECT_DOUBLE_EQ(fit.slope, 1.0);
  EXPECT_DOUBLE_EQ(fit.r2, 1.0);
}

// ---------------------------------------------------------------- penetration_stop_time

// depth = U t until ts = 123.4 dt, constant after: the first sample at rest is 124 dt, one sample
// after the true stop (the samples before it still rise by >= 0.4 U dt > tolerance).
TEST(PenetrationStopTime, AbruptStopWithinOneSample) {
  const double dt = 1e-7, U = 1500.0, ts = 123.4 * dt;
  std::vector<double> t, depth;
  for (int i = 0; i <= 300; ++i) {
    t.push_back(i * dt);
    depth.push_back(U * std::min(t.back(), ts));
  }
  const double stop = penetration_stop_time(t, depth, 0.01 * U * dt, 50 * dt);
  ASSERT_FALSE(std::isnan(stop));
  EXPECT_GE(stop, ts);
  EXPECT_LE(stop - ts, dt);
  // Not held long enough before the end: not stopped.
  EXPECT_TRUE(std::isnan(penetration_stop_time(t, depth, 0.01 * U * dt, 200 * dt)));
}

// Smooth stop depth = D (1 - (1 - t/ts)^2) for t < ts, D after: the remaining rise from t is
// D (1 - t/ts)^2, below tol once t > ts (1 - sqrt(tol/D)); the answer is the first sample past it.
TEST(PenetrationStopTime, SmoothStopMatchesClosedForm) {
  const double ts = 4e-5, D = 0.08, tol = 1e-4;
  std::vector<double> t, depth;
  const int n = 1000;
  const double dt = 2.0 * ts / n;
  for (int i = 0; i <= n; ++i) {
    t.push_back(i * dt);
    const double x = std::min(t.back() / ts, 1.0);
    depth.push_back(D * (1.0 - (1.0 - x) * (1.0 - x)));
  }
  const double expected = ts * (1.0 - std::sqrt(tol / D));
  const double stop = penetration_stop_time(t, depth, tol, 0.0);
  EXPECT_GE(stop, expected);
  EXPECT_LE(stop - expected, dt);
}

TEST(PenetrationStopTime, StillPenetratingIsNaN) {
  std::vector<double> t, depth;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 1e-7);
    depth.push_back(1000.0 * t.back() - 2e6 * t.back() * t.back());  // rate 1000 -> 960 m/s
  }
  EXPECT_TRUE(std::isnan(penetration_stop_time(t, depth, 1e-6, 1e-6)));
  EXPECT_TRUE(std::isnan(penetration_stop_time({}, {}, 1e-6, 0.0)));
  // Rebound (depth decreasing at the end) counts as stopped: depth never rises by tol again.
  std::vector<double> d2{0.0, 1.0, 2.0, 2.0, 1.9, 1.8};
  EXPECT_DOUBLE_EQ(penetration_stop_time({0, 1, 2, 3, 4, 5}, d2, 0.01, 1.0), 2.0);
}

TEST(PenetrationStopTime, RejectsBadInput) {
  EXPECT_THROW(penetration_stop_time({0, 1}, {0}, 1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(penetration_stop_time({0, 0}, {0, 0}, 1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(penetration_stop_time({0, 1}, {0, 0}, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(penetration_stop_time({0, 1}, {0, 0}, 1e-3, -1.0), std::invalid_argument);
}

// ---------------------------------------------------------------- channel_profile

// Target material occupies r in [R(z), R(z) + W] with R = 3 mm for z < 20 mm, 2 mm beyond, and no
// material at all for z in [30, 35) mm (a void). 20000 points uniform in (z, r) over the material:
// each 5 mm bin holds ~2800 points, and the smallest r - R(z) among them exceeds 0.01 W with
// probability 0.99^2800 ~ 6e-13; the seed is fixed anyway. Bin edges are aligned with the step.
TEST(ChannelProfile, RecoversSteppedChannelAndVoid) {
  const double W = 5e-3, max_depth = 40e-3;
  auto R = [](double z) { return z < 20e-3 ? 3e-3 : 2e-3; };
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uz(0.0, max_depth), ur(0.0, W);
  std::vector<double> depth, radius;
  while (depth.size() < 20000) {
    const double z = uz(gen);
    if (z >= 30e-3 && z < 35e-3) continue;
    depth.push_back(z);
    radius.push_back(R(z) + ur(gen));
  }
  // Points outside [0, max_depth] are ignored (they would otherwise set a 0 radius).
  depth.push_back(-1e-3);
  radius.push_back(0.0);
  depth.push_back(50e-3);
  radius.push_back(0.0);
  const auto p = channel_profile(depth, radius, max_depth, 8);
  ASSERT_EQ(p.depth.size(), 8u);
  ASSERT_EQ(p.radius.size(), 8u);
  for (int k = 0; k < 8; ++k) {
    EXPECT_DOUBLE_EQ(p.depth[k], (k + 0.5) * 5e-3);
    if (k == 6) {
      EXPECT_TRUE(std::isnan(p.radius[k])) << "bin [30, 35) mm has no material";
      continue;
    }
    const double Rk = R(p.depth[k]);
    EXPECT_GE(p.radius[k], Rk) << k;
    EXPECT_LE(p.radius[k], Rk + 0.01 * W) << k;
  }
}

TEST(ChannelProfile, EdgesAndBadInput) {
  // depth == max_depth goes to the last bin, depth 0 to the first.
  const auto p = channel_profile({0.0, 1.0, 0.5}, {0.1, 0.2, 0.3}, 1.0, 2);
  EXPECT_DOUBLE_EQ(p.radius[0], 0.1);
  EXPECT_DOUBLE_EQ(p.radius[1], 0.2);
  EXPECT_THROW(channel_profile({0.1}, {}, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(channel_profile({0.1}, {0.1}, 0.0, 2), std::invalid_argument);
  EXPECT_THROW(channel_profile({0.1}, {0.1}, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(channel_profile({0.1}, {-0.1}, 1.0, 2), std::invalid_argument);
}

}  // namespace test_penetration_series
