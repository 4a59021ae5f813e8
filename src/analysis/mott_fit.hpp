#pragma once
// Mott's fragment-mass distribution fitted to a list of fragment masses (fragment statistics of a
// fragmenting run, docs/validation.md "Fragment statistics"; seed: fragmentation V&V of the EMU
// peridynamics talk).
//
// Mott (Proc. R. Soc. A 189 (1947) 300) and Grady & Kipp (J. Appl. Phys. 58 (1985) 1210; Grady,
// "Fragmentation of Rings and Shells: The Legacy of N.F. Mott", Springer 2006) describe the
// cumulative number of fragments heavier than m as
//     N(>m) = N0 exp(-sqrt(m / mu)),
// N0 the total number of fragments, mu (kg) the distribution's mass scale (mean fragment mass
// 2 mu). Read as a probability law, P(M > m) = exp(-sqrt(m / mu)): X = sqrt(M) is exponentially
// distributed with mean theta = sqrt(mu).
//
// Estimator: maximum likelihood. For an exponential sample X_1..X_n the MLE of the mean is the
// sample mean (e.g. Johnson, Kotz & Balakrishnan, Continuous Univariate Distributions vol. 1,
// 2nd ed., ch. 19), so sqrt(mu) = (1/n) sum sqrt(m_i), mu = (that)^2 (invariance of the MLE), and
// N0 = n (every fragment has m > 0). Chosen over a least-squares line through the ranked data
// because it weighs every fragment equally (the line is dominated by the few largest fragments,
// whose ranks are correlated), needs no plotting position (the largest fragment has N(>m) = 0,
// ln 0 undefined), is indifferent to ties, and has a known sampling error: Var(theta_hat) =
// theta^2 / n exactly, so the relative standard error is 1/sqrt(n) on sqrt(mu) and ~2/sqrt(n) on
// mu (delta method).
//
// Goodness of fit: r2, the coefficient of determination of the least-squares line through the
// Mott plot, ln N(>=m) against sqrt(m) (the axes on which the Mott law is a straight line; Mott
// 1947, Grady 2006 plot fragment data this way). One point per distinct mass, at the empirical
// count N(>=m) = number of fragments with mass >= m (ties share the point; the largest fragment
// is at N = 1). r2 = 1: the data lie exactly on some Mott law; it judges the shape, not the mu
// estimate. NaN when fewer than two distinct masses (no line).
#include <string>
#include <vector>

namespace ballista {

struct MottFit {
  bool ok = false;     ///< false: too few fragments (or an invalid mass); see `reason`
  std::string reason;  ///< why there is no fit (empty when ok)
  double N0 = 0.0;     ///< fragments in the law, N(>0) = number of fragments used
  double mu = 0.0;     ///< kg, Mott mass scale (mean fragment mass = 2 mu)
  int fragments = 0;   ///< fragments used (all given masses)
  double r2 = 0.0;     ///< R^2 of ln N(>=m) vs sqrt(m) on the Mott plot (NaN: < 2 distinct masses)
};

/// At least this many fragments are needed for a fit.
inline constexpr int kMottMinFragments = 3;

/// Fits N(>m) = N0 exp(-sqrt(m/mu)) to the fragment masses (kg, any order). Never throws: fewer
/// than kMottMinFragments masses, or a mass that is not finite and > 0, gives ok = false and a
/// reason.
MottFit fit_mott(const std::vector<double>& masses);

}  // namespace ballista
