#include "peridynamics/bond_family.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <limits>

#include "core/error.hpp"
#include "points/cell_bins.hpp"

namespace ballista::pd {

double partial_volume_factor(double xi, double delta, double dx) {
  if (dx <= 0.0) return xi <= delta * (1.0 + 1e-9) ? 1.0 : 0.0;
  if (xi <= delta - 0.5 * dx) return 1.0;
  if (xi >= delta + 0.5 * dx) return 0.0;
  // A bond within round-off of the horizon counts as exactly at it (factor 1/2): the same for all.
  if (std::abs(xi - delta) <= 1e-9 * delta) return 0.5;
  return (delta + 0.5 * dx - xi) / dx;
}

double lattice_family_size(double m, int dim) {
  if (!(m >= 1.0) || !std::isfinite(m)) return 0.0;
  if (m > 100.0) return dim == 3 ? 4.0 / 3.0 * std::numbers::pi * m * m * m : std::numbers::pi * m * m;
  const int M = static_cast<int>(std::floor(m));
  const double reach2 = m * m * (1.0 + 2e-9);  // the tie rule of build_bond_family
  double count = 0.0;
  for (int k = dim == 3 ? -M : 0; k <= (dim == 3 ? M : 0); ++k)
    for (int j = -M; j <= M; ++j)
      for (int i = -M; i <= M; ++i) {
        const double r2 = double(i) * i + double(j) * j + double(k) * k;
        if (r2 > 0.0 && r2 <= reach2) count += 1.0;
      }
  return count;
}

LatticeMoments lattice_moments(double delta, double dx, bool partial, int dim) {
  LatticeMoments m;
  for_each_lattice_bond(delta, dx, partial, dim, [&](double x, double r, double b, double V) {
    m.m1 += r * b * V;
    if (x > 0.0) m.m2 += r * x * b * V;
  });
  return m;
}

void family_with_rows(const std::vector<Index>& count, BondFamily& f) {
  const Index n = static_cast<Index>(count.size());
  f.offset.resize(static_cast<size_t>(n) + 1);
  f.offset[0] = 0;
  for (Index p = 0; p < n; ++p) f.offset[p + 1] = f.offset[p] + count[p];
  const auto nbond = static_cast<size_t>(f.offset[n]);
  f.other.resize(nbond);
  f.length0.resize(nbond);
  f.volume_factor.resize(nbond);
  f.broken.assign(nbond, 0);
}

BondFamily family_with_rows(const std::vector<Index>& count) {
  BondFamily f;
  family_with_rows(count, f);
  return f;
}

namespace {

/// The horizon and partial-volume spacing of one candidate pair (delta <= 0: not a pair).
struct PairRule {
  double delta = 0.0;
  double dx = 0.0;
};

/// The families of build_bond_family and build_gas_family: the pairs within their horizon that
/// `rule(p, o)` admits (a symmetric rule, so that each bond is in both ends' rows); no pair's
/// horizon exceeds `reach`.
template <class Rule>
BondFamily build_family(const Vec3* x0, Index n, double reach, int dim, const Rule& rule) {
  if (n > std::numeric_limits<std::int32_t>::max())
    throw Error("peridynamics: more than 2^31 points in one bond family");
  BondFamily f;
  f.offset.assign(static_cast<size_t>(n) + 1, 0);
  if (n == 0) return f;
  // Bins of size >= the horizon, so that neighbours lie in the 3^dim surrounding bins. Bonds end
  // at the horizon (|xi| <= delta); the correction scales those within dx/2 of it (as LAMMPS PERI).
  // Bins a hair wider than the horizon: two points exactly delta apart along an axis could otherwise
  // round into bins two apart and never be compared (found by the energy-release verification).
  const CellBins bins(x0, n, reach * (1.0 + 1e-6), dim);
  // Lattice points at exactly the horizon (m = 3 on a cubic lattice: 30 of them) must be in or out
  // for every point alike, whatever the round-off of their coordinates: the test admits a relative
  // 1e-9 beyond delta (LAMMPS sidesteps the tie with delta = 3.0002 dx).
  // Two passes over the same search: count each row, then fill it (rows sorted by index).
  auto visit = [&](Index p, auto&& emit) {
    bins.visit(x0[p], [&](Index o) {
      if (o == p) return;
      const PairRule pr = rule(p, o);
      if (!(pr.delta > 0.0)) return;
      Vec3 d = x0[o] - x0[p];
      if (dim == 2) d[2] = 0.0;
      const double r2 = dot(d, d);
      if (r2 > pr.delta * pr.delta * (1.0 + 2e-9)) return;
      const double r = std::sqrt(r2);
      const double w = partial_volume_factor(r, pr.delta, pr.dx);
      if (w > 0.0) emit(o, r, w);
    });
  };
  std::vector<Index> count(static_cast<size_t>(n), 0);
  for_each(0, n, [&](Index p) {
    Index k = 0;
    visit(p, [&](Index, double, double) { ++k; });
    count[p] = k;
  });
  f = family_with_rows(count);
  for_each(0, n, [&](Index p) {
    Index k = f.offset[p];
    visit(p, [&](Index o, double r, double w) {
      f.other[k] = static_cast<std::int32_t>(o);
      f.length0[k] = r;
      f.volume_factor[k] = static_cast<float>(w);
      ++k;
    });
    // Rows in increasing neighbour index: the force sums then run in a fixed order.
    std::vector<Index> idx(static_cast<size_t>(f.offset[p + 1] - f.offset[p]));
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = f.offset[p] + static_cast<Index>(i);
    std::sort(idx.begin(), idx.end(), [&](Index a, Index b) { return f.other[a] < f.other[b]; });
    std::vector<std::int32_t> o2(idx.size());
    std::vector<double> l2(idx.size());
    std::vector<float> w2(idx.size());
    for (size_t i = 0; i < idx.size(); ++i) {
      o2[i] = f.other[idx[i]];
      l2[i] = f.length0[idx[i]];
      w2[i] = f.volume_factor[idx[i]];
    }
    std::copy(o2.begin(), o2.end(), f.other.begin() + f.offset[p]);
    std::copy(l2.begin(), l2.end(), f.length0.begin() + f.offset[p]);
    std::copy(w2.begin(), w2.end(), f.volume_factor.begin() + f.offset[p]);
  });
  return f;
}

}  // namespace

BondFamily build_bond_family(const Vec3* x0, Index n, double delta, double dx, int dim, const std::int64_t* body,
                             const std::uint8_t* gas) {
  return build_family(x0, n, delta, dim, [&](Index p, Index o) {
    const bool bonded = (!body || body[o] == body[p]) && !(gas && (gas[p] || gas[o]));
    return bonded ? PairRule{delta, dx} : PairRule{};
  });
}

BondFamily build_gas_family(const Vec3* x0, Index n, double delta, double dx, int dim, const std::uint8_t* gas,
                            const double* scale) {
  double top = 1.0;
  if (scale)
    for (Index p = 0; p < n; ++p)
      if (gas[p]) top = std::max(top, scale[p]);
  return build_family(x0, n, delta * top, dim, [&](Index p, Index o) {
    if (!gas[p] && !gas[o]) return PairRule{};
    if (!scale) return PairRule{delta, dx};
    // The gas ends' horizons (a solid end takes the gas end's); the spacing of the finer end for
    // the partial volume (a solid's cell is dx).
    const double sp = gas[p] ? scale[p] : 1.0, so = gas[o] ? scale[o] : 1.0;
    const double reach = gas[p] && gas[o] ? std::min(sp, so) : (gas[p] ? sp : so);
    return PairRule{delta * reach, dx * std::min(sp, so)};
  });
}

BondFamily restrict_family(const BondFamily& f, const std::vector<char>& keep, const std::vector<char>& owned) {
  const Index n = f.points();
  std::vector<std::int32_t> renumber(static_cast<std::size_t>(n), -1);
  std::int32_t m = 0;
  for (Index p = 0; p < n; ++p)
    if (keep[p]) renumber[p] = m++;
  BondFamily out;
  out.offset.assign(1, 0);
  for (Index p = 0; p < n; ++p) {
    if (!keep[p]) continue;
    for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) {
      const Index q = f.other[k];
      if (!keep[q] || !(owned[p] || owned[q])) continue;
      out.other.push_back(renumber[q]);  // renumbering keeps the order: rows stay sorted
      out.length0.push_back(f.length0[k]);
      out.volume_factor.push_back(f.volume_factor[k]);
      out.broken.push_back(f.broken[k]);
    }
    out.offset.push_back(static_cast<Index>(out.other.size()));
  }
  return out;
}

}  // namespace ballista::pd
