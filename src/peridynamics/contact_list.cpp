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

bool ContactList::stale_relative(const Vec3* x, Index n, int dim, const std::uint8_t* skip,
                                 const std::uint8_t* gas) const {
  if (static_cast<Index>(x_build.size()) != n) return true;
  if (!(max_reach > 0.0)) return true;
  RelativeScratch& r = relative;
  r.x.clear();
  r.id.clear();
  for (Index p = 0; p < n; ++p) {
    if (skip && skip[p]) continue;
    r.x.push_back(x[p]);
    r.id.push_back(p);
  }
  const Index m = static_cast<Index>(r.id.size());
  // Bins of at least the largest reach: two points within reach are in neighbouring bins.
  const CellBins bins(r.x.data(), m, max_reach * (1.0 + 1e-6), dim);
  const Index nbins = bins.bin_count();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  r.box.resize(static_cast<size_t>(12 * nbins));
  const auto& order = bins.order();
  for_each(0, nbins, [&](Index b) {
    double* bx = &r.box[static_cast<size_t>(12 * b)];
    for (int k = 0; k < 12; ++k) bx[k] = (k % 6) < 3 ? kInf : -kInf;
    for (Index i = bins.bin_first(b); i < bins.bin_last(b); ++i) {
      const Index p = r.id[order[i]];
      const Vec3 d = x[p] - x_build[p];
      double* k = bx + (gas && gas[p] ? 6 : 0);
      for (int a = 0; a < 3; ++a) {
        k[a] = std::min(k[a], d[a]);
        k[3 + a] = std::max(k[3 + a], d[a]);
      }
    }
  });
  // The diagonal of the box spanning two displacement boxes bounds the relative motion of any
  // point of one and any point of the other.
  const double skin2 = skin * skin;
  auto too_far = [&](const double* a, const double* b) {
    if (!(a[0] <= a[3]) || !(b[0] <= b[3])) return false;  // an empty box
    double s2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double w = std::max(a[3 + k], b[3 + k]) - std::min(a[k], b[k]);
      s2 += w * w;
    }
    return s2 > skin2;
  };
  bool moved = false;
#pragma omp parallel for schedule(dynamic, 4096) reduction(|| : moved) if (nbins > kParallelThreshold)
  for (Index b = 0; b < nbins; ++b) {
    if (moved) continue;
    const double* solid = &r.box[static_cast<size_t>(12 * b)];
    if (!(solid[0] <= solid[3])) continue;  // no solid here (gas-gas pairs do not exist)
    bins.visit_neighbour_bins(b, [&](Index c) {
      const double* other = &r.box[static_cast<size_t>(12 * c)];
      moved = moved || too_far(solid, other) || too_far(solid, other + 6);
    });
  }
  return moved;
}

