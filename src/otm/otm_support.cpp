#include "otm/otm_support.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "points/cell_bins.hpp"

namespace ballista::otm {

double support_radius(const SupportOptions& opt) { return opt.h * std::sqrt(-std::log(opt.tolerance) / opt.gamma); }

namespace {

/// Squared distance from a point to a node as the search measures it (in the plane in 2D).
double distance2(const Vec3& x, const Vec3& xa, int dim) {
  Vec3 d = x - xa;
  if (dim == 2) d[2] = 0.0;
  return dot(d, d);
}

/// Nodes of point p's body within radius r of it, in increasing index, appended to ids.
template <class Bins>
void nodes_within(const Bins& bins, const Vec3& x, std::int64_t body, const Vec3* xn, const std::int64_t* nbody,
                  double r, int dim, std::vector<std::int32_t>& ids) {
  const double r2 = r * r;
  const size_t first = ids.size();
  bins.visit(x, [&](Index a) {
    if (nbody[a] != body) return;
    if (distance2(x, xn[a], dim) <= r2) ids.push_back(static_cast<std::int32_t>(a));
  });
  std::sort(ids.begin() + static_cast<std::ptrdiff_t>(first), ids.end());
}

/// Compressed rows of points 0..np: append(p, ids) appends point p's nodes to ids. Blocks of
/// points fill their own lists in parallel, laid out in point order afterwards (the same for any
/// thread count).
template <class Append>
void rows_of_points(Index np, const Append& append, std::vector<Index>& offset, std::vector<std::int32_t>& node) {
  constexpr Index kBlock = 64;
  const Index blocks = (np + kBlock - 1) / kBlock;
  std::vector<std::vector<std::int32_t>> found(static_cast<size_t>(blocks));
  offset.assign(static_cast<size_t>(np) + 1, 0);
#pragma omp parallel for schedule(dynamic, 1) if (np > kHeavyParallelThreshold)
  for (Index b = 0; b < blocks; ++b) {
    std::vector<std::int32_t>& ids = found[static_cast<size_t>(b)];
    for (Index p = b * kBlock; p < std::min(np, (b + 1) * kBlock); ++p) {
      const size_t before = ids.size();
      append(p, ids);
      offset[p + 1] = static_cast<Index>(ids.size() - before);
    }
  }
  for (Index p = 0; p < np; ++p) offset[p + 1] += offset[p];
  node.resize(static_cast<size_t>(offset[np]));
  for_each(0, blocks, [&](Index b) {
    const std::vector<std::int32_t>& ids = found[static_cast<size_t>(b)];
    std::copy(ids.begin(), ids.end(), node.begin() + offset[b * kBlock]);
  });
}

/// True while every point's candidate list still holds every node of its body within radius(p):
/// r_p + |x_p - x_p'| + max_a |x_a - x_a'| <= reach_p, with the sizes and bodies of the search.
template <class Radius>
bool candidates_hold(const SupportCandidates& c, const Vec3* xp, const std::int64_t* pbody, Index np, const Vec3* xn,
                     const std::int64_t* nbody, Index nn, int dim, const Radius& radius) {
  if (static_cast<Index>(c.point_x.size()) != np || static_cast<Index>(c.node_x.size()) != nn) return false;
  double moved2 = 0.0;
  for (Index a = 0; a < nn; ++a) {
    if (nbody[a] != c.node_body[a]) return false;
    moved2 = std::max(moved2, distance2(xn[a], c.node_x[a], dim));
  }
  const double node_moved = std::sqrt(moved2);
  for (Index p = 0; p < np; ++p) {
    if (pbody[p] != c.point_body[p]) return false;
    // The 1e-12 covers the round-off of the sum.
    if (radius(p) + std::sqrt(distance2(xp[p], c.point_x[p], dim)) + node_moved > c.reach[p] * (1.0 - 1e-12))
      return false;
  }
  return true;
}

}  // namespace

void build_supports(const Vec3* xp, const std::int64_t* pbody, Index np, const Vec3* xn, const std::int64_t* nbody,
                    Index nn, const SupportOptions& opt, const double* scale, const Supports* previous, Vec3* lambda,
                    Supports& out, SupportCandidates* candidates) {
  const double r0 = support_radius(opt);
  const int min_support = opt.min_support > 0 ? opt.min_support : opt.dim + 2;
  double smax = 1.0;
  if (scale)
    for (Index p = 0; p < np; ++p) smax = std::max(smax, std::min(scale[p], kMaxScale));
  auto radius = [&](Index p) { return scale ? r0 * std::clamp(scale[p], 1.0, kMaxScale) : r0; };
  // The binned search of every point's nodes within factor * radius(p).
  auto search = [&](double factor, std::vector<Index>& offset, std::vector<std::int32_t>& node) {
    const CellBins bins(xn, nn, factor * r0 * smax * (1.0 + 1e-9), opt.dim);
    rows_of_points(
        np,
        [&](Index p, std::vector<std::int32_t>& ids) {
          nodes_within(bins, xp[p], pbody[p], xn, nbody, factor * radius(p), opt.dim, ids);
        },
        offset, node);
  };
  // Pass 1: the nodes each point reaches: from its candidate list, searched again when it may no
  // longer hold them all, or (without lists) by the binned search.
  if (candidates) {
    SupportCandidates& c = *candidates;
    if (!candidates_hold(c, xp, pbody, np, xn, nbody, nn, opt.dim, radius)) {
      c.reach.resize(static_cast<size_t>(np));
      for (Index p = 0; p < np; ++p) c.reach[p] = kSkin * radius(p);
      search(kSkin, c.offset, c.node);
      c.point_x.assign(xp, xp + np);
      c.point_body.assign(pbody, pbody + np);
      c.node_x.assign(xn, xn + nn);
      c.node_body.assign(nbody, nbody + nn);
      ++c.searches;
    }
    // The candidates are in increasing index, so the nodes within r_p keep that order: the rows
    // are those the search would give.
    rows_of_points(
        np,
        [&](Index p, std::vector<std::int32_t>& ids) {
          const double r = radius(p), r2 = r * r;
          for (Index k = c.offset[p]; k < c.offset[p + 1]; ++k)
            if (distance2(xp[p], xn[c.node[k]], opt.dim) <= r2) ids.push_back(c.node[k]);
        },
        out.offset, out.node);
  } else {
    search(1.0, out.offset, out.node);
  }
  const Index total = out.offset[np];
  out.N.resize(static_cast<size_t>(total));
  out.dN.resize(static_cast<size_t>(total));
  // Pass 2: the LME solve over each point's nodes (in increasing index).
  const double beta = opt.gamma / (opt.h * opt.h);
  std::vector<char> ok(static_cast<size_t>(np), 1);
  int max_size = 0, max_iter = 0;
  double max_cond = 0.0;
  Index fallbacks = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(max : max_size, max_iter, max_cond) \
    reduction(+ : fallbacks) if (np > kHeavyParallelThreshold)
  for (Index p = 0; p < np; ++p) {
    const Index k0 = out.offset[p];
    const int k = static_cast<int>(out.offset[p + 1] - k0);
    const std::int32_t* ids = out.node.data() + k0;
    thread_local std::vector<Vec3> d;
    d.resize(static_cast<size_t>(k));
    for (int j = 0; j < k; ++j) d[j] = xp[p] - xn[ids[j]];
    LmeResult res;
    if (k >= min_support)
      res = lme_shape(opt.dim, d.data(), k, beta, opt.h, lambda[p], out.N.data() + k0, out.dN.data() + k0, opt.lme);
    max_size = std::max(max_size, k);
    max_iter = std::max(max_iter, res.iterations);
    if (res.used_fallback) ++fallbacks;
    if (res.converged) max_cond = std::max(max_cond, res.condition);
    else ok[p] = 0;
  }
  out.retries = 0;
  out.failed = -1;
  // Retries (serial: rare) with the union of the new and the previous nodes of the point.
  std::vector<Index> failed;
  for (Index p = 0; p < np; ++p)
    if (!ok[p]) failed.push_back(p);
  if (!failed.empty() && previous && previous->size() == np) {
    std::vector<std::vector<std::int32_t>> rows(failed.size());
    std::vector<std::vector<double>> Ns(failed.size());
    std::vector<std::vector<Vec3>> dNs(failed.size());
    std::vector<Index> unresolved;
    for (size_t i = 0; i < failed.size(); ++i) {
      const Index p = failed[i];
      std::vector<std::int32_t>& row = rows[i];
      row.assign(out.node.begin() + out.offset[p], out.node.begin() + out.offset[p + 1]);
      row.insert(row.end(), previous->node.begin() + previous->offset[p],
                 previous->node.begin() + previous->offset[p + 1]);
      std::sort(row.begin(), row.end());
      row.erase(std::unique(row.begin(), row.end()), row.end());
      const int k = static_cast<int>(row.size());
      std::vector<Vec3> d(static_cast<size_t>(k));
      for (int j = 0; j < k; ++j) d[j] = xp[p] - xn[row[j]];
      Ns[i].resize(static_cast<size_t>(k));
      dNs[i].resize(static_cast<size_t>(k));
      Vec3 lam;
      const LmeResult res = lme_shape(opt.dim, d.data(), k, beta, opt.h, lam, Ns[i].data(), dNs[i].data(), opt.lme);
      if (res.converged) {
        lambda[p] = lam;
        ok[p] = 1;
        ++out.retries;
        max_size = std::max(max_size, k);
        max_cond = std::max(max_cond, res.condition);
      }
    }
    // Splice the retried rows into the compressed storage.
    if (out.retries > 0) {
      Supports merged;
      merged.offset.assign(static_cast<size_t>(np) + 1, 0);
      size_t next = 0;
      for (Index p = 0; p < np; ++p) {
        const bool retried = next < failed.size() && failed[next] == p;
        const Index k = retried ? static_cast<Index>(rows[next].size()) : out.offset[p + 1] - out.offset[p];
        merged.offset[p + 1] = merged.offset[p] + k;
        if (retried) {
          merged.node.insert(merged.node.end(), rows[next].begin(), rows[next].end());
          merged.N.insert(merged.N.end(), Ns[next].begin(), Ns[next].end());
          merged.dN.insert(merged.dN.end(), dNs[next].begin(), dNs[next].end());
          ++next;
        } else {
          merged.node.insert(merged.node.end(), out.node.begin() + out.offset[p], out.node.begin() + out.offset[p + 1]);
          merged.N.insert(merged.N.end(), out.N.begin() + out.offset[p], out.N.begin() + out.offset[p + 1]);
          merged.dN.insert(merged.dN.end(), out.dN.begin() + out.offset[p], out.dN.begin() + out.offset[p + 1]);
        }
      }
      out.offset.swap(merged.offset);
      out.node.swap(merged.node);
      out.N.swap(merged.N);
      out.dN.swap(merged.dN);
    }
  }
  out.unsolved.clear();
  for (Index p = 0; p < np; ++p)
    if (!ok[p]) out.unsolved.push_back(p);
  if (!out.unsolved.empty()) out.failed = out.unsolved.front();
  out.mean_size = np > 0 ? static_cast<double>(out.offset[np]) / static_cast<double>(np) : 0.0;
  out.max_size = max_size;
  out.max_iterations = max_iter;
  out.max_condition = max_cond;
  out.fallbacks = fallbacks;
  if (out.failed >= 0) {
    // Solve it again (serial) for the diagnostic.
    const Index p = out.failed, k0 = out.offset[p];
    const int k = static_cast<int>(out.offset[p + 1] - k0);
    std::vector<Vec3> d(static_cast<size_t>(k)), g(static_cast<size_t>(k));
    std::vector<double> N(static_cast<size_t>(k));
    for (int j = 0; j < k; ++j) d[j] = xp[p] - xn[out.node[k0 + j]];
    Vec3 lam;
    out.failed_result = lme_shape(opt.dim, d.data(), k, beta, opt.h, lam, N.data(), g.data(), opt.lme);
  }
}

void build_influences(const Supports& sup, Index nn, Influences& out) {
  const Index np = sup.size();
  const Index ne = np > 0 ? sup.offset[np] : 0;
  out.start.assign(static_cast<size_t>(nn) + 1, 0);
  for (Index k = 0; k < ne; ++k) ++out.start[sup.node[k] + 1];
  for (Index a = 0; a < nn; ++a) out.start[a + 1] += out.start[a];
  out.entry.resize(static_cast<size_t>(ne));
  out.owner.resize(static_cast<size_t>(ne));
  std::vector<Index> fill(out.start.begin(), out.start.end() - 1);
  for (Index p = 0; p < np; ++p)
    for (Index k = sup.offset[p]; k < sup.offset[p + 1]; ++k) {
      const Index i = fill[sup.node[k]]++;
      out.entry[i] = k;
      out.owner[i] = p;
    }
}

}  // namespace ballista::otm
