#include "analysis/penetration_series.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ballista {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_sizes(const char* fn, const std::vector<double>& t, const std::vector<double>& y,
                 const char* yname) {
  if (t.size() != y.size())
    throw std::invalid_argument(std::string(fn) + ": t has " + std::to_string(t.size()) +
                                " samples but " + yname + " has " + std::to_string(y.size()));
}

/// Strictly increasing (also rejects NaN times, since every comparison with NaN is false).
void check_increasing(const char* fn, const std::vector<double>& t) {
  for (size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1]))
      throw std::invalid_argument(std::string(fn) + ": times must be strictly increasing; t[" +
                                  std::to_string(i) + "] = " + std::to_string(t[i]) + " after t[" +
                                  std::to_string(i - 1) + "] = " + std::to_string(t[i - 1]));
}

}  // namespace

// Thesis seed 000 §7.2 differentiates penetration histories with a Lagrange interpolating
// polynomial. Interpolation amplifies the sampling noise of particle-based depth histories, so we
// use its smoothing generalisation: a least-squares polynomial over 2m+1 samples, differentiated
// at the sample (Savitzky & Golay, Anal. Chem. 36 (1964) 1627, there for uniform spacing; here
// the fit is done directly on the nonuniform times). With exactly degree+1 samples in the window
// the least-squares fit is the Lagrange interpolant, the thesis method.
std::vector<double> local_polynomial_derivative(const std::vector<double>& t,
                                                const std::vector<double>& y, int half_window,
                                                int degree) {
  const char* fn = "local_polynomial_derivative";
  check_sizes(fn, t, y, "y");
  check_increasing(fn, t);
  if (degree < 1)
    throw std::invalid_argument(std::string(fn) + ": degree must be >= 1, got " +
                                std::to_string(degree));
  if (2 * half_window + 1 <= degree)
    throw std::invalid_argument(
        std::string(fn) + ": the window 2*half_window+1 = " + std::to_string(2 * half_window + 1) +
        " must have more points than the degree " + std::to_string(degree));
  const int n = static_cast<int>(t.size());
  std::vector<double> dydt(t.size(), kNaN);
  if (n < degree + 1) return dydt;
  const int w = std::min(2 * half_window + 1, n);
  Eigen::MatrixXd V(w, degree + 1);
  Eigen::VectorXd b(w);
  for (int i = 0; i < n; ++i) {
    const int lo = std::clamp(i - half_window, 0, n - w);
    // Local variable s = (t - t_i) / L in [-1, 1] keeps the Vandermonde matrix well conditioned
    // whatever the units and offset of t; d/dt = (1/L) d/ds, and dp/ds at s = 0 is coefficient 1.
    const double L = std::max(t[i] - t[lo], t[lo + w - 1] - t[i]);
    for (int k = 0; k < w; ++k) {
      const double s = (t[lo + k] - t[i]) / L;
      double p = 1.0;
      for (int j = 0; j <= degree; ++j, p *= s) V(k, j) = p;
      b(k) = y[lo + k];
    }
    const Eigen::VectorXd c = V.colPivHouseholderQr().solve(b);
    dydt[i] = c(1) / L;
  }
  return dydt;
}

