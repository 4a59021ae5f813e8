#include "peridynamics/gas_pass.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/parallel.hpp"
#include "peridynamics/chunked_rows.hpp"
#include "points/cell_bins.hpp"

namespace ballista::pd {

namespace {

/// (r/p)^m for m = 1 without a pow, the current length floored (kGasMinStretchRatio).
inline double length_ratio(double r, double p) { return r / std::max(p, kGasMinStretchRatio * r); }

inline double current_length(const GasPassArgs& a, Index i, Index j) {
  Vec3 y = a.x[j] - a.x[i];
  if (a.dim == 2) y[2] = 0.0;
  return norm(y);
}

}  // namespace

double density_measure(const GasPassArgs& a, Index i) {
  static_assert(kGasExponent == 1.0, "length_ratio is (r/p)^m for m = 1");
  const BondFamily& f = *a.family;
  double s = 0.0;
  for (Index k = f.offset[i]; k < f.offset[i + 1]; ++k) {
    const Index j = f.other[k];
    s += f.volume_factor[k] * a.vol0[j] * length_ratio(f.length0[k], current_length(a, i, j));
  }
  if (!(a.family_volume[i] > 0.0)) return 1.0;  // no neighbours: nothing to measure (one lone point)
  s /= a.family_volume[i];
  // X = S^(-d/m); S >= S_min keeps X <= kGasMaxExpansion.
  const double s_min = std::pow(kGasMaxExpansion, -kGasExponent / a.dim);
  return std::pow(std::max(s, s_min), -a.dim / kGasExponent);
}

Vec3 gas_force(const GasPassArgs& a, Index p) {
  const BondFamily& f = *a.family;
  Vec3 out;
  const bool p_gas = a.gas[p] != 0;
  const double gp = p_gas ? a.g[p] : 0.0;
  for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) {
    const Index q = f.other[k];
    const double gq = a.gas[q] ? a.g[q] : 0.0;
    // The bond's push from each gas end (gas_pass.hpp): summed in the same order at both ends, so
    // the two ends get equal and opposite forces to the last bit.
    if (a.length_other) {
      // Each end's own length and weight: |f| = G_p w_q dV_q r_p / p_p^2 + G_q w_p dV_p r_q / p_q^2.
      if (gp == 0.0 && gq == 0.0) continue;
      Vec3 y = a.x[q] - a.x[p];
      if (a.dim == 2) y[2] = 0.0;
      const double len = norm(y);
      if (len == 0.0) continue;
      const double rp = f.length0[k], rq = a.length_other[k];
      const double up = gp * (f.volume_factor[k] * a.vol0[q]) * rp, uq = gq * (a.weight_other[k] * a.vol0[p]) * rq;
      if (len >= kGasMinStretchRatio * std::max(rp, rq)) {  // neither end floored: one division
        const double il = 1.0 / len;
        out += (-(up + uq) * il * il * il) * y;
        continue;
      }
      const double pp = std::max(len, kGasMinStretchRatio * rp), pq = std::max(len, kGasMinStretchRatio * rq);
      out += (-(up / (pp * pp) + uq / (pq * pq)) / len) * y;
      continue;
    }
    const double t = (gp * a.vol0[q] + gq * a.vol0[p]) * f.volume_factor[k];
    if (t == 0.0) continue;
    Vec3 y = a.x[q] - a.x[p];
    if (a.dim == 2) y[2] = 0.0;
    const double r = f.length0[k], len = norm(y);
    if (len == 0.0) continue;  // coincident points: no direction to push along
    const double pl = std::max(len, kGasMinStretchRatio * r);
    // |f| = t r^m / p^(m+1) along -y (away from q), m = 1.
    out += (-t * r / (pl * pl * len)) * y;
  }
  return out;
}

double gas_inverse_length_sum(const GasPassArgs& a, Index p) {
  const BondFamily& f = *a.family;
  double s = 0.0;
  for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) s += f.volume_factor[k] * a.vol0[f.other[k]] / f.length0[k];
  return s;
}

