#include "peridynamics/contact_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ballista::pd {

bool ContactList::stale(const Vec3* x, Index n) const {
  if (static_cast<Index>(x_build.size()) != n) return true;
  const double limit2 = 0.25 * skin * skin;
  bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) {
    const Vec3 d = x[p] - x_build[p];
    moved = moved || dot(d, d) > limit2;
  }
  return moved;
}

void build_contact_list(ContactList& list, const Vec3* x, const Vec3* x0, const std::int64_t* body, Index n,
                        double delta, double dx, double skin, int dim) {
  list.skin = skin;
  list.x_build.assign(x, x + n);
  ++list.builds;
  list.offset.assign(static_cast<size_t>(n) + 1, 0);
  list.other.clear();
  list.reach.clear();
  if (n == 0) return;
  const double range = 1.35 * dx;  // S&A 2005 / LAMMPS: the contact distance never exceeds 1.35 dx
  const double cutoff = range + skin;
  double cell = cutoff * (1.0 + 1e-6);  // bin size > cutoff (no pair at the cutoff lost to round-off); enlarged if the points spread far (fragments in flight)
  Vec3 lo{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()}};
  Vec3 hi = -1.0 * lo;
  for (Index p = 0; p < n; ++p)
    for (int a = 0; a < dim; ++a) {
      lo[a] = std::min(lo[a], x[p][a]);
      hi[a] = std::max(hi[a], x[p][a]);
    }
  auto bins_along = [&](int a) { return a < dim ? (hi[a] - lo[a]) / cell + 1.0 : 1.0; };
  while (bins_along(0) * bins_along(1) * bins_along(2) > 4.0 * static_cast<double>(n) + 1024.0) cell *= 2.0;
  int nb[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) nb[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / cell) + 1);
  const Index nbins = static_cast<Index>(nb[0]) * nb[1] * nb[2];
  auto bin_of = [&](const Vec3& y, int c[3]) {
    for (int a = 0; a < 3; ++a) c[a] = a < dim ? std::min(nb[a] - 1, static_cast<int>((y[a] - lo[a]) / cell)) : 0;
  };
  std::vector<Index> start(static_cast<size_t>(nbins) + 1, 0), order(static_cast<size_t>(n)), bin(static_cast<size_t>(n));
  for (Index p = 0; p < n; ++p) {
    int c[3];
    bin_of(x[p], c);
    bin[p] = (static_cast<Index>(c[2]) * nb[1] + c[1]) * nb[0] + c[0];
    ++start[bin[p] + 1];
  }
  for (Index b = 0; b < nbins; ++b) start[b + 1] += start[b];
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index p = 0; p < n; ++p) order[fill[bin[p]]++] = p;
  }
  const double cell2 = cutoff * cutoff, delta2 = delta * delta * (1.0 + 2e-9);  // the bond family's tie rule
  auto visit = [&](Index p, auto&& emit) {
    int c[3];
    bin_of(x[p], c);
    const int zr = dim == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dxb = -1; dxb <= 1; ++dxb) {
          const int b0 = c[0] + dxb, b1 = c[1] + dy, b2 = c[2] + dz;
          if (b0 < 0 || b1 < 0 || b2 < 0 || b0 >= nb[0] || b1 >= nb[1] || b2 >= nb[2]) continue;
          const Index b = (static_cast<Index>(b2) * nb[1] + b1) * nb[0] + b0;
          for (Index i = start[b]; i < start[b + 1]; ++i) {
            const Index q = order[i];
            if (q == p) continue;
            Vec3 d = x[q] - x[p];
            if (dim == 2) d[2] = 0.0;
            if (dot(d, d) > cell2) continue;
            Vec3 d0 = x0[q] - x0[p];
            if (dim == 2) d0[2] = 0.0;
            const double r02 = dot(d0, d0);
            if (body[p] == body[q] && r02 <= delta2) continue;  // bonded (or once bonded): the bond loop's
            emit(q, std::min(0.9 * std::sqrt(r02), range));
          }
        }
  };
  std::vector<Index> count(static_cast<size_t>(n), 0);
  for_each(0, n, [&](Index p) {
    Index k = 0;
    visit(p, [&](Index, double) { ++k; });
    count[p] = k;
  });
  for (Index p = 0; p < n; ++p) list.offset[p + 1] = list.offset[p] + count[p];
  list.other.resize(static_cast<size_t>(list.offset[n]));
  list.reach.resize(list.other.size());
  for_each(0, n, [&](Index p) {
    Index k = list.offset[p];
    visit(p, [&](Index q, double d) {
      list.other[k] = static_cast<std::int32_t>(q);
      list.reach[k] = d;
      ++k;
    });
    // Increasing neighbour index: the force sums run in a fixed order (thread-count independent).
    std::vector<std::pair<std::int32_t, double>> row;
    for (Index i = list.offset[p]; i < list.offset[p + 1]; ++i) row.emplace_back(list.other[i], list.reach[i]);
    std::sort(row.begin(), row.end());
    for (size_t i = 0; i < row.size(); ++i) {
      list.other[list.offset[p] + static_cast<Index>(i)] = row[i].first;
      list.reach[list.offset[p] + static_cast<Index>(i)] = row[i].second;
    }
  });
}

}  // namespace ballista::pd
