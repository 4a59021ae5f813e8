// CellFBar (src/mpm/anti_locking.hpp; Coombs, Charlton, Cortis & Augarde, CMAME 333 (2018) 1):
//  - a deformation that is uniform over a cell is left unchanged;
//  - points of one cell end with the cell's volume ratio dJbar = V_c^{n+1} / V_c^n, the cell's
//    volume is unchanged, each point's isochoric part dF / dJ^(1/m) is kept, and the rewritten L
//    reproduces the rewritten F (F_{n+1} = (I + dt Lbar) F_n, which the material adapter relies on);
//  - plane strain scales only the in-plane block (F_zz = 1, L_zz = 0 stay); axisymmetric scales
//    the hoop component too;
//  - points in different cells do not interact;
//  - each material of a cell is averaged on its own (a second material in the cell changes
//    nothing of the first's result);
//  - the forces' pressure (force_pressure) is the volume average of p + q over the point's
//    material in its cell, by hand, and the work the forces do with it equals the work the
//    averaged rates book (the mean-dilatation identity sum V_p Pbar tr L_p = sum V_p P_p tr Lbar);
//  - with patches of k cells per axis (set_patch), points in different cells of one patch get the
//    patch's volume ratio and the patch's volume is unchanged, a point alone in its cell is
//    averaged with its patch, patches do not interact, and the forces read the patch's pressure;
//  - the result is bitwise the same on 1 and 2 threads.
// Tolerances: every quantity is a handful of flops from its inputs (a cube root, a 3x3
// determinant), so 1e-13 relative is ~100 ulp of slack over the round-off of the formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "mpm/anti_locking.hpp"