RenewedGasFamily build_renewed_gas_family(const Vec3* x, Index n, const std::uint8_t* gas, const std::uint8_t* skip,
                                          const double* X, double delta, int dim, const double* scale) {
  RenewedGasFamily out;
  GasRenewalWorkspace ws;
  build_renewed_gas_family(x, n, gas, skip, X, delta, dim, out, ws, scale);
  return out;
}

void build_renewed_gas_family(const Vec3* x, Index n, const std::uint8_t* gas, const std::uint8_t* skip,
                              const double* X, double delta, int dim, RenewedGasFamily& out, GasRenewalWorkspace& ws,
                              const double* scale) {
  // The products are a fluid: their reference neighbourhood is a quadrature of the local density,
  // not a material memory. Where the gas shears along the case (a detonation sliding along a
  // tube drives the products axially past the wall at km/s), a family fixed in the reference
  // configuration keeps the case points a gas point started beside and loses the ones it flows
  // past, so the products push the wall only through the contact springs. Renewed, the family is
  // every pair of gas points currently within delta min(s_p, s_q), s = X^(1/d) (its spacing has
  // grown so; capped at kHorizonGrowthCap; times the lattice scale of a coarser gas lattice), and
  // every gas point and solid within delta (times the gas point's lattice scale; a solid's
  // s is 1; spanning the gas end's s instead changes the velocities below by < 1 % and costs the
  // search of hundreds of case points per gas point): symmetric, so each pair sits in both rows as
  // gas_force needs. Each end keeps its own
  // reference length r_p = |y| X_p^(-1/d) (length_other), so that the measure of every gas point
  // gives its X again at once: the pressure, and the gas energy, are continuous across a renewal.
  // Each neighbour weighs by its current volume dV0_j X_j (the quadrature is of the current
  // neighbourhood: with reference volumes a solid neighbour would count as much as a gas point
  // grown ten times larger); any weights give X back at the renewal. Partial volumes are not applied.
  constexpr double kHorizonGrowthCap = 2.5;
  const double inv_d = 1.0 / dim;
  // Every array below is resized, not allocated: its pages are mapped by an earlier renewal.
  std::vector<double>& s = ws.s;
  std::vector<double>& root = ws.root;
  s.resize(static_cast<size_t>(n));
  root.resize(static_cast<size_t>(n));
  // The gas in bin order (binned twice: the second binning scans each bin's points contiguously),
  // in bins of half the horizon (an expanded point's search box then hugs its sphere more closely).
  using Binned = GasRenewalWorkspace::Binned;
  std::vector<Binned>& gas_pts = ws.gas_pts;
  std::vector<Index>& solid_ids = ws.solid_ids;
  std::vector<Vec3>& solid_x = ws.solid_x;
  gas_pts.clear();
  solid_ids.clear();
  solid_x.clear();
  for (Index l = 0; l < n; ++l) {
    s[l] = root[l] = 1.0;
    if (gas[l]) {
      if (skip[l]) continue;  // vented: pushes nothing, in no family
      const double a = scale ? scale[l] : 1.0;
      root[l] = std::pow(X[l], inv_d);
      s[l] = a * std::clamp(root[l], 1.0, kHorizonGrowthCap);
      gas_pts.push_back({x[l], s[l], l});
    } else {
      solid_ids.push_back(l);
      solid_x.push_back(x[l]);
    }
  }
  const double half = 0.5 * delta * (1.0 + 1e-6);
  std::vector<Vec3>& gas_x = ws.gas_x;
  const Index ng = static_cast<Index>(gas_pts.size());
  gas_x.resize(static_cast<size_t>(ng));
  for_each(0, ng, [&](Index i) { gas_x[i] = gas_pts[i].x; });
  {
    const CellBins first(gas_x.data(), ng, half, dim);
    ws.sorted.resize(static_cast<size_t>(ng));
    for_each(0, ng, [&](Index i) { ws.sorted[i] = gas_pts[first.order()[i]]; });
    gas_pts.swap(ws.sorted);
  }
  for_each(0, ng, [&](Index i) { gas_x[i] = gas_pts[i].x; });
  const CellBins gas_bins(gas_x.data(), ng, half, dim);
  // Much expanded gas (s > 1.5) searches bins of the whole horizon instead: its box of half bins
  // would be mostly empty bins (s = 2.5: 11^3 of them against 7^3).
  const CellBins gas_bins_wide(gas_x.data(), ng, 2.0 * half, dim);
  const CellBins solid_bins(solid_x.data(), static_cast<Index>(solid_ids.size()), delta * (1.0 + 1e-6), dim);
  // One search per gas point into per-chunk buffers (fixed chunks: the rows do not depend on the
  // thread count): among the gas within delta min(s_p, s_q) and among the solids within delta.
  // A solid's row is the transpose of the gas rows' solid entries, in increasing gas index.
  constexpr Index kChunk = 2048;
  ChunkedRows& rows = ws.rows;
  chunked_rows(
      n, kChunk,
      [&](Index p, auto& buf) {
        if (!gas[p] || skip[p]) return;
        const Vec3 xp = x[p];
        const double sp = s[p], ap = scale ? scale[p] : 1.0;
        auto test = [&](Index q, const Vec3& xq, double sq) {
          if (q == p) return;
          Vec3 y = xq - xp;
          if (dim == 2) y[2] = 0.0;
          const double R = delta * std::min(sp, sq), r2 = dot(y, y);
          if (r2 > R * R || r2 == 0.0) return;
          buf.emplace_back(static_cast<std::int32_t>(q), std::sqrt(r2));
        };
        const CellBins& bins = sp > 1.5 ? gas_bins_wide : gas_bins;
        const int reach = static_cast<int>(std::ceil(delta * sp / bins.size()));
        if (bins.near(xp, reach))
          bins.visit_within(xp, delta * sp, [&](Index i) { test(gas_pts[i].id, gas_pts[i].x, gas_pts[i].s); }, reach);
        // A solid's s is 1: the pair's reach is the gas end's delta x ap.
        const int solid_reach = static_cast<int>(std::ceil(ap - 1e-9));
        if (solid_bins.near(xp, solid_reach))
          solid_bins.visit_within(xp, delta * ap, [&](Index i) { test(solid_ids[i], solid_x[i], ap); }, solid_reach);
      },
      rows);
  const Index nchunk = static_cast<Index>(rows.found.size());
  const auto& found = rows.found;
  std::vector<Index>& count = rows.count;
  for (const auto& buf : found)
    for (const auto& e : buf)
      if (!gas[e.first]) ++count[e.first];
  BondFamily& f = out.family;
  family_with_rows(count, f);
  const Index nb = f.bonds();
  std::vector<double>& other = out.length_other;
  std::vector<float>& weight_other = out.weight_other;
  other.resize(static_cast<size_t>(nb));
  weight_other.resize(static_cast<size_t>(nb));
  auto put = [&](Index k, Index l, Index q, double len) {
    f.other[k] = static_cast<std::int32_t>(q);
    f.length0[k] = gas[l] ? len / root[l] : len;
    other[k] = gas[q] ? len / root[q] : len;
    f.volume_factor[k] = gas[q] ? static_cast<float>(X[q]) : 1.0f;
    weight_other[k] = gas[l] ? static_cast<float>(X[l]) : 1.0f;
  };
  for_each_chunk(nchunk, [&](Index c) {  // the gas rows
    size_t e = 0;
    const auto& buf = found[c];
    for (Index l = c * kChunk; l < std::min(n, (c + 1) * kChunk); ++l) {
      if (!gas[l] || skip[l]) continue;
      for (Index k = f.offset[l]; k < f.offset[l + 1]; ++k, ++e) put(k, l, buf[e].first, buf[e].second);
    }
  });
  std::vector<Index>& cursor = ws.cursor;  // the solid rows, in gas order
  cursor.assign(f.offset.begin(), f.offset.end() - 1);
  for (Index c = 0; c < nchunk; ++c) {
    size_t e = 0;
    const auto& buf = found[c];
    for (Index l = c * kChunk; l < std::min(n, (c + 1) * kChunk); ++l) {
      if (!gas[l] || skip[l]) continue;
      for (Index k = 0; k < f.offset[l + 1] - f.offset[l]; ++k, ++e) {
        const auto [q, len] = buf[e];
        if (!gas[q]) put(cursor[q]++, q, l, len);
      }
    }
  }
}

}  // namespace ballista::pd
