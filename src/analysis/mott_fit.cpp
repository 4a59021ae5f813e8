#include "analysis/mott_fit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <fmt/format.h>

namespace ballista {

namespace {

/// R^2 of the least-squares line y = a + b x (the squared correlation of x and y); NaN when x or
/// y does not vary.
double line_r2(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (size_t k = 0; k < x.size(); ++k) mx += x[k], my += y[k];
  mx /= n;
  my /= n;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;  // centred sums: no cancellation
  for (size_t k = 0; k < x.size(); ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    syy += (y[k] - my) * (y[k] - my);
    sxy += (x[k] - mx) * (y[k] - my);
  }
  if (!(sxx > 0.0) || !(syy > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sxy * sxy / (sxx * syy);
}

}  // namespace

MottFit fit_mott(const std::vector<double>& masses) {
  MottFit f;
  f.fragments = static_cast<int>(masses.size());
  if (f.fragments < kMottMinFragments) {
    f.reason = fmt::format("{} fragment{}: the Mott fit needs at least {}", f.fragments,
                           f.fragments == 1 ? "" : "s", kMottMinFragments);
    return f;
  }
  for (double m : masses)
    if (!std::isfinite(m) || m <= 0.0) {
      f.reason = fmt::format("fragment mass {} kg: the Mott fit needs finite masses > 0", m);
      return f;
    }
  // Maximum likelihood (header): sqrt(mu) = mean of sqrt(m_i), N0 = n.
  std::vector<double> m = masses;
  std::sort(m.begin(), m.end(), std::greater<>());  // descending: the sum is order-independent
  double sum = 0.0;
  for (double v : m) sum += std::sqrt(v);
  const double theta = sum / static_cast<double>(m.size());
  f.mu = theta * theta;
  f.N0 = static_cast<double>(m.size());
  // Mott plot: one point per distinct mass at N(>=m) = number of fragments with mass >= m; in
  // the descending list that is the position (1-based) of the last member of the tie.
  std::vector<double> x, y;
  for (size_t k = 0; k < m.size(); ++k)
    if (k + 1 == m.size() || m[k + 1] != m[k]) {
      x.push_back(std::sqrt(m[k]));
      y.push_back(std::log(static_cast<double>(k + 1)));
    }
  f.r2 = line_r2(x, y);
  f.ok = true;
  return f;
}

}  // namespace ballista