namespace test_anti_locking {

using namespace ballista;

namespace {

GridGeometry grid(int dim) {
  GridGeometry g;
  g.h = 0.5;
  g.dim = dim;
  for (int a = 0; a < 3; ++a) g.nodes[a] = a < dim ? 8 : 1;
  return g;
}

struct Points {
  std::vector<Vec3> x;
  std::vector<Mat3> L, F, Fn;
  std::vector<double> vol, vol0;
  /// A point at x with F_n, velocity gradient L and reference volume v0, after the standard update
  /// F_{n+1} = (I + dt L) F_n, V = V0 det F_{n+1} (what the solver hands to CellFBar).
  void add(const Vec3& at, const Mat3& fn, const Mat3& l, double v0, double dt) {
    x.push_back(at);
    Fn.push_back(fn);
    L.push_back(l);
    F.push_back((Mat3::identity() + dt * l) * fn);
    vol0.push_back(v0);
    vol.push_back(v0 * det(F.back()));
  }
  FBarPoints view() { return {static_cast<Index>(x.size()), x.data(), L.data(), F.data(), vol.data(), vol0.data()}; }
};

Mat3 mat(double a00, double a01, double a02, double a10, double a11, double a12, double a20, double a21, double a22) {
  Mat3 m;
  const double v[9] = {a00, a01, a02, a10, a11, a12, a20, a21, a22};
  for (int k = 0; k < 9; ++k) m.a[k] = v[k];
  return m;
}

double max_abs_diff(const Mat3& a, const Mat3& b) {
  double d = 0.0;
  for (int k = 0; k < 9; ++k) d = std::max(d, std::abs(a.a[k] - b.a[k]));
  return d;
}

constexpr double kDt = 1e-3;
constexpr double kTol = 1e-13;

}  // namespace

TEST(AntiLocking, ParsesNames) {
  EXPECT_EQ(parse_anti_locking("none"), AntiLocking::None);
  EXPECT_EQ(parse_anti_locking("FBar"), AntiLocking::FBar);
  EXPECT_THROW(parse_anti_locking("bbar"), Error);
  EXPECT_EQ(anti_locking_names(), (std::vector<std::string>{"none", "fbar"}));
}

TEST(AntiLocking, UniformCellIsUnchanged) {
  Points p;
  const Mat3 l = mat(3.0, 1.0, 0.5, -2.0, 1.0, 0.2, 0.1, 0.3, -4.0);
  const Mat3 fn = mat(1.01, 0.02, 0.0, 0.01, 0.99, 0.03, 0.0, 0.0, 1.02);
  for (int k = 0; k < 4; ++k) p.add({{0.6 + 0.1 * k, 0.7, 0.8}}, fn, l, 0.01 * (k + 1), kDt);
  const Points before = p;
  CellFBar fbar;
  fbar.apply(grid(3), Dimension::ThreeD, kDt, p.view());
  for (size_t k = 0; k < p.x.size(); ++k) {
    EXPECT_LT(max_abs_diff(p.F[k], before.F[k]), kTol);
    EXPECT_LT(max_abs_diff(p.L[k], before.L[k]), kTol * 10.0 / kDt);  // (s - 1)/dt: round-off / dt
    EXPECT_NEAR(p.vol[k], before.vol[k], kTol * before.vol[k]);
  }
}

TEST(AntiLocking, CellAverageOfTheVolumeRatio3D) {
  // Two points in cell (1,1,1), one in cell (2,1,1) (h = 0.5).
  Points p;
  const Mat3 l1 = mat(40.0, 5.0, 0.0, 0.0, -10.0, 3.0, 1.0, 0.0, 20.0);
  const Mat3 l2 = mat(-30.0, 0.0, 2.0, 7.0, 5.0, 0.0, 0.0, -1.0, -15.0);
  const Mat3 fn1 = mat(1.02, 0.01, 0.0, 0.0, 0.98, 0.0, 0.0, 0.02, 1.0);
  const Mat3 fn2 = Mat3::identity();
  p.add({{0.6, 0.7, 0.8}}, fn1, l1, 0.002, kDt);
  p.add({{0.9, 0.55, 0.6}}, fn2, l2, 0.003, kDt);
  p.add({{1.2, 0.7, 0.8}}, fn2, l1, 0.004, kDt);
  const Points before = p;
  CellFBar fbar;
  fbar.apply(grid(3), Dimension::ThreeD, kDt, p.view());
  const double vn = before.vol[0] + before.vol[1];
  const double dJ[2] = {det(Mat3::identity() + kDt * l1), det(Mat3::identity() + kDt * l2)};
  const double vo = before.vol[0] / dJ[0] + before.vol[1] / dJ[1];
  const double dJbar = vn / vo;
  EXPECT_NEAR(p.vol[0] + p.vol[1], vn, kTol * vn);  // the cell's volume is that of the plain update
  for (int k = 0; k < 2; ++k) {
    const Mat3 dF = Mat3::identity() + kDt * p.L[k];
    EXPECT_NEAR(det(dF), dJbar, kTol) << k;                       // every point gets the cell's ratio
    EXPECT_LT(max_abs_diff(dF * before.Fn[k], p.F[k]), kTol) << k;  // Lbar reproduces Fbar
    EXPECT_NEAR(p.vol[k], p.vol0[k] * det(p.F[k]), kTol * p.vol[k]) << k;
    // Isochoric part unchanged: Fbar_{n+1} = (dJbar / dJ)^(1/3) F_{n+1}.
    EXPECT_LT(max_abs_diff(p.F[k], std::cbrt(dJbar / dJ[k]) * before.F[k]), kTol) << k;
  }
  EXPECT_GT(std::abs(dJ[0] - dJ[1]), 1e-2);  // the test means something
  // Alone in its cell: unchanged.
  EXPECT_LT(max_abs_diff(p.F[2], before.F[2]), kTol);
  EXPECT_NEAR(p.vol[2], before.vol[2], kTol * before.vol[2]);
}

TEST(AntiLocking, PlaneStrainScalesTheInPlaneBlockOnly) {
  Points p;
  p.add({{0.6, 0.7, 0.0}}, Mat3::identity(), mat(40.0, 5.0, 0.0, 2.0, -10.0, 0.0, 0.0, 0.0, 0.0), 0.002, kDt);
  p.add({{0.8, 0.9, 0.0}}, Mat3::identity(), mat(-20.0, 0.0, 0.0, 7.0, -5.0, 0.0, 0.0, 0.0, 0.0), 0.002, kDt);
  const Points before = p;
  CellFBar fbar;
  fbar.apply(grid(2), Dimension::PlaneStrain, kDt, p.view());
  const double dJ0 = det(Mat3::identity() + kDt * before.L[0]);
  const double dJ1 = det(Mat3::identity() + kDt * before.L[1]);
  const double dJbar = (before.vol[0] + before.vol[1]) / (before.vol[0] / dJ0 + before.vol[1] / dJ1);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(p.F[k](2, 2), 1.0);
    EXPECT_EQ(p.L[k](2, 2), 0.0);
    EXPECT_EQ(p.F[k](0, 2), 0.0);
    EXPECT_NEAR(det(Mat3::identity() + kDt * p.L[k]), dJbar, kTol);
  }
}

