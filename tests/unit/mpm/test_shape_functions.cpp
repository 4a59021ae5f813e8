// MPM shape functions: partition of unity, linear completeness, gradient consistency, the
// CPDI/GIMP equivalence condition, stencil reach and node counts.
//
// Tolerances: identities that hold exactly in real arithmetic are checked against a round-off
// bound (n + 8) * eps * scale, where n is the number of stencil entries summed and `scale` is the
// sum of the magnitudes of the summed terms (standard recursive-summation bound, Higham,
// "Accuracy and Stability of Numerical Algorithms", 2nd ed., eq. 4.4; the +8 covers the few
// rounded products that form each term). Finite-difference checks state their own bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

#include "core/error.hpp"
#include "mpm/shape_functions.hpp"

namespace test_shape_functions {

using namespace ballista;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kN = 24;  // nodes per axis: particles live in cells 8..15, stencils reach <= 5 cells

double roundoff_bound(int n, double scale) {
  return (n + 8) * kEps * scale;
}

GridGeometry make_grid(int dim) {
  GridGeometry g;
  g.origin = Vec3{{-0.3, 0.7, 1.1}};
  g.h = 0.25;
  g.dim = dim;
  g.nodes[0] = kN;
  g.nodes[1] = kN;
  g.nodes[2] = dim == 3 ? kN : 1;
  return g;
}

void decode(const GridGeometry& g, Index n, int ijk[3]) {
  ijk[0] = static_cast<int>(n % g.nodes[0]);
  ijk[1] = static_cast<int>((n / g.nodes[0]) % g.nodes[1]);
  ijk[2] = static_cast<int>(n / (static_cast<Index>(g.nodes[0]) * g.nodes[1]));
}

/// Random point in cells 8..15 of each axis (z = origin z in 2D, which the kernels ignore anyway).
Vec3 random_point(const GridGeometry& g, int dim, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(8.0, 16.0);
  Vec3 x = g.origin;
  for (int d = 0; d < dim; ++d) x[d] += u(rng) * g.h;
  if (dim == 2) x[2] = 123.0;  // must be ignored
  return x;
}

/// r = F diag(lp): columns r_j = F (lp_j e_j), with F = I + random perturbation, det F >= 0.3.
Mat3 random_cpdi_r(const GridGeometry& g, int dim, std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), ul(0.1, 0.5);
  for (;;) {
    Mat3 F = Mat3::identity();
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) F(i, j) += amplitude * u(rng);
    const double detF = dim == 3 ? det(F) : F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0);
    if (detF < 0.3) continue;
    const Mat3 L = Mat3::diag(ul(rng) * g.h, ul(rng) * g.h, dim == 3 ? ul(rng) * g.h : 0.0);
    return F * L;
  }
}

/// Largest |corner - centre| component in cells: max_k sum_j |r_kj| / h.
double cpdi_extent(const GridGeometry& g, int dim, const Mat3& r) {
  double e = 0.0;
  for (int k = 0; k < dim; ++k) {
    double s = 0.0;
    for (int j = 0; j < dim; ++j) s += std::fabs(r(k, j));
    e = std::max(e, s / g.h);
  }
  return e;
}

struct Params {
  Vec3 lp;  // GIMP
  Mat3 r;   // CPDI
};

template <int Dim>
void compute(ShapeKind kind, const GridGeometry& g, const Vec3& x, const Params& p,
             Stencil<Dim>& s) {
  switch (kind) {
    case ShapeKind::Linear:
      linear_stencil<Dim>(g, x, s);
      break;
    case ShapeKind::Gimp:
      gimp_stencil<Dim>(g, x, p.lp, s);
      break;
    case ShapeKind::Cpdi:
      cpdi_stencil<Dim>(g, x, p.r, s);
      break;
    case ShapeKind::BSpline3:
      bspline3_stencil<Dim>(g, x, s);
      break;
  }
}

template <int Dim>
Params random_params(const GridGeometry& g, std::mt19937& rng) {
  std::uniform_real_distribution<double> ul(0.0, 0.5);
  Params p;
  p.lp = Vec3{{ul(rng) * g.h, ul(rng) * g.h, ul(rng) * g.h}};
  p.r = random_cpdi_r(g, Dim, rng, 0.4);
  return p;
}

/// Node -> (weight, gradient), duplicates (CPDI) accumulated.
struct Merged {
  double w = 0.0;
  Vec3 grad;
};
template <int Dim>
std::map<Index, Merged> merge(const Stencil<Dim>& s) {
  std::map<Index, Merged> m;
  for (int q = 0; q < s.count; ++q) {
    m[s.node[q]].w += s.w[q];
    m[s.node[q]].grad += s.grad[q];
  }
  return m;
}

constexpr ShapeKind kKinds[] = {ShapeKind::Linear, ShapeKind::Gimp, ShapeKind::Cpdi,
                                ShapeKind::BSpline3};

// ---------------------------------------------------------------------------------------------

