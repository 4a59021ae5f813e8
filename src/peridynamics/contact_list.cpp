#include "peridynamics/contact_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "peridynamics/chunked_rows.hpp"
#include "points/cell_bins.hpp"

namespace ballista::pd {

double ContactList::solid_moved(const Vec3* x, Index n, const std::uint8_t* skip, const std::uint8_t* gas) const {
  if (static_cast<Index>(x_build.size()) != n) return std::numeric_limits<double>::infinity();
  double m2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : m2) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) {
    if ((skip && skip[p]) || (gas && gas[p])) continue;  // skip: vented gas (no longer part of the run)
    const Vec3 d = x[p] - x_build[p];
    m2 = std::max(m2, dot(d, d));
  }
  return std::sqrt(m2);
}

bool ContactList::stale(const Vec3* x, Index n, double moved_solid, const std::uint8_t* skip,
                        const std::uint8_t* gas) const {
  if (static_cast<Index>(x_build.size()) != n) return true;
  if (2.0 * moved_solid > skin) return true;
  if (!gas) return false;
  bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) {
    if (!gas[p] || (skip && skip[p])) continue;
    const double budget = allowance[p] - moved_solid;  // > skin/2 here
    const Vec3 d = x[p] - x_build[p];
    moved = moved || dot(d, d) > budget * budget;
  }
  return moved;
}

void build_contact_list(ContactList& list, const Vec3* x, const Vec3* x0, const std::int64_t* body, Index n,
                        double delta, double dx, double skin, int dim, const std::uint8_t* skip,
                        const std::uint8_t* gas, const std::int64_t* key, bool clearance) {
  list.skin = skin;
  list.x_build.assign(x, x + n);
  list.allowance.clear();
  ++list.builds;
  list.offset.assign(static_cast<size_t>(n) + 1, 0);
  list.other.clear();
  list.reach.clear();
  if (n == 0) return;
  const double range = 1.35 * dx;  // S&A 2005 / LAMMPS: the contact distance never exceeds 1.35 dx
  const double cutoff = range + skin;
  // Bins a hair wider than the cutoff (no pair at the cutoff lost to round-off), over the points
  // that take part (vented gas flying far off would stretch the bins over its whole cloud), in two
  // sets when there is gas: a gas point looks only among the solids (gas-gas pairs are never
  // pairs), which keeps the search of a charge's many gas points short.
  std::vector<Index> solid_ids, gas_ids;
  std::vector<Vec3> solid_x, gas_x;
  for (Index p = 0; p < n; ++p) {
    if (skip && skip[p]) continue;
    if (gas && gas[p]) {
      gas_ids.push_back(p);
      gas_x.push_back(x[p]);
    } else {
      solid_ids.push_back(p);
      solid_x.push_back(x[p]);
    }
  }
  const double bin = cutoff * (1.0 + 1e-6);
  const CellBins solid_bins(solid_x.data(), static_cast<Index>(solid_ids.size()), bin, dim);
  const CellBins gas_bins(gas_x.data(), static_cast<Index>(gas_ids.size()), bin, dim);
  // Gas allowances: the skin, or for a gas point whose bin is d >= 2 bins (chessboard) from every
  // solid's bin, or which lies outside the solids' bounding box, its clearance less the contact
  // distance (every solid is at least (d - 1) bin sizes away along one axis, and at least the
  // distance to their box).
  if (gas) {
    list.allowance.assign(static_cast<size_t>(n), skin);
    if (clearance && !solid_ids.empty()) {
      const std::vector<std::uint8_t> dist = solid_bins.chessboard_distance(16);
      for (Index i = 0; i < static_cast<Index>(gas_ids.size()); ++i) {
        const int d = dist[solid_bins.bin_of(gas_x[i])];
        const double clear = std::max((d - 1) * solid_bins.size(), solid_bins.outside_distance(gas_x[i]));
        list.allowance[gas_ids[i]] = std::max(clear - range, skin);
      }
    }
  }
  const double cut2 = cutoff * cutoff, delta2 = delta * delta * (1.0 + 2e-9);  // the bond family's tie rule
  auto visit = [&](Index p, auto&& emit) {
    if (skip && skip[p]) return;
    auto test = [&](Index q) {
      if (q == p) return;
      Vec3 d = x[q] - x[p];
      if (dim == 2) d[2] = 0.0;
      if (dot(d, d) > cut2) return;
      Vec3 d0 = x0[q] - x0[p];
      if (dim == 2) d0[2] = 0.0;
      const double r02 = dot(d0, d0);
      if (body[p] == body[q] && r02 <= delta2) return;  // bonded (or once bonded): the bond loop's
      emit(q, std::min(0.9 * std::sqrt(r02), range));
    };
    // Gas escaped beyond the solids' box is far from every solid: not clamped into the edge bins.
    if (solid_bins.near(x[p])) solid_bins.visit_within(x[p], cutoff, [&](Index i) { test(solid_ids[i]); });
    if (!(gas && gas[p]) && gas_bins.near(x[p]))
      gas_bins.visit_within(x[p], cutoff, [&](Index i) { test(gas_ids[i]); });
  };
  // One search per point (the list is rebuilt often: a point driven at 100 m/s crosses the half-skin
  // in a dozen steps): the pairs go to per-chunk buffers (fixed chunks, so the result does not
  // depend on the thread count), then into the rows. Pairs are rare (most neighbours are bonded),
  // so the buffers stay small.
  constexpr Index kChunk = 4096;
  ChunkedRows& rows = list.scratch;
  chunked_rows(n, kChunk, [&](Index p, auto& buf) {
    const size_t first = buf.size();
    visit(p, [&](Index q, double d) { buf.emplace_back(static_cast<std::int32_t>(q), d); });
    // Increasing neighbour index (or key): the force sums run in a fixed order (thread-count and,
    // by id, decomposition independent).
    if (key)
      std::sort(buf.begin() + static_cast<std::ptrdiff_t>(first), buf.end(),
                [&](const auto& a, const auto& b) { return key[a.first] < key[b.first]; });
    else
      std::sort(buf.begin() + static_cast<std::ptrdiff_t>(first), buf.end());
  }, rows);
  const Index nchunk = static_cast<Index>(rows.found.size());
  const auto& found = rows.found;
  const auto& count = rows.count;
  for (Index p = 0; p < n; ++p) list.offset[p + 1] = list.offset[p] + count[p];
  list.other.resize(static_cast<size_t>(list.offset[n]));
  list.reach.resize(list.other.size());
  for_each_chunk(nchunk, [&](Index c) {
    Index k = list.offset[c * kChunk];
    for (const auto& [q, d] : found[c]) {
      list.other[k] = q;
      list.reach[k] = d;
      ++k;
    }
  });
}

}  // namespace ballista::pd
