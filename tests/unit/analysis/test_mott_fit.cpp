// Mott fit of fragment masses (analysis/mott_fit.hpp) against truth: samples drawn from a Mott
// distribution of known mu (sqrt(m/mu) ~ Exp(1)) recover mu within the estimator's sampling error,
// that sampling error itself, a closed-form case lying exactly on a Mott line, ties, and the
// refusal of fewer than three fragments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <vector>

#include "analysis/mott_fit.hpp"

namespace test_mott_fit {

using namespace ballista;

namespace {

/// n masses with sqrt(m / mu) ~ Exp(1) (P(M > m) = exp(-sqrt(m / mu)), the Mott law). The
/// exponential variate is built from mt19937_64 by inversion, -ln(1 - u), so the sample is the
/// same with every standard library (std::exponential_distribution is not specified bit for bit).
std::vector<double> mott_sample(int n, double mu, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::vector<double> m(n);
  for (double& v : m) {
    const double u = static_cast<double>(gen() >> 11) * 0x1.0p-53;  // [0, 1)
    const double e = -std::log1p(-u);
    v = mu * e * e;
  }
  return m;
}

}  // namespace

// 10,000 fragments: the MLE sqrt(mu) = mean sqrt(m) has relative standard error 1/sqrt(n) = 1%
// (Var of an exponential sample mean = theta^2 / n), so mu has 2/sqrt(n) = 2% (delta method);
// asserted at 4 sigma. N0 is the fragment count.
TEST(MottFit, RecoversMuOfAMottSample) {
  const int n = 10000;
  const double mu = 3.0e-4;  // kg
  const MottFit f = fit_mott(mott_sample(n, mu, 20240612));
  ASSERT_TRUE(f.ok) << f.reason;
  EXPECT_EQ(f.fragments, n);
  EXPECT_EQ(f.N0, static_cast<double>(n));
  EXPECT_NEAR(f.mu / mu, 1.0, 4.0 * 2.0 / std::sqrt(n));
  std::printf("Mott sample of %d fragments: mu_hat / mu = %.4f (standard error %.4f), R^2 = %.5f\n", n, f.mu / mu,
              2.0 / std::sqrt(n), f.r2);
  // Shape: in 200 replicates of 10,000 Mott fragments the Mott-plot R^2 ranged 0.997-0.9999,
  // that of 10,000 masses uniform on [0.5, 1.5] mu 0.699-0.719 (numpy simulation): the bars 0.99
  // and 0.8 separate them.
  EXPECT_GT(f.r2, 0.99);
  std::vector<double> uniform(n);
  std::mt19937_64 gen(7);
  for (double& v : uniform) v = mu * (0.5 + static_cast<double>(gen() >> 11) * 0x1.0p-53);
  const MottFit g = fit_mott(uniform);
  ASSERT_TRUE(g.ok);
  EXPECT_LT(g.r2, 0.8);
  std::printf("uniform masses: R^2 = %.4f\n", g.r2);
}

// The claimed sampling error itself: over R = 400 samples of n = 50 fragments the relative spread
// of sqrt(mu_hat) is 1/sqrt(n) (exact for the exponential mean) and the mean of sqrt(mu_hat) is
// sqrt(mu) (unbiased). The spread estimate has relative error ~1/sqrt(2R) = 3.5%, the mean
// ~1/sqrt(nR) = 0.7%: both asserted at 4 sigma.
TEST(MottFit, SamplingErrorIsOneOverRootN) {
  const int n = 50, R = 400;
  const double mu = 2.0e-3;
  double s1 = 0.0, s2 = 0.0;
  for (int r = 0; r < R; ++r) {
    const MottFit f = fit_mott(mott_sample(n, mu, 1000 + r));
    ASSERT_TRUE(f.ok);
    const double q = std::sqrt(f.mu / mu);
    s1 += q;
    s2 += q * q;
  }
  const double mean = s1 / R, sd = std::sqrt((s2 - R * mean * mean) / (R - 1));
  EXPECT_NEAR(mean, 1.0, 4.0 / std::sqrt(static_cast<double>(n) * R));
  EXPECT_NEAR(sd * std::sqrt(n), 1.0, 4.0 / std::sqrt(2.0 * R));
  std::printf("%d samples of %d: mean sqrt(mu_hat/mu) = %.4f, spread x sqrt(n) = %.4f\n", R, n, mean, sd * std::sqrt(n));
}

// Exact case: sqrt(m_k) = c (1 + ln(n / k)) for the k-th largest (k = 1..n) puts ln N(>=m) = ln k
// exactly on a line in sqrt(m): R^2 = 1. The MLE is sqrt(mu) = mean sqrt(m) =
// c (1 + ln n - ln(n!) / n), in closed form through lgamma.
TEST(MottFit, ExactMottLine) {
  const int n = 7;
  const double c = 0.01;
  std::vector<double> m;
  for (int k = n; k >= 1; --k) m.push_back(std::pow(c * (1.0 + std::log(static_cast<double>(n) / k)), 2));
  const MottFit f = fit_mott(m);
  ASSERT_TRUE(f.ok);
  const double theta = c * (1.0 + std::log(n) - std::lgamma(n + 1.0) / n);
  EXPECT_NEAR(f.mu, theta * theta, 1e-14 * theta * theta);
  EXPECT_EQ(f.N0, 7.0);
  EXPECT_NEAR(f.r2, 1.0, 1e-13);
}

// Three masses 1, 4, 9 g: sqrt(mu) = (1 + 2 + 3) / 3 sqrt(g), mu = 4 g. Mott plot points
// (sqrt m, ln N) = (3, 0), (2, ln 2), (1, ln 3) (sqrt(g)): centred x = 1, 0, -1, so
// S_xy = -ln 3, S_xx = 2, S_yy = ln^2 2 + ln^2 3 - ln^2 6 / 3, R^2 = ln^2 3 / (2 S_yy).
TEST(MottFit, ThreeFragmentsByHand) {
  const MottFit f = fit_mott({4e-3, 1e-3, 9e-3});
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.mu, 4e-3, 1e-17);
  EXPECT_EQ(f.fragments, 3);
  const double l2 = std::log(2.0), l3 = std::log(3.0), l6 = std::log(6.0);
  const double syy = l2 * l2 + l3 * l3 - l6 * l6 / 3.0;
  EXPECT_NEAR(f.r2, l3 * l3 / (2.0 * syy), 1e-14);
}