template <int Dim>
void check_node_counts() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(1);
  Stencil<Dim> s;
  const Params p = random_params<Dim>(g, rng);
  const Vec3 x = random_point(g, Dim, rng);
  // GIMP lists 3 nodes on an axis where the particle domain [x - lp, x + lp] straddles a node
  // and 2 where it lies inside one cell (zero-weight ends dropped).
  int gimp = 1;
  for (int d = 0; d < Dim; ++d) {
    const double lo = (x[d] - p.lp[d] - g.origin[d]) / g.h, hi = (x[d] + p.lp[d] - g.origin[d]) / g.h;
    gimp *= std::floor(lo) == std::floor(hi) ? 2 : 3;
  }
  const int expected[4] = {1 << Dim, gimp, Dim == 3 ? 64 : 16, Dim == 3 ? 64 : 16};
  for (int k = 0; k < 4; ++k) {
    compute<Dim>(kKinds[k], g, x, p, s);
    EXPECT_EQ(s.count, expected[k]) << shape_kind_name(kKinds[k]) << " Dim=" << Dim;
    EXPECT_LE(s.count, Stencil<Dim>::kMax);
  }
  // A domain inside one cell on every axis: exactly 2^Dim GIMP nodes.
  Params q = p;
  Vec3 xc;
  for (int d = 0; d < Dim; ++d) { q.lp[d] = 0.25 * g.h; xc[d] = g.origin[d] + (3.25 + 0.5 * d * 0.1) * g.h; }
  compute<Dim>(ShapeKind::Gimp, g, xc, q, s);
  EXPECT_EQ(s.count, 1 << Dim);
}

TEST(ShapeFunctions, NodeCounts) {
  check_node_counts<2>();
  check_node_counts<3>();
}

// Sum_I w_I = 1 and Sum_I grad_I = 0 (all kinds), w_I >= 0, and in 2D the z parts vanish.
template <int Dim>
void check_partition_of_unity() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(2 + Dim);
  Stencil<Dim> s;
  for (int trial = 0; trial < 2000; ++trial) {
    const Params p = random_params<Dim>(g, rng);
    const Vec3 x = random_point(g, Dim, rng);
    for (ShapeKind kind : kKinds) {
      compute<Dim>(kind, g, x, p, s);
      double sw = 0.0, sw_abs = 0.0, g_abs = 0.0;
      Vec3 sg;
      for (int q = 0; q < s.count; ++q) {
        EXPECT_GE(s.w[q], 0.0) << shape_kind_name(kind);
        sw += s.w[q];
        sw_abs += std::fabs(s.w[q]);
        sg += s.grad[q];
        g_abs += norm(s.grad[q]);
        if (Dim == 2) {
          EXPECT_EQ(s.grad[q][2], 0.0);
          EXPECT_LT(s.node[q], static_cast<Index>(g.nodes[0]) * g.nodes[1]);
        }
      }
      EXPECT_NEAR(sw, 1.0, roundoff_bound(s.count, sw_abs)) << shape_kind_name(kind);
      // Each gradient entry carries a few rounded products; g_abs is the summed magnitude.
      EXPECT_LE(norm(sg), roundoff_bound(s.count, g_abs))
          << shape_kind_name(kind) << " trial " << trial;
    }
  }
}

TEST(ShapeFunctions, PartitionOfUnityAndNonNegative2D) {
  check_partition_of_unity<2>();
}
TEST(ShapeFunctions, PartitionOfUnityAndNonNegative3D) {
  check_partition_of_unity<3>();
}

// Linear completeness: Sum_I w_I x_I = x and Sum_I grad_I (x) x_I = I. Holds for linear, GIMP and
// CPDI everywhere, and for the uniform cubic B-spline wherever its 4 nodes per axis exist (the grid
// here has them; near a physical boundary without ghost nodes it would not).
template <int Dim>
void check_linear_reproduction() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(10 + Dim);
  Stencil<Dim> s;
  for (int trial = 0; trial < 2000; ++trial) {
    const Params p = random_params<Dim>(g, rng);
    const Vec3 x = random_point(g, Dim, rng);
    for (ShapeKind kind : kKinds) {
      compute<Dim>(kind, g, x, p, s);
      Vec3 xr;
      Mat3 A;
      double wx_abs = 0.0, gx_abs = 0.0;
      for (int q = 0; q < s.count; ++q) {
        int ijk[3];
        decode(g, s.node[q], ijk);
        const Vec3 xn = g.node_position(ijk[0], ijk[1], ijk[2]);
        xr += s.w[q] * xn;
        wx_abs += std::fabs(s.w[q]) * norm(xn);
        for (int i = 0; i < Dim; ++i)
          for (int j = 0; j < Dim; ++j) A(i, j) += s.grad[q][i] * xn[j];
        gx_abs += norm(s.grad[q]) * norm(xn);
      }
      for (int d = 0; d < Dim; ++d)
        EXPECT_NEAR(xr[d], x[d], roundoff_bound(s.count, wx_abs))
            << shape_kind_name(kind) << " axis " << d;
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j)
          EXPECT_NEAR(A(i, j), i == j ? 1.0 : 0.0, roundoff_bound(s.count, gx_abs))
              << shape_kind_name(kind) << " (" << i << "," << j << ") trial " << trial;
    }
  }
}

TEST(ShapeFunctions, LinearFieldReproduction2D) {
  check_linear_reproduction<2>();
}
TEST(ShapeFunctions, LinearFieldReproduction3D) {
  check_linear_reproduction<3>();
}