TEST(AntiLocking, AxisymmetricScalesTheHoopComponent) {
  Points p;
  p.add({{0.6, 0.7, 0.0}}, Mat3::identity(), mat(40.0, 5.0, 0.0, 2.0, -10.0, 0.0, 0.0, 0.0, 30.0), 0.002, kDt);
  p.add({{0.8, 0.9, 0.0}}, Mat3::identity(), mat(-20.0, 0.0, 0.0, 7.0, -5.0, 0.0, 0.0, 0.0, -8.0), 0.002, kDt);
  const Points before = p;
  CellFBar fbar;
  fbar.apply(grid(2), Dimension::Axisymmetric, kDt, p.view());
  const double dJ0 = det(Mat3::identity() + kDt * before.L[0]);
  const double dJ1 = det(Mat3::identity() + kDt * before.L[1]);
  const double dJbar = (before.vol[0] + before.vol[1]) / (before.vol[0] / dJ0 + before.vol[1] / dJ1);
  for (int k = 0; k < 2; ++k) {
    const double dJ = k ? dJ1 : dJ0;
    EXPECT_NEAR(det(Mat3::identity() + kDt * p.L[k]), dJbar, kTol);
    EXPECT_NEAR(p.F[k](2, 2), std::cbrt(dJbar / dJ) * before.F[k](2, 2), kTol);
  }
}

TEST(AntiLocking, EachMaterialOfACellIsAveragedOnItsOwn) {
  // Cell (1,1,1) holds two points of material 0 and one of material 1, which expands while they
  // compress. Material 0's result must be what it is without the third point; the third point,
  // alone in its (cell, material), is unchanged.
  const Mat3 l1 = mat(40.0, 5.0, 0.0, 0.0, -10.0, 3.0, 1.0, 0.0, 20.0);
  const Mat3 l2 = mat(-30.0, 0.0, 2.0, 7.0, 5.0, 0.0, 0.0, -1.0, -15.0);
  const Mat3 l3 = mat(90.0, 0.0, 0.0, 0.0, 80.0, 0.0, 0.0, 0.0, 70.0);
  Points two, three;
  for (Points* p : {&two, &three}) {
    p->add({{0.6, 0.7, 0.8}}, Mat3::identity(), l1, 0.002, kDt);
    p->add({{0.9, 0.55, 0.6}}, Mat3::identity(), l2, 0.003, kDt);
  }
  three.add({{0.7, 0.6, 0.9}}, Mat3::identity(), l3, 0.004, kDt);
  const Points before = three;
  const std::int64_t mat2[] = {0, 0}, mat3[] = {0, 0, 1};
  FBarPoints v2 = two.view(), v3 = three.view();
  v2.material = mat2;
  v2.materials = 2;
  v3.material = mat3;
  v3.materials = 2;
  CellFBar fbar;
  fbar.apply(grid(3), Dimension::ThreeD, kDt, v2);
  fbar.apply(grid(3), Dimension::ThreeD, kDt, v3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(std::memcmp(&two.F[k], &three.F[k], sizeof(Mat3)), 0) << k;
    EXPECT_EQ(two.vol[k], three.vol[k]) << k;
  }
  EXPECT_LT(max_abs_diff(three.F[2], before.F[2]), kTol);
  EXPECT_NEAR(three.vol[2], before.vol[2], kTol * before.vol[2]);
  // Without the material index the three are averaged together, and material 0 changes.
  Points all = before;
  fbar.apply(grid(3), Dimension::ThreeD, kDt, all.view());
  EXPECT_GT(std::abs(all.vol[0] - three.vol[0]), 1e-3 * three.vol[0]);
}

