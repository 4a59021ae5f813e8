#include "otm/split_state.hpp"

#include <algorithm>
#include <cmath>

#include "core/point_fields.hpp"
#include "otm/lme_shape.hpp"
#include "otm/otm_adaptivity.hpp"
#include "points/cell_bins.hpp"

namespace ballista::otm {

namespace {

// The largest phi in [0, 1] that keeps value + phi * f * delta within [lo, hi] for both children's
// factors f (lo <= value <= hi, as the parent is one of the samples).
double limit(double value, double delta, double lo, double hi, double fa, double fb, double phi) {
  for (const double f : {fa, fb}) {
    const double v = f * delta;
    if (v > 0.0) phi = std::min(phi, (hi - value) / v);
    if (v < 0.0) phi = std::min(phi, (lo - value) / v);
  }
  return std::max(phi, 0.0);
}

}  // namespace

std::vector<SplitIncrement> split_increments(const FieldStore& pts, const std::vector<Index>& parents,
                                             const std::vector<Vec3>& offsets, const std::vector<Vec3>& ref_offsets,
                                             bool axisymmetric, const SplitStateSpec& spec, int dim,
                                             const std::string& failed) {
  std::vector<SplitIncrement> out(parents.size());
  struct Column {
    const double* v;
    int nc;
  };
  std::vector<Column> cols;
  size_t ncomp = 0;
  for (const std::string& name : spec.fields) {
    if (!pts.has(name)) continue;
    cols.push_back({pts.real(name), pts.info(name).ncomp});
    ncomp += static_cast<size_t>(cols.back().nc);
  }
  if (!spec.interpolate || parents.empty() || ncomp == 0) return out;

  const Index n = pts.size();
  const Vec3* x = pts.view(kPosition);
  const Vec3* x0 = pts.view(kReferencePosition);
  const Mat3* extent = pts.view<Mat3>(kExtentField);
  std::vector<double> radius(parents.size()), share_first(parents.size());
  for (size_t i = 0; i < parents.size(); ++i) {
    const Index p = parents[i];
    double lo, hi;
    symmetric_extremes(extent[p] * transpose(extent[p]), dim, lo, hi);
    radius[i] = 1.5 * std::sqrt(std::max(hi, 0.0));
    // The limiter's factors; apply_split_increments takes the same shares from split_points.
    share_first[i] = first_child_share(x0[p][0], ref_offsets[i][0], axisymmetric);
  }
  const auto* body = pts.ints(kBodyIndex);
  const auto* material = pts.ints(kMaterialIndex);
  const double* dead = !failed.empty() && pts.has(failed) ? pts.real(failed) : nullptr;
  const CellBins bins(x, n, *std::max_element(radius.begin(), radius.end()), dim);

  std::vector<Index> nb;
  std::vector<Vec3> dxs;  // each neighbour's offset from the parent (in plane in 2D)
  std::vector<double> coef;
  for (size_t i = 0; i < parents.size(); ++i) {
    const Index p = parents[i];
    const double r2 = radius[i] * radius[i];
    nb.clear();
    dxs.clear();
    bins.visit(x[p], [&](Index q) {
      if (q == p || body[q] != body[p] || material[q] != material[p] || (dead && dead[q] != 0.0)) return;
      Vec3 dx = x[q] - x[p];
      if (dim == 2) dx[2] = 0.0;
      if (dot(dx, dx) > r2) return;
      nb.push_back(q);
    });
    // In point order, not the bins' (whose width is the largest radius among the parents at hand, so
    // their order depends on which points split together: on several ranks, each rank's own).
    std::sort(nb.begin(), nb.end());
    for (const Index q : nb) {
      Vec3 dx = x[q] - x[p];
      if (dim == 2) dx[2] = 0.0;
      dxs.push_back(dx);
    }
    // Weighted least squares: G = M^-1 sum w dx df with M = sum w dx dx^T, so that G . d =
    // sum c_q df_q with c_q = w_q dx_q . (M^-1 d): one solve per parent.
    Mat3 M = dim == 2 ? Mat3::diag(0.0, 0.0, 1.0) : Mat3{};
    for (const Vec3& dx : dxs) {
      const double w = 1.0 / dot(dx, dx);
      for (int r = 0; r < dim; ++r)
        for (int c = 0; c < dim; ++c) M(r, c) += w * dx[r] * dx[c];
    }
    // A gradient needs neighbours spanning every direction: M's determinant against its trace's
    // scale (the smallest eigenvalue at least ~1e-6 of the mean).
    const double tr = (trace(M) - (dim == 2 ? 1.0 : 0.0)) / dim;
    if (static_cast<int>(nb.size()) < dim + 1 || !(det(M) > 1e-6 * std::pow(tr, dim))) continue;
    const Vec3 b = inverse(M) * offsets[i];
    coef.clear();
    for (const Vec3& dx : dxs) coef.push_back(dot(dx, b) / dot(dx, dx));
    const double fa = 2.0 * (1.0 - share_first[i]), fb = -2.0 * share_first[i];
    SplitIncrement& inc = out[i];
    inc.assign(ncomp, 0.0);
    double phi = 1.0;
    size_t j = 0;
    for (const Column& col : cols)
      for (int c = 0; c < col.nc; ++c, ++j) {
        const double fp = col.v[p * col.nc + c];
        double d = 0.0, l = fp, h = fp;
        for (size_t k = 0; k < nb.size(); ++k) {
          const double fq = col.v[nb[k] * col.nc + c];
          d += coef[k] * (fq - fp);
          l = std::min(l, fq);
          h = std::max(h, fq);
        }
        // A component uniform up to round-off reconstructs noise: dropped, so that it does not
        // stop the others' interpolation.
        if (std::abs(d) <= 1e-12 * std::max(std::abs(l), std::abs(h))) d = 0.0;
        inc[j] = d;
        phi = limit(fp, d, l, h, fa, fb, phi);
      }
    for (double& d : inc) d *= phi;
  }
  return out;
}

void apply_split_increments(FieldStore& pts, const std::vector<SplitIncrement>& increments,
                            const std::vector<Index>& parents, Index first_new, const std::vector<double>& shares,
                            const SplitStateSpec& spec) {
  size_t j0 = 0;  // the field's first component in each increment
  for (const std::string& name : spec.fields) {
    if (!pts.has(name)) continue;
    const int nc = pts.info(name).ncomp;
    double* f = pts.real(name);
    for (size_t i = 0; i < parents.size(); ++i) {
      const SplitIncrement& inc = increments[i];
      if (inc.empty()) continue;
      const Index a = parents[i], b = first_new + static_cast<Index>(i);
      const double wa = shares[2 * i], fa = 2.0 * (1.0 - wa), fb = -2.0 * wa;
      for (int c = 0; c < nc; ++c) {
        const double fp = f[a * nc + c];
        f[a * nc + c] = fp + fa * inc[j0 + c];
        f[b * nc + c] = fp + fb * inc[j0 + c];
      }
    }
    j0 += static_cast<size_t>(nc);
  }
}

}  // namespace ballista::otm