// grad_I equals the central difference of w_I (linear, GIMP, B-spline; CPDI's gradient is by design
// the volume average over the deformed domain, not dw/dx, so it is checked separately below).
// delta = 1e-5 h, dividing by the exactly representable xp - xm. Comparing h*grad with h*FD:
// the weights carry round-off ~ eps * |x - origin|/h ~ 4e-15 (t is formed from ~16 cells), so the
// difference quotient carries <= ~1e-9; truncation error is zero for the piecewise (bi/tri)linear
// hat and the piecewise-quadratic GIMP away from their breakpoints (central differences are exact
// for quadratics per axis; positions within 1e-4 h > delta of a breakpoint are skipped: the hat's
// cell faces, GIMP's t = a and t = 1 - a), and <= (delta/h)^2 ~ 1e-10 for the C2 cubic B-spline,
// which is checked everywhere including across cell faces. Tolerance 1e-8.
template <int Dim>
void check_gradient_fd(ShapeKind kind) {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(20 + Dim + 7 * static_cast<int>(kind));
  std::uniform_real_distribution<double> ul(0.05, 0.5);
  const double delta = 1e-5 * g.h;
  Stencil<Dim> s, sp, sm;
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Params p;
    p.lp = Vec3{{ul(rng) * g.h, ul(rng) * g.h, ul(rng) * g.h}};
    if (trial % 10 == 0) p.lp = Vec3{{0.5 * g.h, 0.5 * g.h, 0.5 * g.h}};  // the lp = h/2 limit
    const Vec3 x = random_point(g, Dim, rng);
    bool near_break = false;
    for (int d = 0; d < Dim; ++d) {
      const double t = (x[d] - g.origin[d]) / g.h - std::floor((x[d] - g.origin[d]) / g.h);
      const double a = p.lp[d] / g.h;
      auto near = [&](double b) { return std::fabs(t - b) < 1e-4; };
      if (kind == ShapeKind::Linear && (near(0.0) || near(1.0))) near_break = true;
      if (kind == ShapeKind::Gimp && (near(a) || near(1.0 - a))) near_break = true;
    }
    if (near_break) continue;
    ++checked;
    compute<Dim>(kind, g, x, p, s);
    for (int d = 0; d < Dim; ++d) {
      Vec3 xp = x, xm = x;
      xp[d] += delta;
      xm[d] -= delta;
      compute<Dim>(kind, g, xp, p, sp);
      compute<Dim>(kind, g, xm, p, sm);
      const auto mp = merge(sp), mm = merge(sm);
      for (int q = 0; q < s.count; ++q) {
        const auto ip = mp.find(s.node[q]), im = mm.find(s.node[q]);
        const double wp = ip == mp.end() ? 0.0 : ip->second.w;  // node left the window: weight 0
        const double wm = im == mm.end() ? 0.0 : im->second.w;
        const double fd = (wp - wm) / (xp[d] - xm[d]);
        EXPECT_NEAR(g.h * s.grad[q][d], g.h * fd, 1e-8) << shape_kind_name(kind) << " axis " << d;
      }
    }
  }
  EXPECT_GT(checked, 400);
}

TEST(ShapeFunctions, GradientMatchesFiniteDifference2D) {
  for (ShapeKind k : {ShapeKind::Linear, ShapeKind::Gimp, ShapeKind::BSpline3})
    check_gradient_fd<2>(k);
}
TEST(ShapeFunctions, GradientMatchesFiniteDifference3D) {
  for (ShapeKind k : {ShapeKind::Linear, ShapeKind::Gimp, ShapeKind::BSpline3})
    check_gradient_fd<3>(k);
}

// GIMP 1-D weight equals its definition, (1/2lp) * integral of the hat over [x - lp, x + lp],
// evaluated independently (trapezoid rule on each linear piece between nodes: exact), for lp from
// 1e-9 h (linear limit) to h/2. Both sides are O(1) sums of a few rounded terms: 1e-13.
TEST(ShapeFunctions, GimpIsHatAveragedOverParticle) {
  const GridGeometry g = make_grid(2);
  std::mt19937 rng(30);
  std::uniform_real_distribution<double> ua(0.0, 0.5);
  Stencil<2> s;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 x = random_point(g, 2, rng);
    double a = ua(rng);
    if (trial % 100 == 0) a = 0.5;
    if (trial % 100 == 1) a = 1e-9;
    const double lp = a * g.h;
    gimp_stencil<2>(g, x, Vec3{{lp, lp, lp}}, s);
    const auto m = merge(s);
    const int c = g.cell_of(x[0], 0);
    const int j = g.cell_of(x[1], 1);
    for (int n = c - 2; n <= c + 3; ++n) {
      // Exact average of the hat of node n over [x - lp, x + lp], split at the hat's kinks; in
      // units of h relative to x (s in [-a, a], node at un) so that tiny a stays accurate.
      const double un = (g.origin[0] + n * g.h - x[0]) / g.h;
      auto hat = [&](double u) { return std::max(0.0, 1.0 - std::fabs(u - un)); };
      const double pts[5] = {-a, un - 1.0, un, un + 1.0, a};
      double integral = 0.0, prev = -a;
      for (int k = 1; k < 5; ++k) {
        const double b = std::min(std::max(pts[k], -a), a);
        if (b > prev) {
          integral += 0.5 * (b - prev) * (hat(prev) + hat(b));
          prev = b;
        }
      }
      const double ref = integral / (2.0 * a);
      // Recover the 1-D x-weight: sum the 2-D weights over the y nodes of this column.
      double w1 = 0.0;
      for (int jj = j - 2; jj <= j + 3; ++jj) {
        const auto it = m.find(g.node_index(n, jj, 0));
        if (it != m.end()) w1 += it->second.w;
      }
      EXPECT_NEAR(w1, ref, 1e-13) << "a=" << a << " node offset " << n - c;
    }
  }
}