void build_contact_list(ContactList& list, const Vec3* x, const Vec3* x0, const std::int64_t* body, Index n,
                        double delta, double dx, double skin, int dim, const std::uint8_t* skip,
                        const std::uint8_t* gas, const std::int64_t* key, bool clearance, const double* scale) {
  list.skin = skin;
  list.x_build.assign(x, x + n);
  list.allowance.clear();
  ++list.builds;
  list.offset.assign(static_cast<size_t>(n) + 1, 0);
  list.other.clear();
  list.reach.clear();
  if (n == 0) return;
  const double range = 1.35 * dx;  // S&A 2005 / LAMMPS: the contact distance never exceeds 1.35 dx
  // A point of a lattice `a` times coarser (gas seeded at its body's point_spacing) is a cell a
  // times wider: its pairs reach the sum of the two half-cells, range (a_p + a_q)/2. Contact stays
  // the one short-range law; only the size of the points it keeps apart changes.
  auto scale_of = [&](Index p) { return scale && gas && gas[p] ? scale[p] : 1.0; };
  // The reach of a pair of p with a solid (a solid's scale is 1).
  auto reach_to_solid = [&](double sp) { return 0.5 * range * (sp + 1.0); };
  double top = 1.0;
  if (scale && gas)
    for (Index p = 0; p < n; ++p)
      if (gas[p] && !(skip && skip[p])) top = std::max(top, scale[p]);
  // Solid-solid pairs search within range + skin; gas-solid pairs within their own reach + skin:
  // a coarse gas lattice does not widen the solids' search among themselves.
  list.max_reach = reach_to_solid(top);
  const double cutoff = range + skin;
  // Bins of the solids a hair wider than the cutoff (no pair at the cutoff lost to round-off), over
  // the solids that take part: a gas point looks only among the solids (gas-gas pairs are never
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
  // The solids in bin order, with what the search reads of them side by side, then binned again:
  // a bin's solids are then one contiguous run of memory (the search of 10^5-10^6 solids was
  // bound by the scattered reads of x, x0 and body through the bins' index order).
  const Index ns = static_cast<Index>(solid_ids.size());
  auto& packed = list.packed;
  auto& packed_x = list.packed_x;
  packed.resize(static_cast<size_t>(ns));
  packed_x.resize(static_cast<size_t>(ns));
  {
    const CellBins first(solid_x.data(), ns, cutoff * (1.0 + 1e-6), dim);
    for_each(0, ns, [&](Index i) {
      const Index q = solid_ids[first.order()[i]];
      packed[i] = {x[q], x0[q], body[q], q};
      packed_x[i] = x[q];
    });
  }
  // Stable binning of points already in bin order: order() is the identity.
  const CellBins solid_bins(packed_x.data(), ns, cutoff * (1.0 + 1e-6), dim);
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
        list.allowance[gas_ids[i]] = std::max(clear - reach_to_solid(scale_of(gas_ids[i])), skin);
      }
    }
  }
  const double delta2 = delta * delta * (1.0 + 2e-9);  // the bond family's tie rule
  auto visit = [&](Index p, auto&& emit) {
    if (skip && skip[p]) return;
    const Vec3 xp = x[p], x0p = x0[p];
    const std::int64_t bp = body[p];
    const double sp = scale_of(p);
    // A candidate q (its position, reference position and body), listed if within reach + skin
    // and never bonded to p. Gas-gas pairs never get here: every pair has a solid end.
    auto consider = [&](Index q, const Vec3& xq, const Vec3& x0q, std::int64_t bq, double reach) {
      if (q == p) return;
      Vec3 d = xq - xp;
      if (dim == 2) d[2] = 0.0;
      const double cut = reach + skin;
      if (dot(d, d) > cut * cut) return;
      Vec3 d0 = x0q - x0p;
      if (dim == 2) d0[2] = 0.0;
      const double r02 = dot(d0, d0);
      if (bq == bp && r02 <= delta2) return;  // bonded (or once bonded): the bond loop's
      emit(q, std::min(0.9 * std::sqrt(r02), reach));
    };
    // Solids are read from the packed copy.
    const double reach_solid = reach_to_solid(sp);
    auto solid = [&](Index i) {
      const ContactList::PackedSolid& c = packed[i];
      consider(c.id, c.x, c.x0, c.body, reach_solid);
    };
    // Gas escaped beyond the solids' box is far from every solid: not clamped into the edge bins.
    if (gas && gas[p]) {
      const double cut = reach_solid + skin;
      const int reach = static_cast<int>(std::ceil(cut / solid_bins.size()));
      if (solid_bins.near(xp, reach)) solid_bins.visit_within(xp, cut, solid, reach);
      return;
    }
    // Each pair is searched for once (the rule is symmetric): a solid pair from its lower end, a
    // gas-solid pair from its gas end. Both rows then get it (below).
    if (solid_bins.near(xp))
      solid_bins.visit_within(xp, cutoff, [&](Index i) {
        if (packed[i].id > p) solid(i);
      });
  };
  // One search per point (the list is rebuilt often: a point driven at 100 m/s crosses the half-skin
  // in a dozen steps): the pairs go to per-chunk buffers (fixed chunks, so the result does not
  // depend on the thread count). Pairs are rare (most neighbours are bonded), so the buffers stay
  // small.
  constexpr Index kChunk = 4096;
  ChunkedRows& rows = list.scratch;
  chunked_rows(n, kChunk, [&](Index p, auto& buf) {
    visit(p, [&](Index q, double d) { buf.emplace_back(static_cast<std::int32_t>(q), d); });
  }, rows);
  // Each pair found once goes to both rows: p's own finds first, then (a serial pass in chunk order,
  // O(pairs)) those that found p. Each row is then sorted by increasing neighbour index (or key),
  // so the force sums run in a fixed order (thread-count and, by id, decomposition independent) and
  // the rows are those of a search from every point.
  const Index nchunk = static_cast<Index>(rows.found.size());
  const auto& found = rows.found;
  const auto& count = rows.count;
  std::vector<Index>& fill = list.fill;
  fill.assign(static_cast<size_t>(n), 0);
  for (Index c = 0; c < nchunk; ++c)
    for (const auto& [q, d] : found[c]) ++fill[q];
  for (Index p = 0; p < n; ++p) list.offset[p + 1] = list.offset[p] + count[p] + fill[p];
  auto& entries = list.entries;
  entries.resize(static_cast<size_t>(list.offset[n]));
  for_each_chunk(nchunk, [&](Index c) {
    const auto* e = found[c].data();
    for (Index p = c * kChunk; p < std::min(n, (c + 1) * kChunk); ++p)
      for (Index j = 0; j < count[p]; ++j) entries[static_cast<size_t>(list.offset[p] + j)] = *e++;
  });
  for (Index p = 0; p < n; ++p) fill[p] = list.offset[p] + count[p];
  for (Index c = 0; c < nchunk; ++c) {
    const auto* e = found[c].data();
    for (Index p = c * kChunk; p < std::min(n, (c + 1) * kChunk); ++p)
      for (Index j = 0; j < count[p]; ++j, ++e)
        entries[static_cast<size_t>(fill[e->first]++)] = {static_cast<std::int32_t>(p), e->second};
  }
  list.other.resize(entries.size());
  list.reach.resize(entries.size());
  for_each_chunk(nchunk, [&](Index c) {
    for (Index p = c * kChunk; p < std::min(n, (c + 1) * kChunk); ++p) {
      const auto first = entries.begin() + list.offset[p], last = entries.begin() + list.offset[p + 1];
      if (key)
        std::sort(first, last, [&](const auto& a, const auto& b) { return key[a.first] < key[b.first]; });
      else
        std::sort(first, last);
      for (Index k = list.offset[p]; k < list.offset[p + 1]; ++k) {
        list.other[k] = entries[static_cast<size_t>(k)].first;
        list.reach[k] = entries[static_cast<size_t>(k)].second;
      }
    }
  });
}

}  // namespace ballista::pd
