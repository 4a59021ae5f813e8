#include "otm/otm_adaptivity.hpp"

#include <cmath>

#include "core/error.hpp"
#include "otm/lme_shape.hpp"
#include "points/cell_bins.hpp"

namespace ballista::otm {

Vec3 largest_eigenvector(const Mat3& A, int dim, double hi) {
  // A null vector of B = A - hi I: in 2D either row rotated by 90 degrees, in 3D the largest cross
  // product of two rows. Degenerate (isotropic) blocks return the first axis.
  const Mat3 B = A - Mat3::diag(hi, hi, hi);
  Vec3 best;
  double best2 = 0.0;
  auto consider = [&](const Vec3& c) {
    const double c2 = dot(c, c);
    if (c2 > best2) {
      best = c;
      best2 = c2;
    }
  };
  if (dim == 2) {
    consider(Vec3{{-B(0, 1), B(0, 0), 0.0}});
    consider(Vec3{{-B(1, 1), B(1, 0), 0.0}});
  } else {
    const Vec3 r0{{B(0, 0), B(0, 1), B(0, 2)}}, r1{{B(1, 0), B(1, 1), B(1, 2)}}, r2{{B(2, 0), B(2, 1), B(2, 2)}};
    consider(cross(r0, r1));
    consider(cross(r0, r2));
    consider(cross(r1, r2));
  }
  // Below round-off of the block's scale the eigenvalues coincide: any direction is principal.
  const double scale = std::max(std::abs(A(0, 0)) + std::abs(A(1, 1)) + std::abs(A(2, 2)), 1e-300);
  if (best2 <= 1e-24 * scale * scale * (dim == 2 ? 1.0 : scale * scale)) return Vec3{{1.0, 0.0, 0.0}};
  return (1.0 / std::sqrt(best2)) * best;
}

std::vector<Index> split_points(FieldStore& pts, const std::vector<std::string>& extensive,
                                const std::vector<double>& spacing, int dim, bool axisymmetric, const Vec3& lower,
                                const Vec3& upper, const AdaptivityOptions& opt, const SplitStateSpec& state,
                                const std::string& failed, std::int64_t& next_id,
                                const Neighbourhood* neighbourhood) {
  const Index n = pts.size();
  // Fields by name here, not by typed key (core/field_key.hpp): the keys change how GCC optimises
  // this file's split arithmetic (FMA contraction with -march=native) and with it the last bits of
  // the 750 m/s bar (examples/taylor_bar_otm_750.yaml), which stays bitwise.
  const auto* S = pts.view<Mat3>(kExtentField);
  const auto* body = pts.ints("body");
  const auto* xc = pts.view<Vec3>("x");
  const auto* Fc = pts.view<Mat3>("F");
  const auto* xr = pts.view<Vec3>("x0");
  // A failed (eroded) point does not split: it carries no stress, so resolving its shape buys
  // nothing, and, stretched freely by the material around it, it would split without end.
  const double* dead = !failed.empty() && pts.has(failed) ? pts.real(failed) : nullptr;
  std::vector<Index> which;
  std::vector<Vec3> half, half0;  // parent centre to the first child's: current and reference
  for (Index p = 0; p < n; ++p) {
    if (dead && dead[p] != 0.0) continue;
    const double s0 = spacing.at(static_cast<size_t>(body[p]));
    const Mat3 SSt = S[p] * transpose(S[p]);
    double lo, hi;
    symmetric_extremes(SSt, dim, lo, hi);
    if (!(std::sqrt(std::max(hi, 0.0)) > opt.split_stretch * s0)) continue;
    // The children sit at the centres of the two halves of the cell: a quarter of its extent away.
    Vec3 d = (0.25 * std::sqrt(hi)) * largest_eigenvector(SSt, dim, hi);
    const double nominal = norm(d);
    // Near a box face (a wall, a symmetry plane, the axis) the split stays parallel to it: the
    // offset loses its component along any axis on which a child would come closer to the face
    // than half its parent's distance (a thin layer on a wall splits along the wall). A point
    // whose offset is then mostly gone is not split.
    for (int a = 0; a < dim; ++a)
      if (std::abs(d[a]) > 0.5 * std::min(xc[p][a] - lower[a], upper[a] - xc[p][a])) d[a] = 0.0;
    // The same material fibre in the reference configuration (x - x0 maps by F locally; in 2D the
    // in-plane block: the hoop or out-of-plane stretch does not mix with it).
    Vec3 d0 = inverse(Fc[p]) * d;
    if (dim == 2) d0[2] = 0.0;
    if (axisymmetric && std::abs(d0[0]) > 0.5 * xr[p][0]) continue;
    if (!(norm(d) > 0.5 * nominal)) continue;
    which.push_back(p);
    half.push_back(d);
    half0.push_back(d0);
  }
  if (which.empty()) return which;
  // Before anything moves: the children's state from the parent's neighbourhood (split_state.hpp).
  // Computed and applied outside the split arithmetic below, whose last bits (GCC's FMA contraction
  // of this function) the 750 m/s bar with the copied state keeps.
  std::vector<Index> among = which;
  if (neighbourhood)
    for (Index& p : among) p = neighbourhood->own_at[static_cast<size_t>(p)];
  const std::vector<SplitIncrement> increments = split_increments(neighbourhood ? neighbourhood->points : pts, among,
                                                                  half, half0, axisymmetric, state, dim, failed);
  FieldStore kids = pts.empty_like();
  kids.append_from(pts, which);
  // Second children are appended; the parents become the first children.
  const Index m = static_cast<Index>(which.size());
  pts.append_from(kids, [&] {
    std::vector<Index> all(static_cast<size_t>(m));
    for (Index i = 0; i < m; ++i) all[i] = i;
    return all;
  }());
  auto* x = pts.view<Vec3>("x");
  auto* x0 = pts.view<Vec3>("x0");
  auto* ext = pts.view<Mat3>(kExtentField);
  auto* F = pts.view<Mat3>("F");
  auto* vol = pts.real("volume");
  const auto* vol0 = pts.real("volume0");
  auto* id = pts.ints("id");
  Vec3* hs = pts.has("half_size") ? pts.view<Vec3>("half_size") : nullptr;
  std::vector<double> share(static_cast<size_t>(2 * m));  // each child's share of the parent
  for (Index i = 0; i < m; ++i) {
    const Index a = which[i], b = n + i;
    const Vec3 d = half[i], d0 = half0[i];
    const Vec3 u = (1.0 / norm(d)) * d;
    const double wa = first_child_share(x0[a][0], d0[0], axisymmetric);
    share[2 * i] = wa;
    share[2 * i + 1] = 1.0 - wa;
    x[b] = x[a] - d;
    x[a] = x[a] + d;
    x0[b] = x0[a] - d0;
    x0[a] = x0[a] + d0;
    // The hoop stretch is each child's own r / r0 (the in-plane F is the parent's).
    if (axisymmetric) {
      F[a](2, 2) = x[a][0] / x0[a][0];
      F[b](2, 2) = x[b][0] / x0[b][0];
    }
    // The reference box x0 +- half_size (the probes' and the writer's domains, x + F (+-half))
    // halves along the reference axis whose edge spans most of the box along the split direction,
    // max_c |u . F e_c| half_c: exact for a stretch along a reference axis; otherwise a box of the
    // right reference volume, the shape approximate.
    if (hs) {
      int ax = 0;
      double best = -1.0;
      for (int c = 0; c < dim; ++c) {
        const double span = std::abs(u[0] * F[a](0, c) + u[1] * F[a](1, c) + u[2] * F[a](2, c)) * hs[a][c];
        if (span > best) {
          best = span;
          ax = c;
        }
      }
      hs[a][ax] *= 0.5;
      hs[b] = hs[a];
    }
    // The cell halves along u: S' = (I - u u^T / 2) S.
    Mat3 P = Mat3::identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) P(r, c) -= 0.5 * u[r] * u[c];
    ext[a] = P * ext[a];
    ext[b] = ext[a];
    id[b] = next_id++;
  }
  apply_split_increments(pts, increments, which, n, share, state);
  for (const std::string& name : extensive) {
    if (!pts.has(name)) continue;
    const int nc = pts.info(name).ncomp;
    double* f = pts.real(name);
    for (Index i = 0; i < m; ++i)
      for (int c = 0; c < nc; ++c) {
        f[which[i] * nc + c] *= share[2 * i];
        f[(n + i) * nc + c] *= share[2 * i + 1];
      }
  }
  // The current volume follows from the reference one, V = J V0 (Algorithm 1 line 15).
  for (Index i = 0; i < m; ++i)
    for (const Index p : {which[i], n + i}) vol[p] = det(F[p]) * vol0[p];
  return which;
}

bool nodes_crowded(const NodeCloud& nodes, double distance, int dim) {
  const Index nn = nodes.size();
  if (nn == 0) return false;
  const CellBins bins(nodes.x.data(), nn, distance, dim);
  const double d2 = distance * distance;
  bool crowded = false;
  for (Index a = 0; a < nn && !crowded; ++a) {
    if (!(nodes.mass[a] > 0.0)) continue;
    bins.visit(nodes.x[a], [&](Index b) {
      if (b <= a || nodes.body[b] != nodes.body[a] || !(nodes.mass[b] > 0.0)) return;
      Vec3 d = nodes.x[a] - nodes.x[b];
      if (dim == 2) d[2] = 0.0;
      if (dot(d, d) < d2) crowded = true;
    });
  }
  return crowded;
}

}  // namespace ballista::otm