// CPDI1 with r = diag(lp) (undeformed, axis-aligned domain) equals uGIMP with the same lp at every
// node if and only if, on every axis, the particle domain [x - lp, x + lp] lies inside one cell
// (t in [a, 1-a], a = lp/h). Reason: per axis CPDI's weight is the trapezoid rule
// (S(x-lp) + S(x+lp))/2 of the hat, GIMP's is its exact average; they agree when the hat is linear
// over the domain, i.e. no node inside it. The 1-D gradients, (S(x+lp) - S(x-lp))/(2lp), agree
// always, so dN/dx_d also agrees when only axis d straddles a node. Round-off: 1e-14 on weights,
// 1e-13 / h on gradients (gradient terms are O(1/h) products).
template <int Dim>
void check_cpdi_equals_gimp() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(40 + Dim);
  std::uniform_real_distribution<double> uin(0.25, 0.75), uout(0.0, 0.2), ucell(8.0, 15.0);
  const double lp = 0.25 * g.h;
  Params p;
  p.lp = Vec3{{lp, lp, lp}};
  p.r = Mat3::diag(lp, lp, lp);
  Stencil<Dim> sc, sg;
  for (int trial = 0; trial < 1000; ++trial) {
    // Axis `straddle` (or none when straddle == Dim) puts the domain across a node.
    const int straddle = trial % (Dim + 1);
    Vec3 x = g.origin;
    for (int d = 0; d < Dim; ++d) {
      double t = uin(rng);
      if (d == straddle) t = trial % 2 ? uout(rng) : 1.0 - uout(rng) * 0.999;
      x[d] += (std::floor(ucell(rng)) + t) * g.h;
    }
    compute<Dim>(ShapeKind::Cpdi, g, x, p, sc);
    compute<Dim>(ShapeKind::Gimp, g, x, p, sg);
    auto mc = merge(sc), mg = merge(sg);
    for (auto& [n, v] : mg) mc[n];  // union of nodes; missing = 0
    for (auto& [n, v] : mc) mg[n];
    double max_dw = 0.0;
    for (const auto& [n, vc] : mc) {
      const Merged& vg = mg[n];
      max_dw = std::max(max_dw, std::fabs(vc.w - vg.w));
      for (int d = 0; d < Dim; ++d) {
        // grad_d = (1-D gradient on d) x (weights on the other axes): equal unless another axis
        // straddles.
        const bool other_straddles = straddle < Dim && straddle != d;
        if (!other_straddles) {
          EXPECT_NEAR(vc.grad[d], vg.grad[d], 1e-13 / g.h) << "axis " << d;
        }
      }
    }
    if (straddle == Dim) {
      EXPECT_LT(max_dw, 1e-14);
    } else {
      EXPECT_GT(max_dw, 1e-8) << "domain straddles a node on axis " << straddle
                              << ": weights should differ";
    }
  }
}

TEST(ShapeFunctions, CpdiEqualsGimpWhenDomainInsideOneCell2D) {
  check_cpdi_equals_gimp<2>();
}
TEST(ShapeFunctions, CpdiEqualsGimpWhenDomainInsideOneCell3D) {
  check_cpdi_equals_gimp<3>();
}

// CPDI against an independent evaluation of the paper's closed forms (Sadeghirad et al. 2011):
// 2D: grad = (1/V){[S(x1)-S(x3)](r1y-r2y, r2x-r1x) + [S(x2)-S(x4)](r1y+r2y, -r1x-r2x)}, V = 4 r1 x
// r2, corners x1 = x-r1-r2, x2 = x+r1-r2, x3 = x+r1+r2, x4 = x-r1+r2; 3D: grad = (1/V) sum_alpha
// S(x_alpha)(xi1 r2 x r3 + xi2 r3 x r1 + xi3 r1 x r2), V = 8 r1.(r2 x r3). Linear hats are
// evaluated directly from node positions. Tolerance: round-off of O(1/h_min) gradient terms, 1e-12
// / h.
double hat_at(const GridGeometry& g, int dim, const Vec3& y, const int ijk[3]) {
  double s = 1.0;
  for (int d = 0; d < dim; ++d)
    s *= std::max(0.0, 1.0 - std::fabs((y[d] - g.origin[d]) / g.h - ijk[d]));
  return s;
}

template <int Dim>
void check_cpdi_closed_form() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(50 + Dim);
  Stencil<Dim> s;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 x = random_point(g, Dim, rng);
    const Mat3 r = random_cpdi_r(g, Dim, rng, 0.6);
    cpdi_stencil<Dim>(g, x, r, s);
    const auto m = merge(s);
    const Vec3 r1{{r(0, 0), r(1, 0), r(2, 0)}}, r2{{r(0, 1), r(1, 1), r(2, 1)}},
        r3{{r(0, 2), r(1, 2), r(2, 2)}};
    for (const auto& [n, v] : m) {
      int ijk[3];
      decode(g, n, ijk);
      double w_ref = 0.0;
      Vec3 g_ref;
      if constexpr (Dim == 2) {
        const Vec3 xc[4] = {x - r1 - r2, x + r1 - r2, x + r1 + r2, x - r1 + r2};
        double S[4];
        for (int a = 0; a < 4; ++a) S[a] = hat_at(g, 2, xc[a], ijk);
        const double V = 4.0 * (r1[0] * r2[1] - r1[1] * r2[0]);
        w_ref = 0.25 * (S[0] + S[1] + S[2] + S[3]);
        g_ref[0] = ((S[0] - S[2]) * (r1[1] - r2[1]) + (S[1] - S[3]) * (r1[1] + r2[1])) / V;
        g_ref[1] = ((S[0] - S[2]) * (r2[0] - r1[0]) + (S[1] - S[3]) * (-r1[0] - r2[0])) / V;
      } else {
        const double V = 8.0 * dot(r1, cross(r2, r3));
        const Vec3 c23 = cross(r2, r3), c31 = cross(r3, r1), c12 = cross(r1, r2);
        for (int a = 0; a < 8; ++a) {
          const double x1 = a & 1 ? 1.0 : -1.0, x2 = a & 2 ? 1.0 : -1.0, x3 = a & 4 ? 1.0 : -1.0;
          const Vec3 y = x + x1 * r1 + x2 * r2 + x3 * r3;
          const double S = hat_at(g, 3, y, ijk);
          w_ref += S / 8.0;
          g_ref += (S / V) * (x1 * c23 + x2 * c31 + x3 * c12);
        }
      }
      EXPECT_NEAR(v.w, w_ref, 1e-14);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(v.grad[d], g_ref[d], 1e-12 / g.h) << "axis " << d;
    }
  }
}