// Ties share one Mott-plot point at the count including all of them: masses a, a, b (b < a) give
// the two points (sqrt a, ln 2), (sqrt b, ln 3), exactly a line. Equal masses: no line (NaN) but
// mu = that mass. The order of the masses does not matter (bitwise).
TEST(MottFit, TiesAndOrder) {
  const double a = 5e-3, b = 1e-3;
  const MottFit f = fit_mott({a, b, a});
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.r2, 1.0, 1e-14);
  const double theta = (2 * std::sqrt(a) + std::sqrt(b)) / 3;
  EXPECT_NEAR(f.mu, theta * theta, 1e-15 * a);
  const MottFit same = fit_mott({a, a, a});
  ASSERT_TRUE(same.ok);
  EXPECT_TRUE(std::isnan(same.r2));
  EXPECT_NEAR(same.mu, a, 1e-15 * a);
  std::vector<double> m = mott_sample(101, 1e-3, 3);
  const MottFit f1 = fit_mott(m);
  std::reverse(m.begin(), m.end());
  std::rotate(m.begin(), m.begin() + 37, m.end());
  const MottFit f2 = fit_mott(m);
  EXPECT_EQ(f1.mu, f2.mu);
  EXPECT_EQ(f1.r2, f2.r2);
}

// Fewer than three fragments, or a mass that is not a positive number: ok = false with a reason,
// no exception (a run must still write its summary).
TEST(MottFit, RefusesTooFewFragmentsAndBadMasses) {
  for (const std::vector<double>& m : {std::vector<double>{}, {1e-3}, {1e-3, 2e-3}}) {
    const MottFit f = fit_mott(m);
    EXPECT_FALSE(f.ok);
    EXPECT_EQ(f.fragments, static_cast<int>(m.size()));
    EXPECT_NE(f.reason.find("at least 3"), std::string::npos) << f.reason;
  }
  for (double bad : {0.0, -1e-3, std::nan("")}) {
    const MottFit f = fit_mott({1e-3, 2e-3, bad});
    EXPECT_FALSE(f.ok);
    EXPECT_NE(f.reason.find("masses > 0"), std::string::npos) << f.reason;
  }
}

}  // namespace test_mott_fit
