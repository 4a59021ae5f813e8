// The eight-nodes-per-vector particle-to-grid pass (mpm/p2g_linear_3d.hpp) against the general
// loop of MpmSolver::particles_to_grid, written out here point by point from linear_stencil: the
// grid must be bitwise the same (the kernel only keeps a cell's node sums in registers while
// consecutive points lie in that cell), for the full pass and for each part (momentum only; USAVG's
// mass and momentum, then forces), with and without external forces and a pressure beside the
// stress, and whatever the points' order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "mpm/p2g_linear_3d.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {
namespace {

struct Cloud {
  GridGeometry g;
  std::vector<Vec3> x, v, fext, ftrac;
  std::vector<double> mass, vol, bq;
  std::vector<Mat3> stress;
  std::vector<Index> slab_start, slab_points;
};

/// n points in a 6 x 5 x 4 cell box, a few per cell and some cells shared by runs of points
/// (sorted by cell, as the solver sorts them) or scattered (unsorted); slabs of two cells along z.
/// With `one_per_cell`, point p lies in cell p (x fastest) of every cell of the box (n <= 120), as
/// at one particle per cell, where every point starts a new run of held node sums.
Cloud make_cloud(int n, bool sorted, unsigned seed, bool one_per_cell = false) {
  Cloud c;
  c.g.origin = Vec3{{-0.1, 0.2, 0.05}};
  c.g.h = 0.013;
  c.g.nodes[0] = 7;
  c.g.nodes[1] = 6;
  c.g.nodes[2] = 5;
  c.g.dim = 3;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int p = 0; p < n; ++p) {
    // Points in a few cells only, so that runs of several points per cell occur.
    int ci = static_cast<int>(u(rng) * 3), cj = static_cast<int>(u(rng) * 2), ck = static_cast<int>(u(rng) * 4);
    if (one_per_cell) {
      ci = p % 6;
      cj = (p / 6) % 5;
      ck = p / 30;
    }
    c.x.push_back(Vec3{{c.g.origin[0] + (ci + u(rng)) * c.g.h, c.g.origin[1] + (cj + u(rng)) * c.g.h,
                        c.g.origin[2] + (ck + u(rng)) * c.g.h}});
    c.v.push_back(Vec3{{u(rng) - 0.5, 200.0 * (u(rng) - 0.5), 3.0 * u(rng)}});
    c.fext.push_back(Vec3{{u(rng), -u(rng), 1e3 * u(rng)}});
    c.ftrac.push_back(Vec3{{0.1 * u(rng), 0.0, -0.2 * u(rng)}});
    c.mass.push_back(1e-3 * (0.5 + u(rng)));
    c.vol.push_back(1e-7 * (0.5 + u(rng)));
    c.bq.push_back(1e6 * u(rng));
    Mat3 s;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) s(i, j) = s(j, i) = 1e8 * (u(rng) - 0.5);
    c.stress.push_back(s);
  }
  std::vector<Index> order(n);
  for (int p = 0; p < n; ++p) order[p] = p;
  auto cell = [&](Index p) {
    return c.g.node_index(c.g.cell_of(c.x[p][0], 0), c.g.cell_of(c.x[p][1], 1), c.g.cell_of(c.x[p][2], 2));
  };
  if (sorted) std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return cell(a) < cell(b); });
  // Slabs of two cells along z: slabs of one colour never share a node.
  for (int s = 0; s < 2; ++s) {
    c.slab_start.push_back(static_cast<Index>(c.slab_points.size()));
    for (Index p : order)
      if (c.g.cell_of(c.x[p][2], 2) / 2 == s) c.slab_points.push_back(p);
  }
  c.slab_start.push_back(static_cast<Index>(c.slab_points.size()));
  return c;
}