TEST(ShapeFunctions, CpdiMatchesPaperClosedForm2D) {
  check_cpdi_closed_form<2>();
}
TEST(ShapeFunctions, CpdiMatchesPaperClosedForm3D) {
  check_cpdi_closed_form<3>();
}

// CPDI with a reflected (negative-orientation) r gives the same stencil as the positively oriented
// one describing the same domain (r with a column negated): the signed determinant handles it.
TEST(ShapeFunctions, CpdiIndependentOfColumnSign) {
  const GridGeometry g = make_grid(3);
  std::mt19937 rng(60);
  Stencil<3> a, b;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 x = random_point(g, 3, rng);
    Mat3 r = random_cpdi_r(g, 3, rng, 0.4);
    cpdi_stencil<3>(g, x, r, a);
    for (int i = 0; i < 3; ++i) r(i, 1) = -r(i, 1);
    cpdi_stencil<3>(g, x, r, b);
    const auto ma = merge(a), mb = merge(b);
    ASSERT_EQ(ma.size(), mb.size());
    for (const auto& [n, v] : ma) {
      EXPECT_NEAR(v.w, mb.at(n).w, 1e-14);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(v.grad[d], mb.at(n).grad[d], 1e-12 / g.h);
    }
  }
}

// Every node offset observed stays within stencil_reach, including large CPDI deformations and
// corners placed exactly on cell faces with an integer extent.
template <int Dim>
void check_reach() {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(70 + Dim);
  Stencil<Dim> s;
  int max_seen[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 3000; ++trial) {
    Params p = random_params<Dim>(g, rng);
    if (trial % 3 == 0) p.r = random_cpdi_r(g, Dim, rng, 2.0);  // extents up to ~3 cells
    Vec3 x = random_point(g, Dim, rng);
    if (trial % 7 == 0) {  // integer extent e = 1, corners on (or one ulp off) cell faces
      p.r = Mat3::diag(g.h, g.h, g.h);
      for (int d = 0; d < Dim; ++d) {
        x[d] = g.origin[d] + (10 + (trial % 3)) * g.h;
        if (trial % 2) x[d] = std::nextafter(x[d], -1e300);
      }
    }
    const double e = cpdi_extent(g, Dim, p.r);
    for (int k = 0; k < 4; ++k) {
      const ShapeKind kind = kKinds[k];
      const int reach = stencil_reach(kind, e);
      compute<Dim>(kind, g, x, p, s);
      for (int q = 0; q < s.count; ++q) {
        int ijk[3];
        decode(g, s.node[q], ijk);
        for (int d = 0; d < Dim; ++d) {
          const int off = std::abs(ijk[d] - g.cell_of(x[d], d));
          max_seen[k] = std::max(max_seen[k], off);
          EXPECT_LE(off, reach) << shape_kind_name(kind) << " e=" << e;
        }
        if (Dim == 2) {
          EXPECT_EQ(ijk[2], 0);
        }
      }
    }
  }
  EXPECT_EQ(max_seen[0], 1);  // linear: c, c+1
  EXPECT_EQ(max_seen[1], 2);  // GIMP: c-1..c+2
  EXPECT_EQ(max_seen[3], 2);  // B-spline: c-1..c+2
  EXPECT_EQ(stencil_reach(ShapeKind::Cpdi, 0.5), 2);
  EXPECT_EQ(stencil_reach(ShapeKind::Cpdi, 1.0), 3);
  EXPECT_EQ(stencil_reach(ShapeKind::Cpdi, 2.7), 4);
}

TEST(ShapeFunctions, StencilReachBoundsOffsets2D) {
  check_reach<2>();
}
TEST(ShapeFunctions, StencilReachBoundsOffsets3D) {
  check_reach<3>();
}

// Round-off at integer CPDI extents: with r = diag(h) (e = 1) and the particle a few ulps off a
// cell face, a corner can land one cell further than exact arithmetic allows, reaching node offset
// 3 > ceil(e) + 1. stencil_reach returns floor(e + 1e-6) + 2 = 3 for this; scan grids (random
// origin and h) for such cases and check the bound holds for all of them, for e = 1 and for e a
// hair below 1.
TEST(ShapeFunctions, StencilReachCoversRoundOffAtIntegerExtent) {
  std::mt19937 rng(80);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Stencil<2> s;
  int beyond_exact = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    GridGeometry g = make_grid(2);
    g.origin = Vec3{{3.0 * u(rng), 3.0 * u(rng), 0.0}};
    g.h = std::exp(3.0 * u(rng));
    const double scale = trial % 2 ? 1.0 : 1.0 - 1e-12;
    const Mat3 r = Mat3::diag(scale * g.h, scale * g.h, 0.0);
    const double e = cpdi_extent(g, 2, r);
    const int reach = stencil_reach(ShapeKind::Cpdi, e);
    ASSERT_EQ(reach, 3);
    Vec3 x = g.node_position(12, 12, 0);
    for (int k = 0; k < trial % 9; ++k) x[0] = std::nextafter(x[0], trial % 4 < 2 ? -1e300 : 1e300);
    x[1] = x[0] - g.origin[0] + g.origin[1];
    cpdi_stencil<2>(g, x, r, s);
    for (int q = 0; q < s.count; ++q) {
      int ijk[3];
      decode(g, s.node[q], ijk);
      for (int d = 0; d < 2; ++d) {
        const int off = std::abs(ijk[d] - g.cell_of(x[d], d));
        EXPECT_LE(off, reach);
        if (off > 2) ++beyond_exact;
      }
    }
  }
  // Informational (depends on rounding, so not asserted): how often the slack was needed; on
  // x86-64/GCC 12 this scan finds such cases, which is why stencil_reach is not ceil(e) + 1.
  RecordProperty("offsets_beyond_exact_bound", beyond_exact);
  std::printf("CPDI node offsets beyond the exact-arithmetic bound ceil(e)+1: %d\n", beyond_exact);
}