// Orphal & Anderson (Int. J. Impact Eng. 33 (2006) 546) take U as the slope of a straight line
// fitted to the quasi-steady part of depth(t); thesis seed 000 Figs. 5.11 and 7.4 do the same.
// Selecting that part automatically:
//  - a run [i, j] qualifies when all its rates are finite and > 0 and lie within
//    [(1 - tol) mean, (1 + tol) mean] of the run's own mean rate;
//  - qualifying runs are NOT closed under sub-runs (dropping an end sample moves the mean, and
//    another sample can fall outside the band), so a two-pointer sweep could miss the longest one.
//    We therefore search every start i and extend j, with a running sum, min and max: O(1) per
//    (i, j), O(n^2) worst case (n = 5000: 1.25e7 cheap steps).
//  - pruning that keeps the result exact: a qualifying run has max/min <= (1 + tol)/(1 - tol),
//    and max/min only grows as j extends, so the extension from i stops there; a start i that
//    cannot beat the best length found stops the search. On a real history (one steady part)
//    the inner loop is therefore short and the search close to linear.
//  - ties in length: the earliest run.
SteadyFit steady_state_fit(const std::vector<double>& t, const std::vector<double>& depth,
                           const std::vector<double>& rate, double rate_tolerance, int min_points) {
  const char* fn = "steady_state_fit";
  check_sizes(fn, t, depth, "depth");
  check_sizes(fn, t, rate, "rate");
  check_increasing(fn, t);
  if (!(rate_tolerance > 0.0 && rate_tolerance < 1.0))
    throw std::invalid_argument(std::string(fn) + ": rate_tolerance must be in (0, 1), got " +
                                std::to_string(rate_tolerance));
  if (min_points < 2)
    throw std::invalid_argument(std::string(fn) + ": min_points must be >= 2 to fit a line, got " +
                                std::to_string(min_points));
  const int n = static_cast<int>(t.size());
  const double hi_f = 1.0 + rate_tolerance, lo_f = 1.0 - rate_tolerance;
  const double ratio_max = hi_f / lo_f;
  auto usable = [&](int k) { return std::isfinite(rate[k]) && rate[k] > 0.0; };
  int best_i = -1, best_len = 0;
  for (int i = 0; i < n && n - i > best_len; ++i) {
    if (!usable(i)) continue;
    double sum = 0.0, mn = rate[i], mx = rate[i];
    for (int j = i; j < n && usable(j); ++j) {
      sum += rate[j];
      mn = std::min(mn, rate[j]);
      mx = std::max(mx, rate[j]);
      if (mx > ratio_max * mn) break;
      const int len = j - i + 1;
      const double mean = sum / len;
      if (len > best_len && mx <= hi_f * mean && mn >= lo_f * mean) {
        best_len = len;
        best_i = i;
      }
    }
  }
  SteadyFit fit;
  if (best_len < min_points) return fit;
  // Least-squares line depth = intercept + slope t on the run, in centred form for accuracy.
  const int i0 = best_i, i1 = best_i + best_len - 1;
  double tm = 0.0, dm = 0.0;
  for (int k = i0; k <= i1; ++k) {
    tm += t[k];
    dm += depth[k];
  }
  tm /= best_len;
  dm /= best_len;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int k = i0; k <= i1; ++k) {
    sxx += (t[k] - tm) * (t[k] - tm);
    sxy += (t[k] - tm) * (depth[k] - dm);
    syy += (depth[k] - dm) * (depth[k] - dm);
  }
  fit.slope = sxy / sxx;
  fit.intercept = dm - fit.slope * tm;
  double ss_res = 0.0;
  for (int k = i0; k <= i1; ++k) {
    const double r = depth[k] - (dm + fit.slope * (t[k] - tm));
    ss_res += r * r;
  }
  fit.r2 = syy > 0.0 ? 1.0 - ss_res / syy : 1.0;  // constant depth is fitted exactly
  fit.ok = true;
  fit.t_begin = t[i0];
  fit.t_end = t[i1];
  fit.points = best_len;
  fit.first = i0;
  fit.last = i1;
  return fit;
}

double penetration_stop_time(const std::vector<double>& t, const std::vector<double>& depth,
                             double depth_tolerance, double hold) {
  const char* fn = "penetration_stop_time";
  check_sizes(fn, t, depth, "depth");
  check_increasing(fn, t);
  if (!(depth_tolerance > 0.0))
    throw std::invalid_argument(std::string(fn) + ": depth_tolerance must be > 0, got " +
                                std::to_string(depth_tolerance));
  if (!(hold >= 0.0))
    throw std::invalid_argument(std::string(fn) + ": hold must be >= 0, got " +
                                std::to_string(hold));
  const int n = static_cast<int>(t.size());
  if (n == 0) return kNaN;
  // Sweep backwards with the largest later depth: s qualifies when that maximum is less than
  // depth[s] + tolerance. The earliest qualifying s is the answer; later ones are closer to the
  // end, so if the earliest misses `hold` every one does.
  double later_max = -std::numeric_limits<double>::infinity();
  int earliest = -1;
  for (int s = n - 1; s >= 0; --s) {
    if (later_max - depth[s] < depth_tolerance) earliest = s;
    later_max = std::max(later_max, depth[s]);
  }
  if (earliest < 0 || t[n - 1] - t[earliest] < hold) return kNaN;
  return t[earliest];
}

ChannelProfile channel_profile(const std::vector<double>& depth, const std::vector<double>& radius,
                               double max_depth, int bins) {
  const char* fn = "channel_profile";
  if (depth.size() != radius.size())
    throw std::invalid_argument(std::string(fn) + ": " + std::to_string(depth.size()) +
                                " depths but " + std::to_string(radius.size()) + " radii");
  if (!(max_depth > 0.0) || !std::isfinite(max_depth))
    throw std::invalid_argument(std::string(fn) + ": max_depth must be finite and > 0, got " +
                                std::to_string(max_depth));
  if (bins < 1)
    throw std::invalid_argument(std::string(fn) + ": bins must be >= 1, got " +
                                std::to_string(bins));
  const double h = max_depth / bins;
  ChannelProfile out;
  out.depth.resize(bins);
  out.radius.assign(bins, std::numeric_limits<double>::infinity());
  for (int k = 0; k < bins; ++k) out.depth[k] = (k + 0.5) * h;
  for (size_t p = 0; p < depth.size(); ++p) {
    if (radius[p] < 0.0)
      throw std::invalid_argument(std::string(fn) + ": radius " + std::to_string(p) + " is " +
                                  std::to_string(radius[p]) + "; a distance from the axis is >= 0");
    if (!std::isfinite(depth[p]) || !std::isfinite(radius[p])) continue;
    if (depth[p] < 0.0 || depth[p] > max_depth) continue;
    const int k = std::min(static_cast<int>(depth[p] / h), bins - 1);
    out.radius[k] = std::min(out.radius[k], radius[p]);
  }
  for (double& r : out.radius)
    if (std::isinf(r)) r = std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace ballista
