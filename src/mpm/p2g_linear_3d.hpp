#pragma once
// The particle-to-grid pass of linear weights in 3D on a uniform grid with one velocity field,
// eight nodes per vector: a point's eight weights and gradients are one vector each, its
// contributions to the eight nodes' mass, momentum and force are a few vector multiply-adds, and
// consecutive points of one cell (the points are sorted by cell) add into the cell's node sums
// held in registers, written to the grid when the next point lies in another cell.
//
// Bitwise the same grid as the general loop of MpmSolver::particles_to_grid: every weight and
// gradient is the product linear_stencil forms (the same two multiplications in the same order),
// every node's contribution is the same expression, and each node receives the points'
// contributions in the same order (a cell's nodes are read from the grid when its run of points
// starts and written back when it ends, and no other point of the slab touches them in between).
// The lanes of a vector are nodes, never points, so no sum is reordered.
#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "mpm/p2g_part.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {

/// What the pass reads and writes (the same arrays as the general loop).
struct P2gLinear3dArgs {
  const GridGeometry* g = nullptr;
  const Index* slab_start = nullptr;
  const Index* slab_points = nullptr;
  int nslab = 0;
  const Vec3* x = nullptr;
  const Vec3* v = nullptr;
  const double* mass = nullptr;
  const double* vol = nullptr;
  const Mat3* stress = nullptr;
  const double* bq = nullptr;    ///< pressure beside the stress (bulk viscosity or the F-bar's), or null
  const Vec3* fext = nullptr;    ///< external point forces, or null
  const Vec3* ftrac = nullptr;   ///< the part of fext spread from surface points, or null
  P2gPart part = P2gPart::All;  ///< the sums formed (the others are left as they are)
  bool parallel = false;
  double* gm = nullptr;
  Vec3* gp = nullptr;
  Vec3* gf = nullptr;
};

namespace p2g_detail {

typedef double V8 __attribute__((vector_size(8 * sizeof(double))));

/// The node sums of one cell's eight nodes (tensor_product's order: x fastest, then y, then z).
struct CellSums {
  Index base = -1;  ///< node index of the cell's lowest corner; -1: none held
  Index off[8];
  V8 m{}, px{}, py{}, pz{}, fx{}, fy{}, fz{};

  void take(Index b, const P2gLinear3dArgs& a) {
    base = b;
    for (int k = 0; k < 8; ++k) {
      const Index I = b + off[k];
      if (maps_momentum(a.part)) {
        px[k] = a.gp[I][0];
        py[k] = a.gp[I][1];
        pz[k] = a.gp[I][2];
      }
      if (maps_mass(a.part)) m[k] = a.gm[I];
      if (maps_forces(a.part)) {
        fx[k] = a.gf[I][0];
        fy[k] = a.gf[I][1];
        fz[k] = a.gf[I][2];
      }
    }
  }
  void write_back(const P2gLinear3dArgs& a) const {
    if (base < 0) return;
    for (int k = 0; k < 8; ++k) {
      const Index I = base + off[k];
      if (maps_momentum(a.part)) a.gp[I] = Vec3{{px[k], py[k], pz[k]}};
      if (maps_mass(a.part)) a.gm[I] = m[k];
      if (maps_forces(a.part)) a.gf[I] = Vec3{{fx[k], fy[k], fz[k]}};
    }
  }
};

}  // namespace p2g_detail