// Linear weights at a node position: weight 1 on that node, exactly.
TEST(ShapeFunctions, LinearInterpolatesAtNodes) {
  const GridGeometry g = make_grid(3);
  Stencil<3> s;
  const Vec3 x = g.node_position(9, 11, 10);
  linear_stencil<3>(g, x, s);
  const auto m = merge(s);
  EXPECT_NEAR(m.at(g.node_index(9, 11, 10)).w, 1.0, 1e-14);
}

TEST(ShapeFunctions, NamesRoundTripAndErrors) {
  const auto names = shape_kind_names();
  ASSERT_EQ(names.size(), 4u);
  EXPECT_EQ(names[0], "linear");
  EXPECT_EQ(names[1], "gimp");
  EXPECT_EQ(names[2], "cpdi");
  EXPECT_EQ(names[3], "bspline3");
  for (ShapeKind k : kKinds) {
    EXPECT_EQ(parse_shape_kind(shape_kind_name(k)), k);
    const std::string desc = shape_kind_description(k);
    EXPECT_NE(desc.find_first_of("0123456789"), std::string::npos) << desc;  // cites a paper/year
  }
  EXPECT_EQ(parse_shape_kind("GIMP"), ShapeKind::Gimp);
  try {
    parse_shape_kind("quadratic");
    FAIL() << "expected ballista::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("quadratic"), std::string::npos);
    for (const auto& n : names) EXPECT_NE(msg.find(n), std::string::npos) << msg;
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Boundary-modified cubic B-spline (Steffen, Wallstedt, Guilkey, Kirby & Berzins, CMES 31 (2008)
// 107; bspline3_1d). The box of these tests spans nodes kLo..kHi on every axis of make_grid's
// block; points are drawn in the first two cells next to a face (where the modified functions and
// their uniform neighbours meet) and anywhere in the box.

namespace {

constexpr int kLo = 8, kHi = 16;

SplineFaces box_faces(int lo = kLo, int hi = kHi) {
  SplineFaces f;
  for (int d = 0; d < 3; ++d) { f.lo[d] = lo; f.hi[d] = hi; }
  return f;
}

/// Random coordinate (in cells from the origin) in the two cells next to the low or high face, or
/// anywhere in the box.
double near_face_cells(std::mt19937& rng, int lo, int hi) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int which = static_cast<int>(rng() % 3);
  const double c = which == 0 ? lo + 2.0 * u(rng) : which == 1 ? hi - 2.0 * u(rng) : lo + (hi - lo) * u(rng);
  return std::min(std::max(c, static_cast<double>(lo)), static_cast<double>(hi));
}

/// Steffen et al.'s piecewise cubics in node units xi = (x - x_I)/h, for a node at the low face
/// (face node), its first interior neighbour, and any other node (uniform), restricted to x >= face.
double steffen_face_node(double xi) {
  if (xi < 0.0 || xi >= 2.0) return 0.0;
  return xi < 1.0 ? xi * xi * xi / 6.0 - xi + 1.0 : (2.0 - xi) * (2.0 - xi) * (2.0 - xi) / 6.0;
}
double uniform_kernel(double xi) {
  const double u = std::fabs(xi);
  if (u >= 2.0) return 0.0;
  return u < 1.0 ? 0.5 * u * u * u - u * u + 2.0 / 3.0 : (2.0 - u) * (2.0 - u) * (2.0 - u) / 6.0;
}
double steffen_first_interior(double xi) {
  if (xi >= -1.0 && xi < 0.0) return -xi * xi * xi / 3.0 - xi * xi + 2.0 / 3.0;
  return uniform_kernel(xi);
}

}  // namespace

// Partition of unity, linear reproduction with the real node positions (the property the
// boundary modification restores), non-negativity, no weight beyond a face, in the face cells and
// the cells next to them.
template <int Dim>
void check_bspline_faces(const SplineFaces& faces, int lo, int hi) {
  const GridGeometry g = make_grid(Dim);
  std::mt19937 rng(90 + Dim + lo + hi);
  Stencil<Dim> s;
  for (int trial = 0; trial < 3000; ++trial) {
    Vec3 x = g.origin;
    for (int d = 0; d < Dim; ++d) x[d] += near_face_cells(rng, lo, hi) * g.h;
    if (trial < 8) x[trial % Dim] = g.origin[trial % Dim] + (trial % 2 ? hi : lo) * g.h;  // on a face
    bspline3_stencil<Dim>(g, x, s, faces);
    double sw = 0.0, sw_abs = 0.0, g_abs = 0.0, wx_abs = 0.0, gx_abs = 0.0;
    Vec3 sg, xr;
    Mat3 A;
    for (int q = 0; q < s.count; ++q) {
      int ijk[3];
      decode(g, s.node[q], ijk);
      for (int d = 0; d < Dim; ++d)
        if (ijk[d] < lo || ijk[d] > hi) {
          ASSERT_EQ(s.w[q], 0.0) << "weight beyond a face, trial " << trial;
          ASSERT_EQ(norm(s.grad[q]), 0.0);
        }
      EXPECT_GE(s.w[q], 0.0) << "trial " << trial;
      const Vec3 xn = g.node_position(ijk[0], ijk[1], ijk[2]);
      sw += s.w[q];
      sw_abs += std::fabs(s.w[q]);
      sg += s.grad[q];
      g_abs += norm(s.grad[q]);
      xr += s.w[q] * xn;
      wx_abs += std::fabs(s.w[q]) * norm(xn);
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) A(i, j) += s.grad[q][i] * xn[j];
      gx_abs += norm(s.grad[q]) * norm(xn);
    }
    EXPECT_NEAR(sw, 1.0, roundoff_bound(s.count, sw_abs)) << "trial " << trial;
    EXPECT_LE(norm(sg), roundoff_bound(s.count, g_abs)) << "trial " << trial;
    for (int d = 0; d < Dim; ++d) EXPECT_NEAR(xr[d], x[d], roundoff_bound(s.count, wx_abs)) << "trial " << trial;
    for (int i = 0; i < Dim; ++i)
      for (int j = 0; j < Dim; ++j)
        EXPECT_NEAR(A(i, j), i == j ? 1.0 : 0.0, roundoff_bound(s.count, gx_abs)) << "trial " << trial;
  }
}

TEST(ShapeFunctions, BSplineFacesPartitionOfUnityAndLinearReproduction2D) {
  check_bspline_faces<2>(box_faces(), kLo, kHi);
}
TEST(ShapeFunctions, BSplineFacesPartitionOfUnityAndLinearReproduction3D) {
  check_bspline_faces<3>(box_faces(), kLo, kHi);
}
TEST(ShapeFunctions, BSplineFacesOneCellAxis) {
  // Both faces bound the same cell: the two extrapolations compose (to the linear hat).
  check_bspline_faces<2>(box_faces(kLo, kLo + 1), kLo, kLo + 1);
}

// The uniform B-spline's nodes beyond the face cell lose nothing: without the modification the
// linear reproduction with only the nodes inside the box fails by ~t-dependent O(h) amounts, with
// it, it is exact (the gap the modification closes; reported, and asserted to be large).
TEST(ShapeFunctions, BSplineUniformTruncatedAtAFaceIsNotConsistent) {
  const GridGeometry g = make_grid(2);
  Stencil<2> s;
  const Vec3 x{{g.origin[0] + (kLo + 0.25) * g.h, g.origin[1] + 12.5 * g.h, 0.0}};
  bspline3_stencil<2>(g, x, s);
  double sw_inside = 0.0;
  for (int q = 0; q < s.count; ++q) {
    int ijk[3];
    decode(g, s.node[q], ijk);
    if (ijk[0] >= kLo) sw_inside += s.w[q];
  }
  EXPECT_NEAR(sw_inside, 1.0 - std::pow(0.75, 3) / 6.0, 1e-14);  // the beyond-face node's (1-t)^3/6
}

// Steffen et al.'s closed forms (node units, face at node kLo) against the kernel, 1D, for the face
// node, the first interior node and the next two (uniform), both faces (the high face mirrored),
// at points in the two face cells; derivatives by central differences of the closed forms
// (delta 1e-6 h: truncation ~1e-12, round-off ~1e-10 of h dN/dx). Also: interpolatory at the face.
TEST(ShapeFunctions, BSplineFaceFunctionsAreSteffensCubics) {
  const GridGeometry g = make_grid(2);
  const SplineFaces f = box_faces();
  const double inv_h = 1.0 / g.h;
  std::mt19937 rng(95);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  auto closed = [](int node_from_face, double xi_from_face) {
    // node_from_face: 0 face node, 1 first interior, >= 2 uniform; xi_from_face = (x - x_face)/h.
    const double xi = xi_from_face - node_from_face;
    if (node_from_face == 0) return steffen_face_node(xi);
    if (node_from_face == 1) return steffen_first_interior(xi);
    return uniform_kernel(xi);
  };
  for (int trial = 0; trial < 2000; ++trial) {
    const double c = trial == 0 ? 0.0 : u(rng);  // cells from the face, into the box
    for (int side = 0; side < 2; ++side) {
      const double cells = side == 0 ? kLo + c : kHi - c;
      shape_detail::Axis1D<4> a;
      shape_detail::bspline3_1d(g.origin[0] + cells * g.h, g.origin[0], g.h, inv_h, a, f.lo[0], f.hi[0]);
      for (int n = 0; n < 4; ++n) {
        const int node = a.first + n;
        const int from_face = side == 0 ? node - kLo : kHi - node;
        const double expect = from_face < 0 ? 0.0 : closed(from_face, c);
        EXPECT_NEAR(a.w[n], expect, 1e-14) << "side " << side << " node " << from_face << " c " << c;
        const double d = 1e-6;
        const double fd = from_face < 0 ? 0.0 : (closed(from_face, c + d) - closed(from_face, c - d)) / (2.0 * d);
        // d/dx = (d/dc) / h on the low side, -(d/dc) / h on the high side.
        if (c > 2e-6 && std::fabs(c - 1.0) > 2e-6) {
          EXPECT_NEAR(g.h * a.dw[n], side == 0 ? fd : -fd, 1e-8) << "side " << side << " node " << from_face;
        }
      }
      if (trial == 0) {  // at the face: weight 1 on the face node, 0 elsewhere
        for (int n = 0; n < 4; ++n) {
          const int node = a.first + n;
          EXPECT_EQ(a.w[n], node == (side == 0 ? kLo : kHi) ? 1.0 : 0.0) << "side " << side << " n " << n;
        }
      }
    }
  }
}

// C2 across the face cell's inner boundary (t = 1) and C1 / C2 elsewhere: value, slope and
// curvature of every node's function from both sides of each cell boundary in the first three
// cells of each face. Curvature by differences of dN/dx over 1e-7 h (the pieces are cubic: exact
// up to round-off ~1e-8 of h^2 N''); the jumps of value and slope over 2e-9 h are <= ~1e-8.
TEST(ShapeFunctions, BSplineFacesAreC2InsideTheBox) {
  const GridGeometry g = make_grid(2);
  const SplineFaces f = box_faces();
  const double inv_h = 1.0 / g.h;
  auto eval = [&](double cells, int node, double& w, double& dw) {
    shape_detail::Axis1D<4> a;
    shape_detail::bspline3_1d(g.origin[0] + cells * g.h, g.origin[0], g.h, inv_h, a, f.lo[0], f.hi[0]);
    w = dw = 0.0;
    const int n = node - a.first;
    if (n >= 0 && n < 4) { w = a.w[n]; dw = a.dw[n]; }
  };
  for (int b : {kLo + 1, kLo + 2, kLo + 3, kHi - 3, kHi - 2, kHi - 1}) {
    for (int node = b - 3; node <= b + 3; ++node) {
      const double e = 1e-9, d = 1e-7;
      double wl, dl, wr, dr, wl2, dl2, wr2, dr2;
      eval(b - e, node, wl, dl);
      eval(b + e, node, wr, dr);
      EXPECT_NEAR(wl, wr, 1e-8) << "boundary " << b << " node " << node;
      EXPECT_NEAR(g.h * dl, g.h * dr, 1e-8) << "boundary " << b << " node " << node;
      eval(b - d, node, wl2, dl2);
      eval(b + d, node, wr2, dr2);
      const double curv_l = g.h * (dl - dl2) / (d - e), curv_r = g.h * (dr2 - dr) / (d - e);
      EXPECT_NEAR(curv_l, curv_r, 1e-6) << "boundary " << b << " node " << node;
    }
  }
}

// Gradients against central differences in the face cells and across their boundaries (as
// check_gradient_fd for the uniform spline: tolerance 1e-8 of h dN/dx).
TEST(ShapeFunctions, BSplineFacesGradientMatchesFiniteDifference) {
  const GridGeometry g = make_grid(3);
  const SplineFaces f = box_faces();
  std::mt19937 rng(97);
  const double delta = 1e-5 * g.h;
  Stencil<3> s, sp, sm;
  for (int trial = 0; trial < 500; ++trial) {
    Vec3 x = g.origin;
    for (int d = 0; d < 3; ++d) x[d] += near_face_cells(rng, kLo, kHi) * g.h;
    for (int d = 0; d < 3; ++d) {  // keep x +- delta inside the box (the face is a boundary of the basis)
      x[d] = std::max(x[d], g.origin[d] + kLo * g.h + 2.0 * delta);
      x[d] = std::min(x[d], g.origin[d] + kHi * g.h - 2.0 * delta);
    }
    bspline3_stencil<3>(g, x, s, f);
    for (int d = 0; d < 3; ++d) {
      Vec3 xp = x, xm = x;
      xp[d] += delta;
      xm[d] -= delta;
      bspline3_stencil<3>(g, xp, sp, f);
      bspline3_stencil<3>(g, xm, sm, f);
      const auto mp = merge(sp), mm = merge(sm);
      for (int q = 0; q < s.count; ++q) {
        const auto ip = mp.find(s.node[q]), im = mm.find(s.node[q]);
        const double wp = ip == mp.end() ? 0.0 : ip->second.w;
        const double wm = im == mm.end() ? 0.0 : im->second.w;
        EXPECT_NEAR(g.h * s.grad[q][d], g.h * (wp - wm) / (xp[d] - xm[d]), 1e-8) << "axis " << d;
      }
    }
  }
}

// Away from the face cells the bounded basis is the uniform one, bitwise (the solver's interior
// particles are unaffected), and with no faces it is the uniform one everywhere.
TEST(ShapeFunctions, BSplineFacesLeaveOtherCellsBitwiseUniform) {
  const GridGeometry g = make_grid(3);
  std::mt19937 rng(98);
  std::uniform_real_distribution<double> u(kLo + 1.0, kHi - 1.0);
  Stencil<3> a, b;
  for (int trial = 0; trial < 1000; ++trial) {
    Vec3 x = g.origin;
    for (int d = 0; d < 3; ++d) x[d] += u(rng) * g.h;
    bspline3_stencil<3>(g, x, a, box_faces());
    bspline3_stencil<3>(g, x, b);
    ASSERT_EQ(a.count, b.count);
    for (int q = 0; q < a.count; ++q) {
      ASSERT_EQ(a.node[q], b.node[q]);
      ASSERT_EQ(a.w[q], b.w[q]);
      for (int d = 0; d < 3; ++d) ASSERT_EQ(a.grad[q][d], b.grad[q][d]);
    }
  }
}

}  // namespace test_shape_functions