TEST(AntiLocking, ForcesReadTheCellAveragedPressureOfTheirMaterial) {
  // Cell (1,1,1): points 0 and 1 of material 0 and point 2 of material 1; point 3 of material 0
  // in cell (2,1,1). Stresses with different pressures, and a bulk viscosity q.
  CellFBar fbar;
  const Vec3 x[] = {{{0.6, 0.7, 0.8}}, {{0.9, 0.55, 0.6}}, {{0.7, 0.6, 0.9}}, {{1.2, 0.7, 0.8}}};
  const double vol[] = {0.002, 0.003, 0.004, 0.005};
  const Mat3 s[] = {mat(-3e9, 1e8, 0.0, 1e8, -1e9, 0.0, 0.0, 0.0, -2e9),
                    mat(-9e9, 0.0, 5e7, 0.0, -6e9, 0.0, 5e7, 0.0, -3e9),
                    mat(2e8, 0.0, 0.0, 0.0, 1e8, 0.0, 0.0, 0.0, 0.0),
                    mat(-4e9, 0.0, 0.0, 0.0, -4e9, 0.0, 0.0, 0.0, -4e9)};
  const double q[] = {1e8, 4e8, 3e7, 2e8};
  const std::int64_t material[] = {0, 0, 1, 0};
  std::vector<double> out;
  fbar.force_pressure(grid(3), {4, x, vol, s, q, material, 2}, out);
  const double P[] = {2e9 + 1e8, 6e9 + 4e8, -1e8 + 3e7, 4e9 + 2e8};  // p + q, p = -tr(sigma)/3
  const double pbar01 = (vol[0] * P[0] + vol[1] * P[1]) / (vol[0] + vol[1]);
  const double expected[] = {pbar01 - 2e9, pbar01 - 6e9, P[2] + 1e8, P[3] - 4e9};  // Pbar + tr/3
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(out[k], expected[k], 1e-13 * 1e10) << k;
  // Each forced point's isotropic stress is -Pbar: sigma - out I has trace -3 Pbar.
  EXPECT_NEAR((s[0](0, 0) + s[0](1, 1) + s[0](2, 2)) / 3.0 - out[0], -pbar01, 1e-13 * 1e10);
  // The mean-dilatation identity: with every point of a group at its cell's volume ratio
  // (tr Lbar_c, what apply() hands the materials), the forces' work sum V Pbar tr L_p equals the
  // work the materials book, sum V P_p tr Lbar_c, when sum V tr L_p = V_c tr Lbar_c.
  const double trL[] = {30.0, -60.0};
  const double trLbar = (vol[0] * trL[0] + vol[1] * trL[1]) / (vol[0] + vol[1]);
  double forces = 0.0;  // the forces' pressure: -tr(sigma - out I) / 3 = -tr(sigma) / 3 + out
  for (int k = 0; k < 2; ++k)
    forces += vol[k] * (-(s[k](0, 0) + s[k](1, 1) + s[k](2, 2)) / 3.0 + out[k]) * trL[k];
  const double booked = vol[0] * P[0] * trLbar + vol[1] * P[1] * trLbar;
  EXPECT_NEAR(forces, booked, 1e-12 * std::abs(booked));
  // Without the pairing the two differ: what the demo's energy audit showed.
  const double unpaired = vol[0] * P[0] * trL[0] + vol[1] * P[1] * trL[1];
  EXPECT_GT(std::abs(unpaired - booked), 0.1 * std::abs(booked));
}

