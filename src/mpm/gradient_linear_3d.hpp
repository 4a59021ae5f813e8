#pragma once
// The velocity gradient at the points, L_p = sum_I v_I (x) grad N_I(x_p), with linear weights in
// 3D on a uniform grid, eight points per vector: each lane (a point) forms its weights' gradients
// and its nine sums; when the eight points lie in one cell (several points per cell, sorted by
// cell) they share its nodes, whose velocities are then read once for all.
//
// Each lane evaluates the general loop's expressions (MpmSolver::velocity_gradient_from_grid):
// every gradient is the product linear_stencil forms (the same multiplications in the same order)
// and each sum runs over the cell's nodes in linear_stencil's order. The compiler fuses the general
// loop's multiply-adds differently, so the two agree to round-off
// (tests/unit/mpm/test_gradient_linear_3d.cpp); a run takes this path for all its points or for
// none (decided by shape function, dimension and field count). The lanes are points, which never
// share a sum, so which points form a group changes nothing (bitwise).
#include "core/tensor.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {

inline constexpr int kGradientGroup = 8;

/// The cell of point x (node index of its lowest corner) and its offsets t in the cell per axis,
/// exactly as linear_1d locates it.
inline Index linear_cell_3d(const GridGeometry& g, const Vec3& x, double (&t)[3]) {
  int first[3];
  for (int d = 0; d < 3; ++d) shape_detail::locate(x[d], g.origin[d], g.h, first[d], t[d]);
  return g.node_index(first[0], first[1], first[2]);
}

/// l[j] = sum_I v_I (x) grad N_I(x[j]) for n <= 8 points x[0..n); vg: the field's node velocities.
/// Points of one cell (the points are sorted by cell) read their nodes' velocities once for all.
inline void linear_3d_gradients(const GridGeometry& g, const Vec3* vg, const Vec3* x, int n, Mat3* l) {
  typedef double V8 __attribute__((vector_size(kGradientGroup * sizeof(double))));
  const double inv_h = 1.0 / g.h;
  const Index sy = shape_detail::stride_y(g), sz = shape_detail::stride_z(g);
  Index base[kGradientGroup];
  V8 T[3] = {};
  bool one_cell = true;
  for (int j = 0; j < kGradientGroup; ++j) {
    double t[3];
    base[j] = linear_cell_3d(g, x[j < n ? j : n - 1], t);  // unused lanes repeat the last point
    for (int d = 0; d < 3; ++d) T[d][j] = t[d];
    one_cell = one_cell && base[j] == base[0];
  }
  // linear_1d: w = (1 - t, t), dw = (-1/h, 1/h).
  const V8 W[3][2] = {{1.0 - T[0], T[0]}, {1.0 - T[1], T[1]}, {1.0 - T[2], T[2]}};
  const double dw[2] = {-inv_h, inv_h};
  V8 L[3][3] = {};
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < 2; ++b) {
      // linear_stencil's products (shape_detail::tensor_product_n).
      const V8 wyz = W[1][b] * W[2][c], dyz = dw[b] * W[2][c], yzd = W[1][b] * dw[c];
      for (int a = 0; a < 2; ++a) {
        const V8 grad[3] = {dw[a] * wyz, W[0][a] * dyz, W[0][a] * yzd};
        const Index off = c * sz + b * sy + a;
        V8 U[3];
        if (one_cell) {
          const Vec3& u = vg[base[0] + off];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < kGradientGroup; ++j) U[i][j] = u[i];
        } else {
          for (int j = 0; j < kGradientGroup; ++j) {
            const Vec3& u = vg[base[j] + off];
            for (int i = 0; i < 3; ++i) U[i][j] = u[i];
          }
        }
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) L[i][j] += U[i] * grad[j];
      }
    }
  }
  for (int p = 0; p < n; ++p)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) l[p](i, j) = L[i][j][p];
}

}  // namespace ballista
