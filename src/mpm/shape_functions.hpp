#pragma once
// MPM shape functions: weights N_I(x_p) and gradients dN_I/dx of the grid nodes a particle touches.
//
// Hot path (called per particle per transfer, ~1e7 times per second): everything here is inline,
// allocation-free and free of virtual dispatch. Each kernel evaluates the 1-D weights once per
// axis (or per CPDI corner and axis) and forms the 2-D/3-D stencil as a tensor product.
//
// Conventions: node (i,j,k) sits at g.origin + h (i,j,k); the particle's cell along an axis is
// c = floor((x - origin)/h) and t = (x - origin)/h - c in [0,1) is its offset inside that cell.
// In 2D the z coordinate of x is ignored, nodes use k = 0 and grad[.][2] = 0.
// The caller guarantees that every reached node exists (ghost layers, see stencil_reach);
// this is asserted in debug builds only.
#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "mpm/grid_geometry.hpp"

namespace ballista {

enum class ShapeKind { Linear, Gimp, Cpdi, BSpline3 };

/// "linear" | "gimp" | "cpdi" | "bspline3" (case-insensitive); throws ballista::Error listing the
/// valid names otherwise.
ShapeKind parse_shape_kind(const std::string& name);
const char* shape_kind_name(ShapeKind kind);
/// All valid names, in enum order (for `ballista info`).
std::vector<std::string> shape_kind_names();
/// One line, including the source paper.
std::string shape_kind_description(ShapeKind kind);

/// Weights and gradients of the nodes one particle touches (duplicates allowed for CPDI; the
/// caller accumulates). Entries may carry zero weight (GIMP and B-spline windows are fixed-size).
template <int Dim>
struct Stencil {
  static constexpr int kMax = Dim == 3 ? 64 : 16;
  int count = 0;
  Index node[kMax];  ///< GridGeometry::node_index(i,j,k) (k = 0 in 2D)
  double w[kMax];
  Vec3 grad[kMax];  ///< dN/dx in 1/m; grad[.][2] = 0 in 2D
};

/// Bound on the node offset a stencil can reach from the particle's cell: on every axis, every
/// node index n of the stencil satisfies |n - c| <= stencil_reach(...), c = cell_of(x, axis).
/// (Linear: n in {c, c+1} -> 1. GIMP with lp <= h/2 and cubic B-spline: n in c-1..c+2 -> 2.)
/// For CPDI pass the largest |corner - centre| component in cells, e = max_k sum_j |r_kj| / h
/// (computed by the caller). In exact arithmetic a corner sits at t + delta cells from c with
/// t in [0,1), |delta| <= e, so nodes lie in [c - ceil(e), c + ceil(e) + 1]. Round-off can push a
/// corner that lies within an ulp of a cell face into the next cell (this happens when e is an
/// integer, e.g. r = diag(h) with x one ulp below a face), so we return floor(e + 1e-6) + 2: equal
/// to ceil(e) + 1 for non-integer e, one more for e within 1e-6 cells of an integer. (0.5 -> 2.)
inline int stencil_reach(ShapeKind kind, double cpdi_extent_cells = 0.5) {
  switch (kind) {
    case ShapeKind::Linear:
      return 1;
    case ShapeKind::Gimp:
      return 2;
    case ShapeKind::BSpline3:
      return 2;
    case ShapeKind::Cpdi:
      return static_cast<int>(
                 std::floor((cpdi_extent_cells < 0 ? 0.0 : cpdi_extent_cells) + 1e-6)) +
             2;
  }
  return 2;
}

/// Node index meaning "no bounding face" for the cubic B-spline (SplineFaces, bspline3_1d).
inline constexpr int kNoSplineFace = -(1 << 29);

namespace shape_detail {

/// Per-axis window: first node index and the 1-D weights/derivatives (derivative in 1/m).
template <int N>
struct Axis1D {
  int first;
  double w[N];
  double dw[N];
};

/// Cell index and in-cell offset t in [0,1) of coordinate x along one axis. Divides by h exactly
/// as GridGeometry::cell_of does, so c is bitwise the caller's particle cell (a multiply by 1/h
/// could disagree within an ulp of a face and break the stencil_reach bound by one).
inline void locate(double x, double origin, double h, int& c, double& t) {
  assert(std::isfinite(x) && "non-finite particle position");
  const double s = (x - origin) / h;
  const double f = std::floor(s);
  c = static_cast<int>(f);
  t = s - f;
}
/// Same with a multiply by 1/h: for CPDI corners, whose cells need not match cell_of bitwise
/// (stencil_reach keeps slack for round-off at integer extents).
inline void locate_fast(double x, double origin, double inv_h, int& c, double& t) {
  assert(std::isfinite(x) && "non-finite CPDI corner position");
  const double s = (x - origin) * inv_h;
  const double f = std::floor(s);
  c = static_cast<int>(f);
  t = s - f;
}

/// Linear hat (standard MPM; Sulsky, Chen & Schreyer, CMAME 118 (1994) 179):
/// nodes c, c+1 with N = 1 - t, t and dN/dx = -1/h, +1/h.
inline void linear_1d(double x, double origin, double h, double inv_h, Axis1D<2>& a) {
  double t;
  locate(x, origin, h, a.first, t);
  a.w[0] = 1.0 - t;
  a.w[1] = t;
  a.dw[0] = -inv_h;
  a.dw[1] = inv_h;
}

/// uGIMP 1-D weight of one node at signed distance d = x_p - x_I, for particle half-length
/// lp in (0, h/2] (Bardenhagen & Kober, "The generalized interpolation material point method",
/// CMES 5 (2004) 477, eq. for the linear-hat / piecewise-constant particle characteristic
/// function). In units u = |d|/h, a = lp/h:
///   u < a        : S = 1 - (u^2 + a^2)/(2a)      dS/dd = -d/(h lp)
///   u < 1 - a    : S = 1 - u                     dS/dd = -sign(d)/h
///   u < 1 + a    : S = (1 + a - u)^2/(4a)        dS/dd = -sign(d)(1 + a - u)/(2 a h)
///   otherwise    : 0
/// These are (1/2lp) * integral of the hat over [x_p - lp, x_p + lp] and its exact derivative.
inline void gimp_node_1d(double u_signed, double a, double inv_a, double inv_h, double& w,
                         double& dw) {
  // Branch-free: region boundaries fall on random t, so branches mispredict, and GCC turns
  // ternaries / bool-to-double conversions here into jumps. All three pieces are finite
  // (a >= 1e-12, u < 2, r clamped at 0 beyond the support) and exactly one region mask is set
  // (a <= 1/2 gives u < a => u < 1 - a), so the result is selected bitwise with integer masks.
  const double u = std::fabs(u_signed);
  const double sgn = std::copysign(1.0, u_signed);
  const double w1 = 1.0 - 0.5 * (u * u + a * a) * inv_a;
  const double d1 = -u_signed * inv_a;
  const double w2 = 1.0 - u;
  const double d2 = -sgn;
  const std::uint64_t k1 = -static_cast<std::uint64_t>(u < a);
  const std::uint64_t k12 = -static_cast<std::uint64_t>(u < 1.0 - a);
  const std::uint64_t k4 = -static_cast<std::uint64_t>(u < 1.0 + a);  // inside the support
  const double r = 1.0 + a - u;
  const double w3 = 0.25 * r * r * inv_a;
  const double d3 = -0.5 * sgn * r * inv_a;
  const std::uint64_t k2 = k12 & ~k1, k3 = k4 & ~k12;
  w = std::bit_cast<double>((std::bit_cast<std::uint64_t>(w1) & k1) |
                            (std::bit_cast<std::uint64_t>(w2) & k2) |
                            (std::bit_cast<std::uint64_t>(w3) & k3));
  dw = std::bit_cast<double>((std::bit_cast<std::uint64_t>(d1) & k1) |
                             (std::bit_cast<std::uint64_t>(d2) & k2) |
                             (std::bit_cast<std::uint64_t>(d3) & k3)) *
       inv_h;
}

/// uGIMP on one axis: three nodes cover the support |d| < h + lp when lp <= h/2
/// (node c-1 can be non-zero only for t < a, node c+2 only for t > 1 - a, never both).
/// a = lp/h is clamped to [1e-12, 1/2]: a -> 0 reduces to the linear hat without 0/0.
inline void gimp_1d(double x, double origin, double h, double inv_h, double a, Axis1D<3>& ax) {
  int c;
  double t;
  locate(x, origin, h, c, t);
  const int lo = -static_cast<int>(t < 0.5);  // window c-1..c+1 or c..c+2 (no branch: t is random)
  ax.first = c + lo;
  const double inv_a = 1.0 / a;
  for (int n = 0; n < 3; ++n) gimp_node_1d(t - (lo + n), a, inv_a, inv_h, ax.w[n], ax.dw[n]);
}

/// Uniform cubic B-spline, support 4h, C2 (de Boor, "A Practical Guide to Splines", Springer 1978,
/// ch. IX; used in MPM by Steffen, Kirby & Berzins, IJNME 76 (2008) 922). Node-centred kernel
/// N(u) = |u|^3/2 - u^2 + 2/3 (|u| < 1), (2 - |u|)^3/6 (1 <= |u| < 2). For t in [0,1) the nodes
/// c-1..c+2 sit at u = t+1, t, t-1, t-2, giving the four uniform B-spline segments below.
///
/// Boundary-modified basis (Steffen, Wallstedt, Guilkey, Kirby & Berzins, "Examination and
/// analysis of implementation choices within the material point method (MPM)", CMES 31 (2008)
/// 107, section on cubic B-splines; the same piecewise cubics are the "boundary-modified cubic
/// B-spline" of later MPM codes). At a bounding face with node index `lo` (`hi`), the node beyond
/// the face is removed by linear extrapolation, N'_lo = N_lo + 2 N_(lo-1),
/// N'_(lo+1) = N_(lo+1) - N_(lo-1), N'_(lo-1) = 0 (mirrored at `hi`). Only the face cell changes;
/// there, with t = (x - x_lo)/h in [0,1] (s = 1 - t at the high face, node order reversed):
///   N'_lo     = 1 - t + t^3/6            dN'/dx = (t^2/2 - 1)/h
///   N'_(lo+1) = t - t^3/3                dN'/dx = (1 - t^2)/h
///   N_(lo+2)  = t^3/6  (unchanged)       dN /dx = t^2/(2h)
/// In node units (xi = (x - x_I)/h) this is Steffen et al.'s face-node function
/// xi^3/6 - xi + 1 on [0,1] (uniform on [1,2]) and first-interior-node function
/// -xi^3/3 - xi^2 + 2/3 on [-1,0] (uniform elsewhere). Properties: partition of unity and exact
/// linear reproduction with the real node positions (the extrapolation keeps them), N'_lo(face)
/// = 1 and every other function 0 there (interpolatory at the face: a constrained face node
/// constrains the material at the face), non-negative, C2 inside the box (the face cell's
/// pieces meet the uniform ones with equal value, slope and curvature at t = 1), and N'' = 0 at
/// the face (a natural-spline end: quadratics are not reproduced in the face cell). It is not the
/// open-knot-vector (clamped) basis of isogeometric analysis, whose control points are not at
/// the nodes (Greville abscissae 0, h/3, h, ...).
///
/// `lo`/`hi`: node indices of the bounding faces on this axis, or kNoSplineFace. A coordinate
/// outside the box on a bounded side is evaluated with the face cell's polynomials (extrapolated),
/// so the node beyond the face never carries weight; that happens only for surface-load points
/// (particles outside the box stop the run or are deleted first).
inline void bspline3_1d(double x, double origin, double h, double inv_h, Axis1D<4>& a,
                        int lo = kNoSplineFace, int hi = kNoSplineFace) {
  int c;
  double t;
  locate(x, origin, h, c, t);
  // Rare (face cells only) and well predicted: the uniform path is unchanged bitwise.
  if (c < lo) { t += c - lo; c = lo; }
  if (hi != kNoSplineFace && c > hi - 1) { t += c - (hi - 1); c = hi - 1; }
  const bool at_lo = c == lo, at_hi = hi != kNoSplineFace && c == hi - 1;
  a.first = c - 1;
  const double t2 = t * t, t3 = t2 * t, s = 1.0 - t;
  a.w[0] = s * s * s * (1.0 / 6.0);
  a.w[1] = 0.5 * t3 - t2 + 2.0 / 3.0;
  a.w[2] = -0.5 * t3 + 0.5 * t2 + 0.5 * t + 1.0 / 6.0;
  a.w[3] = t3 * (1.0 / 6.0);
  a.dw[0] = -0.5 * s * s * inv_h;
  a.dw[1] = (1.5 * t2 - 2.0 * t) * inv_h;
  a.dw[2] = (-1.5 * t2 + t + 0.5) * inv_h;
  a.dw[3] = 0.5 * t2 * inv_h;
  if (at_lo && at_hi) {
    // A one-cell axis: both extrapolations at once leave N_lo + 2 N_(lo-1) - N_(lo+2) = 1 - t and
    // N_(lo+1) + 2 N_(lo+2) - N_(lo-1) = t, the linear hat (written directly: exact, >= 0).
    a.w[0] = a.w[3] = a.dw[0] = a.dw[3] = 0.0;
    a.w[1] = s;
    a.w[2] = t;
    a.dw[1] = -inv_h;
    a.dw[2] = inv_h;
  } else if (at_lo) {  // window lo-1..lo+2: the face cell (closed forms above)
    a.w[0] = 0.0;
    a.w[1] = 1.0 - t + t3 * (1.0 / 6.0);
    a.w[2] = t - t3 * (1.0 / 3.0);
    a.dw[0] = 0.0;
    a.dw[1] = (0.5 * t2 - 1.0) * inv_h;
    a.dw[2] = (1.0 - t2) * inv_h;
  } else if (at_hi) {  // window hi-2..hi+1, mirror image (x -> -x, t -> s)
    const double s2 = s * s, s3 = s2 * s;
    a.w[1] = s - s3 * (1.0 / 3.0);
    a.w[2] = 1.0 - s + s3 * (1.0 / 6.0);
    a.w[3] = 0.0;
    a.dw[1] = (s2 - 1.0) * inv_h;
    a.dw[2] = (1.0 - 0.5 * s2) * inv_h;
    a.dw[3] = 0.0;
  }
}

inline Index stride_y(const GridGeometry& g) {
  return g.nodes[0];
}
inline Index stride_z(const GridGeometry& g) {
  return static_cast<Index>(g.nodes[0]) * g.nodes[1];
}

#ifndef NDEBUG
inline void check_node(const GridGeometry& g, int i, int j, int k) {
  assert(i >= 0 && i < g.nodes[0] && j >= 0 && j < g.nodes[1] && k >= 0 && k < g.nodes[2] &&
         "shape function stencil reaches outside the grid block (missing ghost layers?)");
}
#endif

/// Node count per axis known at compile time (full windows: the loops unroll).
template <int N>
struct FixedCount {
  constexpr int operator[](int) const { return N; }
};
/// Node count per axis known at run time (GIMP windows trimmed to the nodes with support).
struct RuntimeCount {
  int n[3] = {0, 0, 0};
  int operator[](int d) const { return n[d]; }
};

/// Tensor product of per-axis windows into s (appending from s.count), using the first n[d]
/// nodes of each axis window (n[d] <= N).
template <int Dim, int N, class Count>
inline void tensor_product_n(const GridGeometry& g, const Axis1D<N>* ax, const Count& n, Stencil<Dim>& s) {
  static_assert(Dim == 2 || Dim == 3);
  const Index sy = stride_y(g);
  int m = s.count;
  if constexpr (Dim == 2) {
#ifndef NDEBUG
    check_node(g, ax[0].first, ax[1].first, 0);
    check_node(g, ax[0].first + n[0] - 1, ax[1].first + n[1] - 1, 0);
#endif
    const Index base = static_cast<Index>(ax[1].first) * sy + ax[0].first;
    for (int b = 0; b < n[1]; ++b) {
      const Index row = base + b * sy;
      const double wy = ax[1].w[b], dwy = ax[1].dw[b];
      for (int a = 0; a < n[0]; ++a, ++m) {
        s.node[m] = row + a;
        s.w[m] = ax[0].w[a] * wy;
        s.grad[m] = Vec3{{ax[0].dw[a] * wy, ax[0].w[a] * dwy, 0.0}};
      }
    }
  } else {
#ifndef NDEBUG
    check_node(g, ax[0].first, ax[1].first, ax[2].first);
    check_node(g, ax[0].first + n[0] - 1, ax[1].first + n[1] - 1, ax[2].first + n[2] - 1);
#endif
    const Index sz = stride_z(g);
    const Index base =
        static_cast<Index>(ax[2].first) * sz + static_cast<Index>(ax[1].first) * sy + ax[0].first;
    for (int c = 0; c < n[2]; ++c) {
      const double wz = ax[2].w[c], dwz = ax[2].dw[c];
      for (int b = 0; b < n[1]; ++b) {
        const Index row = base + c * sz + b * sy;
        const double wy = ax[1].w[b], dwy = ax[1].dw[b];
        const double wyz = wy * wz, dyz = dwy * wz, yzd = wy * dwz;
        for (int a = 0; a < n[0]; ++a, ++m) {
          s.node[m] = row + a;
          s.w[m] = ax[0].w[a] * wyz;
          s.grad[m] = Vec3{{ax[0].dw[a] * wyz, ax[0].w[a] * dyz, ax[0].w[a] * yzd}};
        }
      }
    }
  }
  s.count = m;
}

/// Full N-node windows on every axis.
template <int Dim, int N>
inline void tensor_product(const GridGeometry& g, const Axis1D<N>* ax, Stencil<Dim>& s) {
  tensor_product_n<Dim, N>(g, ax, FixedCount<N>{}, s);
}

/// Drops a zero-weight end node of a 3-node GIMP window (the particle domain lies inside one
/// cell on this axis), leaving 2 nodes; returns the node count kept (2 or 3). Weights outside the
/// support are exactly 0, so nothing is lost.
inline int trim_gimp_window(Axis1D<3>& a) {
  if (a.w[0] == 0.0 && a.dw[0] == 0.0) {
    a.first += 1;
    a.w[0] = a.w[1]; a.dw[0] = a.dw[1];
    a.w[1] = a.w[2]; a.dw[1] = a.dw[2];
    return 2;
  }
  return (a.w[2] == 0.0 && a.dw[2] == 0.0) ? 2 : 3;
}

}  // namespace shape_detail

/// Standard MPM linear hat functions: 2^Dim nodes (c, c+1 per axis).
/// The stencils run per point in every transfer loop and are always inlined there: left to its
/// heuristics, GCC put them out of line once the solver's unit grew past its growth limit, and
/// the call alone cost the uniform block bench 8 %.
template <int Dim>
[[gnu::always_inline]] inline void linear_stencil(const GridGeometry& g, const Vec3& x, Stencil<Dim>& s) {
  const double inv_h = 1.0 / g.h;
  shape_detail::Axis1D<2> ax[Dim];
  for (int d = 0; d < Dim; ++d) shape_detail::linear_1d(x[d], g.origin[d], g.h, inv_h, ax[d]);
  s.count = 0;
  shape_detail::tensor_product<Dim, 2>(g, ax, s);
}

/// A GIMP stencil before its tensor product: the trimmed window of each axis. The 1-D weights are
/// most of a GIMP stencil's cost and depend only on the position and the half-lengths, so a step
/// whose passes all map from the same positions computes them once (MpmSolver::point_stencil).
template <int Dim>
struct GimpWindows {
  shape_detail::Axis1D<3> ax[Dim];
  shape_detail::RuntimeCount n;
};

/// Uniform GIMP (Bardenhagen & Kober 2004), lp = particle half-length per axis, 0 < lp <= h/2
/// (values are clamped into that range; lp > h/2 needs a wider window and is asserted against in
/// debug builds): the windows of gimp_stencil.
template <int Dim>
[[gnu::always_inline]] inline void gimp_windows(const GridGeometry& g, const Vec3& x, const Vec3& lp, GimpWindows<Dim>& w) {
  const double inv_h = 1.0 / g.h;
  for (int d = 0; d < Dim; ++d) {
    assert(lp[d] <= 0.5 * g.h * (1.0 + 1e-12) && "GIMP particle half-length exceeds h/2");
    const double a = std::min(std::max(lp[d] * inv_h, 1e-12), 0.5);
    shape_detail::gimp_1d(x[d], g.origin[d], g.h, inv_h, a, w.ax[d]);
    w.n.n[d] = shape_detail::trim_gimp_window(w.ax[d]);
  }
}

/// The stencil of GIMP windows. Only nodes with support are listed: 2 per axis while the particle
/// domain lies inside one cell (the common case at 2 particles per cell), 3 when it straddles a
/// node.
template <int Dim>
inline void stencil_from_windows(const GridGeometry& g, const GimpWindows<Dim>& w, Stencil<Dim>& s) {
  s.count = 0;
  shape_detail::tensor_product_n<Dim, 3>(g, w.ax, w.n, s);
}

/// Uniform GIMP: between 2^Dim and 3^Dim nodes (zero-weight window ends are dropped).
template <int Dim>
inline void gimp_stencil(const GridGeometry& g, const Vec3& x, const Vec3& lp, Stencil<Dim>& s) {
  GimpWindows<Dim> w;
  gimp_windows<Dim>(g, x, lp, w);
  stencil_from_windows<Dim>(g, w, s);
}

/// The grid faces at which the cubic B-spline basis is boundary-modified (Steffen et al. 2008,
/// bspline3_1d): per axis, the node index of the low / high face, or kNoSplineFace where the
/// uniform basis continues onto the ghost layers. The default bounds nothing.
struct SplineFaces {
  int lo[3] = {kNoSplineFace, kNoSplineFace, kNoSplineFace};
  int hi[3] = {kNoSplineFace, kNoSplineFace, kNoSplineFace};
};

/// Cubic B-spline (de Boor 1978; Steffen, Kirby & Berzins 2008), support 4h: 4^Dim nodes
/// c-1..c+2 per axis (the node beyond a bounding face of `faces` gets weight 0). Uniform where
/// `faces` bounds nothing: the grid's ghost layers provide the outer nodes there, so linear
/// fields are reproduced everywhere the stencil is complete; boundary-modified (Steffen,
/// Wallstedt et al., CMES 31 (2008) 107) in the face cell of a bounded face.
template <int Dim>
inline void bspline3_stencil(const GridGeometry& g, const Vec3& x, Stencil<Dim>& s,
                             const SplineFaces& faces = {}) {
  const double inv_h = 1.0 / g.h;
  shape_detail::Axis1D<4> ax[Dim];
  for (int d = 0; d < Dim; ++d)
    shape_detail::bspline3_1d(x[d], g.origin[d], g.h, inv_h, ax[d], faces.lo[d], faces.hi[d]);
  s.count = 0;
  shape_detail::tensor_product<Dim, 4>(g, ax, s);
}

/// CPDI1 (Sadeghirad, Brannon & Burghardt, "A convected particle domain interpolation technique to
/// extend applicability of the material point method for problems involving massive deformations",
/// IJNME 86 (2011) 1435). The particle domain is the parallelogram/parallelepiped
/// x + sum_j xi_j r_j, xi in [-1,1]^Dim, with r_j = column j of r (r_ij = r.a[3i+j]); in 2D only
/// r1, r2 and their x,y components are used. With S_I the linear hat and corners
/// x_alpha = x + sum_j xi_alpha_j r_j (xi_alpha in {-1,1}^Dim):
///   w_I    = 2^-Dim sum_alpha S_I(x_alpha)
///   grad_I = (1/V) sum_alpha S_I(x_alpha) (integral over the domain of grad M_alpha)
///          = 2^-Dim J^{-T} sum_alpha S_I(x_alpha) xi_alpha,   J = [r_1 .. r_Dim], V = 2^Dim det J,
/// i.e. the volume average of the gradient of the (bi/tri)linear interpolant of S_I between the
/// corners. In 2D this is the paper's closed form
///   grad_I = (1/V){[S_I(x1) - S_I(x3)](r1y - r2y, r2x - r1x) + [S_I(x2) - S_I(x4)](r1y + r2y, -r1x
///   - r2x)},
/// V = 4 (r1 x r2); in 3D J^{-T} xi = (xi_1 r2 x r3 + xi_2 r3 x r1 + xi_3 r1 x r2)/det J (the
/// paper's parallelepiped form). The signed det J is used, so either orientation is correct;
/// r must be non-degenerate. Each corner contributes its 2^Dim linear nodes (4^Dim entries in
/// total, duplicates included).
/// CPDI1 with the corners' cells found by `locate(d, x_d, c, t)` (cell index and in-cell offset
/// along axis d): the uniform grid's below, a graded grid's in mpm/graded_shape_functions.hpp.
template <int Dim, class Locate>
inline void cpdi_stencil_located(const GridGeometry& g, const Vec3& x, const Mat3& r, Stencil<Dim>& s,
                                 const Locate& locate) {
  static_assert(Dim == 2 || Dim == 3);
  constexpr int kCorners = 1 << Dim;
  constexpr double kAvg = 1.0 / kCorners;
  // Rows of kAvg * J^{-T}: gradient of corner alpha is G * xi_alpha.
  double G[Dim][Dim];
  if constexpr (Dim == 2) {
    const double r1x = r.a[0], r1y = r.a[3], r2x = r.a[1], r2y = r.a[4];
    const double detJ = r1x * r2y - r2x * r1y;
    assert(detJ != 0.0 && "degenerate CPDI particle domain");
    const double f = kAvg / detJ;
    // J = [[r1x, r2x], [r1y, r2y]],  J^{-T} = (1/det) [[r2y, -r1y], [-r2x, r1x]].
    G[0][0] = f * r2y;
    G[0][1] = -f * r1y;
    G[1][0] = -f * r2x;
    G[1][1] = f * r1x;
  } else {
    const Mat3 C = cofactor(r);  // det(J) J^{-T}
    const double detJ = det(r);
    assert(detJ != 0.0 && "degenerate CPDI particle domain");
    const double f = kAvg / detJ;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) G[i][j] = f * C.a[3 * i + j];
  }
  const Index sy = shape_detail::stride_y(g);
  const Index sz = Dim == 3 ? shape_detail::stride_z(g) : 0;
  int m = 0;
  for (int alpha = 0; alpha < kCorners; ++alpha) {
    double xi[Dim];
    for (int j = 0; j < Dim; ++j) xi[j] = (alpha >> j) & 1 ? 1.0 : -1.0;
    // Corner position, its linear 1-D weights per axis, and its gradient factor G xi_alpha.
    int c[3] = {0, 0, 0};
    double t[3] = {0.0, 0.0, 0.0};
    double ga[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < Dim; ++d) {
      double xc = x[d];
      for (int j = 0; j < Dim; ++j) xc += xi[j] * r.a[3 * d + j];
      locate(d, xc, c[d], t[d]);
      for (int j = 0; j < Dim; ++j) ga[d] += G[d][j] * xi[j];
    }
#ifndef NDEBUG
    shape_detail::check_node(g, c[0], c[1], Dim == 3 ? c[2] : 0);
    shape_detail::check_node(g, c[0] + 1, c[1] + 1, Dim == 3 ? c[2] + 1 : 0);
#endif
    const double wx[2] = {1.0 - t[0], t[0]}, wy[2] = {1.0 - t[1], t[1]};
    const double wz[2] = {Dim == 3 ? 1.0 - t[2] : 1.0, Dim == 3 ? t[2] : 0.0};
    const Index base = static_cast<Index>(c[2]) * sz + static_cast<Index>(c[1]) * sy + c[0];
    for (int k = 0; k < (Dim == 3 ? 2 : 1); ++k)
      for (int j = 0; j < 2; ++j) {
        const double wyz = wy[j] * wz[k];
        const Index row = base + k * sz + j * sy;
        for (int i = 0; i < 2; ++i, ++m) {
          const double S = wx[i] * wyz;  // linear hat S_I(x_alpha)
          s.node[m] = row + i;
          s.w[m] = kAvg * S;
          s.grad[m] = Vec3{{S * ga[0], S * ga[1], S * ga[2]}};
        }
      }
  }
  s.count = m;
}

template <int Dim>
inline void cpdi_stencil(const GridGeometry& g, const Vec3& x, const Mat3& r, Stencil<Dim>& s) {
  const double inv_h = 1.0 / g.h;
  cpdi_stencil_located<Dim>(g, x, r, s, [&](int d, double xc, int& c, double& t) {
    shape_detail::locate_fast(xc, g.origin[d], inv_h, c, t);
  });
}

}  // namespace ballista