TEST(AntiLocking, PatchesAverageOverBlocksOfCells) {
  // h = 0.5, patches of 2 x 2 cells in an axisymmetric grid: cells (0,0) and (1,1) lie in patch
  // (0,0); cell (2,0) starts the next patch. Point 0 is alone in its cell and compressed hard (a
  // thinned jet point), points 1 and 2 share the other cell of the patch, point 3 is in the next
  // patch.
  Points p;
  p.add({{0.3, 0.2, 0.0}}, Mat3::identity(), mat(-200.0, 0.0, 0.0, 0.0, -150.0, 0.0, 0.0, 0.0, 40.0), 0.002, kDt);
  p.add({{0.6, 0.7, 0.0}}, Mat3::identity(), mat(10.0, 5.0, 0.0, 2.0, -10.0, 0.0, 0.0, 0.0, 5.0), 0.003, kDt);
  p.add({{0.9, 0.9, 0.0}}, Mat3::identity(), mat(-5.0, 0.0, 0.0, 1.0, 8.0, 0.0, 0.0, 0.0, -2.0), 0.004, kDt);
  p.add({{1.1, 0.3, 0.0}}, Mat3::identity(), mat(-90.0, 0.0, 0.0, 0.0, -90.0, 0.0, 0.0, 0.0, 0.0), 0.005, kDt);
  const Points before = p;
  CellFBar fbar;
  fbar.set_patch(2);
  fbar.apply(grid(2), Dimension::Axisymmetric, kDt, p.view());
  double vn = 0.0, vo = 0.0;
  for (int k = 0; k < 3; ++k) {
    vn += before.vol[k];
    vo += before.vol[k] / det(Mat3::identity() + kDt * before.L[k]);
  }
  const double dJbar = vn / vo;
  double vsum = 0.0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(det(Mat3::identity() + kDt * p.L[k]), dJbar, kTol) << k;  // the patch's ratio
    EXPECT_LT(max_abs_diff((Mat3::identity() + kDt * p.L[k]) * before.Fn[k], p.F[k]), kTol) << k;
    vsum += p.vol[k];
  }
  EXPECT_NEAR(vsum, vn, kTol * vn);  // the patch's volume is that of the plain update
  // The lone point's own ratio (0.71) would have stood with cell averages; the patch lifts it.
  EXPECT_LT(det(Mat3::identity() + kDt * before.L[0]), 0.72);
  EXPECT_GT(dJbar, 0.85);
  // Alone in its patch: unchanged.
  EXPECT_LT(max_abs_diff(p.F[3], before.F[3]), kTol);
  // With each cell on its own the lone point keeps its ratio: what the patch changes.
  Points cells = before;
  CellFBar per_cell;
  per_cell.apply(grid(2), Dimension::Axisymmetric, kDt, cells.view());
  EXPECT_LT(max_abs_diff(cells.F[0], before.F[0]), kTol);
  // The forces read the patch's volume-averaged pressure.
  const Vec3 x[] = {before.x[0], before.x[1], before.x[3]};
  const double vol[] = {0.002, 0.003, 0.005};
  const Mat3 s[] = {mat(-9e10, 0.0, 0.0, 0.0, -9e10, 0.0, 0.0, 0.0, -9e10),
                    mat(-1e9, 0.0, 0.0, 0.0, -2e9, 0.0, 0.0, 0.0, -3e9),
                    mat(-4e9, 0.0, 0.0, 0.0, -4e9, 0.0, 0.0, 0.0, -4e9)};
  std::vector<double> out;
  fbar.force_pressure(grid(2), {3, x, vol, s, nullptr, nullptr, 1}, out);
  const double pbar = (vol[0] * 9e10 + vol[1] * 2e9) / (vol[0] + vol[1]);
  EXPECT_NEAR(out[0], pbar - 9e10, 1e-13 * 1e11);
  EXPECT_NEAR(out[1], pbar - 2e9, 1e-13 * 1e11);
  EXPECT_NEAR(out[2], 0.0, 1e-13 * 1e10);  // alone in its patch: its own pressure
}

TEST(AntiLocking, BitwiseIndependentOfThreadCount) {
  // 20,000 random points (above the 4096-point parallel threshold) on a 3D grid.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0.0, 3.99), grad(-50.0, 50.0);
  Points p;
  for (int k = 0; k < 20000; ++k) {
    Mat3 l;
    for (int c = 0; c < 9; ++c) l.a[c] = grad(rng);
    p.add({{pos(rng), pos(rng), pos(rng)}}, Mat3::identity(), l, 1e-4, kDt);
  }
  const int saved = max_threads();
  Points a = p, b = p;
  CellFBar fbar;
  set_threads(1);
  fbar.apply(grid(3), Dimension::ThreeD, kDt, a.view());
  set_threads(2);
  fbar.apply(grid(3), Dimension::ThreeD, kDt, b.view());
  set_threads(saved);
  EXPECT_EQ(std::memcmp(a.F.data(), b.F.data(), a.F.size() * sizeof(Mat3)), 0);
  EXPECT_EQ(std::memcmp(a.L.data(), b.L.data(), a.L.size() * sizeof(Mat3)), 0);
  EXPECT_EQ(std::memcmp(a.vol.data(), b.vol.data(), a.vol.size() * sizeof(double)), 0);
}

}  // namespace test_anti_locking
