// Pinball contact between the material points of different OTM bodies (otm_contact.hpp).
#include "otm/otm_contact.hpp"

#include <algorithm>
#include <cmath>

#include "points/cell_bins.hpp"

namespace ballista::otm {

double pinball_radius(double volume, double r, const ContactGeometry& g) {
  if (g.dim == 3) return 0.5 * std::cbrt(volume);
  const double area = g.axisym ? volume / r : volume;
  return 0.5 * std::sqrt(area);
}

Index pinball_forces(const Vec3* x, const double* volume, const std::int64_t* body, const double* stiffness, Index n,
                     double penalty, const ContactGeometry& g, std::vector<Vec3>& f) {
  f.assign(static_cast<std::size_t>(n), Vec3{});
  if (n == 0) return 0;
  // One body alone has nothing to touch.
  bool several = false;
  for (Index p = 1; p < n && !several; ++p) several = body[p] != body[0];
  if (!several) return 0;
  std::vector<double> a(static_cast<std::size_t>(n));
  double amax = 0.0;
  for (Index p = 0; p < n; ++p) {
    a[p] = pinball_radius(volume[p], x[p][0], g);
    amax = std::max(amax, a[p]);
  }
  if (!(amax > 0.0)) return 0;
  // Bins at least 2 a_max wide: every partner (closer than a_p + a_q <= 2 a_max) is in the 3^dim
  // bins around a point.
  const CellBins bins(x, n, 2.0 * amax, g.dim);
  std::vector<Index> touching(static_cast<std::size_t>(n), 0);
  const double half = 0.5 * penalty;
  for_each_heavy(0, n, [&](Index p) {
    Vec3 sum;
    Index count = 0;
    bins.visit(x[p], [&](Index q) {
      if (body[q] == body[p]) return;
      const Vec3 d = x[p] - x[q];
      const double r2 = dot(d, d), reach = a[p] + a[q];
      if (!(r2 < reach * reach) || !(r2 > 0.0)) return;
      const double dist = std::sqrt(r2);
      // k_pq is symmetric and d_qp = -d_pq exactly, so the pair's two forces cancel bitwise.
      const double k = half * std::min(stiffness[p], stiffness[q]);
      sum += (k * (reach - dist) / dist) * d;
      ++count;
    });
    f[p] = sum;
    touching[p] = count;
  });
  Index pairs = 0;
  for (Index p = 0; p < n; ++p) pairs += touching[p];
  return pairs / 2;
}

}  // namespace ballista::otm