/// The general loop's arithmetic, point by point (MpmSolver::particles_to_grid, one field, 3D).
void reference(const P2gLinear3dArgs& a) {
  for (int s = 0; s < a.nslab; ++s)
    for (Index q = a.slab_start[s]; q < a.slab_start[s + 1]; ++q) {
      const Index p = a.slab_points[q];
      Stencil<3> st;
      linear_stencil<3>(*a.g, a.x[p], st);
      const double m = a.mass[p];
      const Vec3 mv = m * a.v[p];
      if (a.part == P2gPart::Momentum) {
        for (int k = 0; k < st.count; ++k) a.gp[st.node[k]] += st.w[k] * mv;
        continue;
      }
      Mat3 Vs = a.vol[p] * a.stress[p];
      if (a.bq)
        for (int i = 0; i < 3; ++i) Vs(i, i) -= a.vol[p] * a.bq[p];
      const double hoop = 0.0;
      const Vec3 fe = a.fext ? (a.ftrac ? a.fext[p] - a.ftrac[p] : a.fext[p]) : Vec3{};
      for (int k = 0; k < st.count; ++k) {
        const Index I = st.node[k];
        const double w = st.w[k];
        const Vec3& dN = st.grad[k];
        if (maps_mass(a.part)) {
          a.gm[I] += w * m;
          a.gp[I] += w * mv;
        }
        if (!maps_forces(a.part)) continue;
        Vec3 f;
        for (int i = 0; i < 3; ++i)
          f[i] = w * fe[i] - (Vs(i, 0) * dN[0] + Vs(i, 1) * dN[1] + Vs(i, 2) * dN[2]);
        f[0] -= hoop * w;
        a.gf[I] += f;
      }
    }
}

/// The pass's arguments for a cloud: its points, and the external forces, tractions and pressure
/// beside the stress if asked.
P2gLinear3dArgs args_of(const Cloud& c, bool ext, bool trac, bool bq) {
  return {.g = &c.g,
          .slab_start = c.slab_start.data(),
          .slab_points = c.slab_points.data(),
          .nslab = static_cast<int>(c.slab_start.size()) - 1,
          .x = c.x.data(),
          .v = c.v.data(),
          .mass = c.mass.data(),
          .vol = c.vol.data(),
          .stress = c.stress.data(),
          .bq = bq ? c.bq.data() : nullptr,
          .fext = ext ? c.fext.data() : nullptr,
          .ftrac = ext && trac ? c.ftrac.data() : nullptr};
}

/// Points the pass at one set of grid arrays.
void set_grid(P2gLinear3dArgs& a, std::vector<double>& gm, std::vector<Vec3>& gp, std::vector<Vec3>& gf) {
  a.gm = gm.data();
  a.gp = gp.data();
  a.gf = gf.data();
}

void expect_same_grid(int n, bool sorted, P2gPart part, bool ext, bool trac, bool bq, unsigned seed,
                      bool one_per_cell = false) {
  const Cloud c = make_cloud(n, sorted, seed, one_per_cell);
  const Index nn = c.g.node_count();
  // Both grids start from the same non-zero values (a momentum-only pass adds to what is there).
  std::vector<double> gm0(nn);
  std::vector<Vec3> gp0(nn), gf0(nn);
  for (Index i = 0; i < nn; ++i) {
    gm0[i] = 1e-6 * static_cast<double>(i % 7);
    gp0[i] = Vec3{{1e-4 * static_cast<double>(i % 5), 0.0, -1e-5}};
    gf0[i] = Vec3{{0.0, 1e-3 * static_cast<double>(i % 3), 0.0}};
  }
  std::vector<double> gm1 = gm0, gm2 = gm0;
  std::vector<Vec3> gp1 = gp0, gp2 = gp0, gf1 = gf0, gf2 = gf0;
  P2gLinear3dArgs a = args_of(c, ext, trac, bq);
  a.part = part;
  set_grid(a, gm1, gp1, gf1);
  p2g_linear_3d(a);
  set_grid(a, gm2, gp2, gf2);
  reference(a);
  int touched = 0;
  for (Index i = 0; i < nn; ++i) {
    touched += gp1[i][0] != gp0[i][0] || gf1[i][1] != gf0[i][1];
    EXPECT_EQ(gm1[i], gm2[i]) << "node " << i;
    // A sum the part does not form is left exactly as it was.
    if (!maps_mass(part)) EXPECT_EQ(gm1[i], gm0[i]) << "node " << i;
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(gp1[i][d], gp2[i][d]) << "node " << i << " axis " << d;
      EXPECT_EQ(gf1[i][d], gf2[i][d]) << "node " << i << " axis " << d;
      if (!maps_momentum(part)) EXPECT_EQ(gp1[i][d], gp0[i][d]) << "node " << i << " axis " << d;
      if (!maps_forces(part)) EXPECT_EQ(gf1[i][d], gf0[i][d]) << "node " << i << " axis " << d;
    }
  }
  EXPECT_GT(touched, 20);  // the points reached many nodes: the comparison is not vacuous
}

