#pragma once
// Pure numerical functions for penetration histories depth(t): rate by local polynomial
// differentiation, the Orphal & Anderson steady-state line, the stop time and the channel radius
// profile (thesis seed 000 §7.2, Figs. 7.4-7.5; Orphal & Anderson, Int. J. Impact Eng. 33 (2006)
// 546). No solver state: vectors in, numbers out.
#include <vector>

namespace ballista {

/// d y / d t at every sample by a local least-squares polynomial of `degree` fitted to the
/// samples within `half_window` neighbours on each side (the window shifts inward at the ends,
/// so every estimate uses 2*half_window+1 points when there are that many). Times strictly
/// increasing, not necessarily uniform. Exact for polynomials of degree <= `degree`.
/// Throws std::invalid_argument for mismatched sizes, non-increasing t, degree < 1 or
/// 2*half_window+1 <= degree. Fewer samples than degree+1: returns NaNs.
/// With fewer than 2*half_window+1 (but at least degree+1) samples every estimate uses all samples.
std::vector<double> local_polynomial_derivative(const std::vector<double>& t,
                                                const std::vector<double>& y, int half_window = 3,
                                                int degree = 2);

struct SteadyFit {
  bool ok = false;                ///< false: no steady interval found
  double slope = 0;               ///< m/s (steady penetration rate U)
  double intercept = 0;           ///< m (depth at t = 0 of the fitted line)
  double t_begin = 0, t_end = 0;  ///< s, interval fitted
  double r2 = 0;                  ///< coefficient of determination of the fit on that interval
  int points = 0;
  int first = -1, last = -1;  ///< sample indices of the interval (inclusive); -1 when !ok
};
/// The steady-state (quasi-linear) part of a penetration history depth(t), as Orphal & Anderson
/// fit it: the longest contiguous run of samples whose rate stays within `rate_tolerance`
/// (relative) of that run's mean rate, among samples with rate > 0 (ignoring the entry
/// transient and the final deceleration), with at least `min_points`; then a least-squares line
/// through depth on that run.
/// Precisely: a run [i, j] qualifies when every rate in it is finite and > 0 and
/// (1 - tol) mean <= rate_k <= (1 + tol) mean for all k in it. The longest qualifying run is
/// returned; among equally long runs, the earliest. (Qualifying runs are not closed under taking
/// sub-runs, so this is found by exhaustive search over start points, not by two pointers; see the
/// .cpp.) A history with no steady part (e.g. monotone deceleration) still has short qualifying
/// runs: the result is then ok with an interval whose duration is set by the tolerance alone
/// (for rate ~ exp(-t/tau) about tau * ln((1+tol)/(1-tol))); callers judge it by its duration.
/// Throws std::invalid_argument for mismatched sizes, non-increasing t, tol outside (0, 1) or
/// min_points < 2.
SteadyFit steady_state_fit(const std::vector<double>& t, const std::vector<double>& depth,
                           const std::vector<double>& rate, double rate_tolerance = 0.1,
                           int min_points = 5);

/// Time penetration stops: the earliest sample time t_s such that depth(t) - depth(t_s) stays
/// below `depth_tolerance` (m) for all later samples, provided the last sample is at least
/// `hold` seconds after t_s; NaN if penetration has not stopped by the end.
/// Throws std::invalid_argument for mismatched sizes, non-increasing t, depth_tolerance <= 0 or
/// hold < 0. Empty input: NaN.
double penetration_stop_time(const std::vector<double>& t, const std::vector<double>& depth,
                             double depth_tolerance, double hold);

/// Channel radius profile: given points (depth_i, radius_i) of target material near the channel
/// (for each target particle, its depth below the original surface and its distance from the
/// axis), bin depths into `bins` equal bins over [0, max_depth] and return, per bin, the bin
/// centre depth and the channel radius = the smallest radius of target material in that bin (NaN
/// if the bin has no material). Bin k is [k h, (k+1) h) with h = max_depth / bins, the last bin
/// also holds depth == max_depth; points outside [0, max_depth] or with non-finite values are
/// ignored. Throws std::invalid_argument for mismatched sizes, max_depth <= 0, bins < 1 or a
/// negative radius.
struct ChannelProfile {
  std::vector<double> depth, radius;
};
ChannelProfile channel_profile(const std::vector<double>& depth, const std::vector<double>& radius,
                               double max_depth, int bins);

}  // namespace ballista