/// f_I = -V_p sigma_p grad N_I + N_I f_ext,p (Sulsky et al. 1994, eq. 14), m_I and (m v)_I (those of
/// a.part), for every point of every slab (slabs of one colour in parallel, as the general loop).
inline void p2g_linear_3d(const P2gLinear3dArgs& a) {
  using p2g_detail::V8;
  const GridGeometry& g = *a.g;
  const Index sy = shape_detail::stride_y(g), sz = shape_detail::stride_z(g);
  const double inv_h = 1.0 / g.h;
  for (int color = 0; color < 2; ++color) {
#pragma omp parallel for schedule(dynamic, 1) if (a.parallel)
    for (int s = color; s < a.nslab; s += 2) {
      p2g_detail::CellSums cell{.off = {0, 1, sy, sy + 1, sz, sz + 1, sz + sy, sz + sy + 1}};
      for (Index q = a.slab_start[s]; q < a.slab_start[s + 1]; ++q) {
        const Index p = a.slab_points[q];
        shape_detail::Axis1D<2> ax[3];
        for (int d = 0; d < 3; ++d) shape_detail::linear_1d(a.x[p][d], g.origin[d], g.h, inv_h, ax[d]);
        const Index base = g.node_index(ax[0].first, ax[1].first, ax[2].first);
        if (base != cell.base) {
          cell.write_back(a);
          cell.take(base, a);
        }
        // linear_stencil's products: wyz = wy wz, dyz = dwy wz, yzd = wy dwz per (y, z) node pair,
        // then w = wx wyz, grad = (dwx wyz, wx dyz, wx yzd).
        double wyz[4], dyz[4], yzd[4];
        for (int c = 0; c < 2; ++c)
          for (int b = 0; b < 2; ++b) {
            wyz[2 * c + b] = ax[1].w[b] * ax[2].w[c];
            dyz[2 * c + b] = ax[1].dw[b] * ax[2].w[c];
            yzd[2 * c + b] = ax[1].w[b] * ax[2].dw[c];
          }
        const V8 WYZ{wyz[0], wyz[0], wyz[1], wyz[1], wyz[2], wyz[2], wyz[3], wyz[3]};
        const V8 WX{ax[0].w[0], ax[0].w[1], ax[0].w[0], ax[0].w[1], ax[0].w[0], ax[0].w[1], ax[0].w[0], ax[0].w[1]};
        const V8 W = WX * WYZ;
        const double m = a.mass[p];
        if (maps_momentum(a.part)) {
          const Vec3 mv = m * a.v[p];
          cell.px += W * mv[0];
          cell.py += W * mv[1];
          cell.pz += W * mv[2];
        }
        if (maps_mass(a.part)) cell.m += W * m;
        if (!maps_forces(a.part)) continue;
        const V8 DWX{ax[0].dw[0], ax[0].dw[1], ax[0].dw[0], ax[0].dw[1],
                     ax[0].dw[0], ax[0].dw[1], ax[0].dw[0], ax[0].dw[1]};
        const V8 GX = DWX * WYZ;
        const V8 GY = WX * V8{dyz[0], dyz[0], dyz[1], dyz[1], dyz[2], dyz[2], dyz[3], dyz[3]};
        const V8 GZ = WX * V8{yzd[0], yzd[0], yzd[1], yzd[1], yzd[2], yzd[2], yzd[3], yzd[3]};
        Mat3 Vs = a.vol[p] * a.stress[p];
        if (a.bq)
          for (int i = 0; i < 3; ++i) Vs(i, i) -= a.vol[p] * a.bq[p];
        const Vec3 fe = a.fext ? (a.ftrac ? a.fext[p] - a.ftrac[p] : a.fext[p]) : Vec3{};
        // The general loop subtracts the hoop term hoop w (hoop = 0 in 3D) from f_x; subtracting
        // 0 W here keeps every bit of f_x the same, the sign of a zero included.
        cell.fx += W * fe[0] - (Vs(0, 0) * GX + Vs(0, 1) * GY + Vs(0, 2) * GZ) - 0.0 * W;
        cell.fy += W * fe[1] - (Vs(1, 0) * GX + Vs(1, 1) * GY + Vs(1, 2) * GZ);
        cell.fz += W * fe[2] - (Vs(2, 0) * GX + Vs(2, 1) * GY + Vs(2, 2) * GZ);
      }
      cell.write_back(a);
    }
  }
}

}  // namespace ballista