TEST(P2gLinear3d, BitwiseTheGeneralLoopForSortedPoints) {
  expect_same_grid(400, true, P2gPart::All, false, false, false, 1);
  expect_same_grid(400, true, P2gPart::All, true, true, true, 2);
  expect_same_grid(400, true, P2gPart::All, true, false, true, 3);
}

TEST(P2gLinear3d, BitwiseTheGeneralLoopForScatteredPoints) {
  expect_same_grid(300, false, P2gPart::All, true, true, true, 4);
  expect_same_grid(300, false, P2gPart::All, false, false, false, 5);
}

TEST(P2gLinear3d, BitwiseTheGeneralLoopForMomentumOnly) {
  expect_same_grid(400, true, P2gPart::Momentum, false, false, false, 6);
  expect_same_grid(300, false, P2gPart::Momentum, true, true, true, 7);
}

// USAVG's two passes: mass and momentum first, then the forces.
TEST(P2gLinear3d, BitwiseTheGeneralLoopForEachPart) {
  expect_same_grid(400, true, P2gPart::Kinematics, true, true, true, 8);
  expect_same_grid(300, false, P2gPart::Forces, true, true, true, 9);
  expect_same_grid(400, true, P2gPart::Forces, false, false, false, 10);
}

// One point per cell: every point takes and writes back its cell's eight nodes.
TEST(P2gLinear3d, BitwiseTheGeneralLoopForOnePointPerCell) {
  expect_same_grid(120, true, P2gPart::All, true, true, true, 12, true);
  expect_same_grid(120, true, P2gPart::Momentum, false, false, false, 13, true);
  expect_same_grid(120, true, P2gPart::Kinematics, false, false, true, 14, true);
  expect_same_grid(120, true, P2gPart::Forces, true, false, true, 15, true);
  expect_same_grid(100, true, P2gPart::All, false, false, false, 16, true);  // rows cut short
}

// The two passes on a cleared grid form exactly the grid of one full pass.
TEST(P2gLinear3d, KinematicsThenForcesIsTheFullPass) {
  const Cloud c = make_cloud(400, true, 11);
  const Index nn = c.g.node_count();
  std::vector<double> gm1(nn, 0.0), gm2(nn, 0.0);
  std::vector<Vec3> gp1(nn), gp2(nn), gf1(nn), gf2(nn);
  P2gLinear3dArgs a = args_of(c, true, true, true);
  set_grid(a, gm1, gp1, gf1);
  p2g_linear_3d(a);
  set_grid(a, gm2, gp2, gf2);
  a.part = P2gPart::Kinematics;
  p2g_linear_3d(a);
  a.part = P2gPart::Forces;
  p2g_linear_3d(a);
  for (Index i = 0; i < nn; ++i) {
    EXPECT_EQ(gm1[i], gm2[i]) << "node " << i;
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(gp1[i][d], gp2[i][d]) << "node " << i << " axis " << d;
      EXPECT_EQ(gf1[i][d], gf2[i][d]) << "node " << i << " axis " << d;
    }
  }
}

}  // namespace
}  // namespace ballista
