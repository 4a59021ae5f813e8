// Erosion of failed points (thesis seed 000 §6.4, eq. 6.11-6.14) applied by MaterialAdapter after
// the kernel: each rule gives its stress exactly, the next step starts from the eroded stress,
// zero_stress freezes F, and erosion none leaves the stress untouched while damage evolves.
// Failure is triggered with linear_elastic + max_stress (analytic point tested in
// test_failure.cpp), so the stress the kernel produces is known in closed form.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "material_driver.hpp"
#include "materials/strain_increment.hpp"
#include "materials/eos.hpp"
#include "materials/failure.hpp"

namespace test_erosion {

using namespace ballista;
using namespace ballista::test;

namespace {

constexpr double kK = 160e9, kG = 79e9, kSmax = 2.0e8;

ParamValues steel(const std::string& criterion, const std::string& erosion, double smax = kSmax) {
  ParamValues v{{"density", 7850}, {"bulk_modulus", kK}, {"shear_modulus", kG}, {"failure.max_stress", smax}};
  v.choices["failure.criterion"] = criterion;
  v.choices["failure.erosion"] = erosion;
  return v;
}

bool same_bits(const Mat3& a, const Mat3& b) { return std::memcmp(a.a, b.a, sizeof a.a) == 0; }

/// Uniaxial strain F11 = 1 + e(n) under a rotation about a skew axis that turns with time (so the
/// unrotated and spatial frames differ and the eroded stress must be isotropic in both).
Mat3 path_F(double F11, int n) {
  return rotation_about(Vec3{{0.6, 0.0, 0.8}}, 1e-3 * n) * Mat3::diag(F11, 1.0, 1.0);
}

/// Mean stress I1/3 of the hypoelastic kernel after one step from an isotropic stress m I:
/// m + K tr(D) dt, D dt the midpoint increment of G = dt L the adapter hands the kernel
/// (materials/strain_increment.hpp; its trace is rotation-invariant).
double next_mean(double m, const Mat3& L, double dt) { return m + kK * trace(midpoint_strain_increment(dt * L)); }

}  // namespace

// erode() on an arbitrary stress: eq. 6.11-6.13 exactly.
TEST(Erosion, RulesOnAStress) {
  const Mat3 s{{-3e8, 1e7, 2e7, 1e7, 5e7, -4e7, 2e7, -4e7, -1e8}};  // I1 = -3.5e8
  const double m = trace(s) / 3.0;
  Mat3 a = s;
  erode(ErosionRule::None, a);
  EXPECT_TRUE(same_bits(a, s));
  a = s;
  erode(ErosionRule::AllowNoShear, a);
  EXPECT_TRUE(same_bits(a, Mat3::diag(m, m, m)));
  a = s;
  erode(ErosionRule::AllowNoTension, a);  // I1 <= 0: hydrostatic
  EXPECT_TRUE(same_bits(a, Mat3::diag(m, m, m)));
  Mat3 t = (-1.0) * s;  // I1 > 0: nothing
  erode(ErosionRule::AllowNoTension, t);
  EXPECT_TRUE(same_bits(t, Mat3{}));
  a = s;
  erode(ErosionRule::ZeroStress, a);
  EXPECT_TRUE(same_bits(a, Mat3{}));
}

// failure.erosion none: damage and failed evolve, the stress is not modified (thesis: "none" still
// evolves damage but does not modify stress). Bit for bit against the same criterion with a
// sigma_max never reached (same compiled path); against the material without a criterion to
// 1e-13 relative (a separately compiled loop: -march=native may contract a*b+c into FMAs
// differently, 1 ulp per operation over 300 steps).
TEST(Erosion, NoneKeepsTheStressWhileDamageEvolves) {
  PointDriver plain("linear_elastic", steel("none", "none"));
  PointDriver unfailed("linear_elastic", steel("max_stress", "none", 1e30));
  PointDriver damaged("linear_elastic", steel("max_stress", "none"));
  int n_fail = 0;
  for (int n = 1; n <= 300; ++n) {
    const Mat3 F = path_F(1.0 - 1e-5 * n, n);
    plain.advance(F, 1e-7);
    unfailed.advance(F, 1e-7);
    damaged.advance(F, 1e-7);
    ASSERT_TRUE(same_bits(unfailed.stress(), damaged.stress())) << "step " << n;
    ASSERT_LT(rel_diff(plain.stress(), damaged.stress()), 1e-13) << "step " << n;
    ASSERT_EQ(unfailed.state(kFailedField), 0.0);
    if (n_fail == 0 && damaged.state(kFailedField) == 1.0) n_fail = n;
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_LT(n_fail, 300);
  EXPECT_EQ(damaged.state(kDamageField), 1.0);
}

// allow_no_shear (eq. 6.12): up to the failure step the stress is the model's (bitwise); at it,
// sigma* = I1/3 I of the model's stress exactly (the run with erosion none gives that stress);
// afterwards the stress stays isotropic and its mean evolves from the eroded state as the
// kernel's pressure increment, m_{n+1} = m_n + K tr(D) dt (relative 1e-12: rotations round-off).
TEST(Erosion, AllowNoShearKeepsOnlyTheMeanStress) {
  PointDriver ref("linear_elastic", steel("max_stress", "none"));
  PointDriver ero("linear_elastic", steel("max_stress", "allow_no_shear"));
  const double dt = 1e-7;
  int n_fail = 0;
  double m = 0.0;
  for (int n = 1; n <= 300; ++n) {
    const Mat3 F = path_F(1.0 - 1e-5 * n, n);
    ref.advance(F, dt);
    ero.advance(F, dt);
    const Mat3& s = ero.stress();
    if (ero.state(kFailedField) == 0.0) {
      ASSERT_TRUE(same_bits(s, ref.stress())) << n;
      continue;
    }
    if (n_fail == 0) {
      n_fail = n;
      const double mean = trace(ref.stress()) / 3.0;
      EXPECT_TRUE(same_bits(s, Mat3::diag(mean, mean, mean))) << n;
      m = mean;
      continue;
    }
    m = next_mean(m, ero.store().view<Mat3>("L")[0], dt);
    for (auto [i, j] : {std::pair{0, 1}, {1, 0}, {0, 2}, {2, 0}, {1, 2}, {2, 1}}) ASSERT_EQ(s(i, j), 0.0);
    ASSERT_EQ(s(0, 0), s(1, 1));
    ASSERT_EQ(s(0, 0), s(2, 2));
    ASSERT_NEAR(s(0, 0), m, 1e-12 * std::abs(m)) << n;
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_LT(m, 0.0);
}

// allow_no_tension (eq. 6.11): fail in compression (the stress becomes I1/3 I), then pull back into
// tension: the eroded mean follows m + K tr(D) dt while it is <= 0 and the stress is exactly 0
// once the kernel's I1 would be > 0.
TEST(Erosion, AllowNoTensionDropsTensionKeepsPressure) {
  PointDriver ref("linear_elastic", steel("max_stress", "none"));
  PointDriver ero("linear_elastic", steel("max_stress", "allow_no_tension"));
  const double dt = 1e-7;
  int n_fail = 0, n_tension = 0, n_compressed = 0;
  double m = 0.0;
  double F11 = 1.0;
  for (int n = 1; n <= 700; ++n) {
    F11 += n <= 250 ? -1e-5 : 1e-5;  // compress, then stretch back beyond F11 = 1
    ref.advance(path_F(F11, n), dt);
    ero.advance(path_F(F11, n), dt);
    const Mat3& s = ero.stress();
    if (ero.state(kFailedField) == 0.0) continue;
    if (n_fail == 0) {
      n_fail = n;
      const double mean = trace(ref.stress()) / 3.0;
      ASSERT_LE(mean, 0.0);
      EXPECT_TRUE(same_bits(s, Mat3::diag(mean, mean, mean)));
      m = mean;
      continue;
    }
    const double kernel_mean = next_mean(m, ero.store().view<Mat3>("L")[0], dt);
    if (kernel_mean <= 0.0) {
      ++n_compressed;
      m = kernel_mean;
      ASSERT_NEAR(s(0, 0), m, 1e-12 * std::abs(m) + 1e-3) << n;
      ASSERT_EQ(s(0, 0), s(1, 1));
      ASSERT_EQ(s(0, 1), 0.0);
    } else {
      ++n_tension;
      m = 0.0;
      ASSERT_TRUE(same_bits(s, Mat3{})) << n;
    }
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_GT(n_compressed, 50);
  EXPECT_GT(n_tension, 50);
}

// zero_stress (eq. 6.13-6.14) with F_n given (single-element driver path): from the failure step
// on the stress is exactly 0, and F and R are reset to their values at t_n, bit for bit.
TEST(Erosion, ZeroStressFreezesFWithFOldGiven) {
  PointDriver d("linear_elastic", steel("max_stress", "zero_stress"));
  int n_fail = 0;
  for (int n = 1; n <= 300; ++n) {
    const Mat3 F_before = d.F(), R_before = d.R();
    d.advance(path_F(1.0 - 1e-5 * n, n), 1e-7);
    if (d.state(kFailedField) == 0.0) continue;
    if (n_fail == 0) n_fail = n;
    ASSERT_TRUE(same_bits(d.stress(), Mat3{})) << n;
    ASSERT_TRUE(same_bits(d.F(), F_before)) << n;
    ASSERT_TRUE(same_bits(d.R(), R_before)) << n;
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_LT(n_fail, 280);
}

// zero_stress in a solver-like batch (F_old not stored: F_{n+1} = (I + dt L) F_n and the adapter
// recovers F_n = (I + dt L)^-1 F_{n+1}): the failed point's J stays at its value at failure over
// the following steps (1e-14: one inverse per step), its stress and stress power are 0, while the
// other point of the batch, which does not fail, keeps deforming.
TEST(Erosion, ZeroStressFreezesJInASolverBatch) {
  const auto mat = make_material("linear_elastic", steel("max_stress", "zero_stress"));
  FieldStore st;
  for (const char* f : {"F", "L", "R", "stress"}) st.add_real(f, 9, "1");
  st.add_real("volume0", 1, "m^3", true, 1e-9);
  st.add_real("internal_energy", 1, "J");
  st.add_real("plastic_work", 1, "J");
  mat->declare_fields(st);
  st.resize(2);
  for (Index p = 0; p < 2; ++p) st.view<Mat3>("F")[p] = st.view<Mat3>("R")[p] = Mat3::identity();
  const std::vector<Index> pts{0, 1};
  const double dt = 1e-7;
  // Point 0: fast compression with spin; point 1: a hundred times slower (stays below sigma_max).
  Mat3 L0 = Mat3::diag(-100.0, 0.0, 0.0);
  L0(0, 1) = 30.0;
  L0(1, 0) = -30.0;
  const Mat3 L1 = 0.01 * L0;
  int n_fail = 0;
  double J_fail = 0.0, E_fail = 0.0, J1_prev = 1.0;
  for (int n = 1; n <= 400; ++n) {
    Mat3* F = st.view<Mat3>("F");
    st.view<Mat3>("L")[0] = L0;
    st.view<Mat3>("L")[1] = L1;
    F[0] = (Mat3::identity() + dt * L0) * F[0];
    F[1] = (Mat3::identity() + dt * L1) * F[1];
    MaterialBatch b;
    b.points = pts.data();
    b.count = 2;
    b.F_new = F;
    b.L = st.view<Mat3>("L");
    b.R = st.view<Mat3>("R");
    b.stress = st.view<Mat3>("stress");
    b.store = &st;
    b.dt = dt;
    b.volume0 = st.real("volume0");
    b.internal_energy = st.real("internal_energy");
    b.plastic_energy = st.real("plastic_work");
    mat->update(b);
    ASSERT_EQ(st.real(kFailedField)[1], 0.0);
    EXPECT_LT(det(F[1]), J1_prev);  // point 1 keeps compressing
    J1_prev = det(F[1]);
    if (st.real(kFailedField)[0] == 0.0) continue;
    if (n_fail == 0) {
      n_fail = n;
      J_fail = det(F[0]);
      E_fail = st.real("internal_energy")[0];
      continue;
    }
    ASSERT_NEAR(det(F[0]), J_fail, 1e-14) << n;
    ASSERT_TRUE(same_bits(st.view<Mat3>("stress")[0], Mat3{}));
    ASSERT_EQ(st.real("internal_energy")[0], E_fail);  // 0.5 (0 + 0) : D
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_LT(n_fail, 350);
  EXPECT_GT(E_fail, 0.0);
}

// zero_stress freezes the model's state with F (eq. 6.14): a Johnson-Cook point with a
// Mie-Gruneisen EOS (OFHC copper constants, Johnson & Cook 1983 and the EOS of test_eos.cpp) that
// fails by max_stress under fast compression keeps its EOS energy, temperature and plastic strain
// bit for bit while the compression goes on, and so its dilatational wave speed. Its kernel would
// otherwise advance them along a volume change the point does not take: the EOS energy grew by
// p dV every step (to 5e8 J/kg in a tungsten rod's eroded head) and the time step fell 100x.
TEST(Erosion, ZeroStressFreezesTheModelsState) {
  ParamValues v{{"density", 8930.0}, {"bulk_modulus", 137e9}, {"shear_modulus", 45e9}, {"jc_a", 90e6},
                {"jc_b", 292e6},     {"jc_n", 0.31},          {"jc_c", 0.025},        {"jc_m", 1.09},
                {"melt_temperature", 1356.0}, {"specific_heat", 383.0}, {"eos.sound_speed", 3940.0},
                {"eos.hugoniot_slope", 1.49}, {"eos.gruneisen_gamma", 2.0}, {"failure.max_stress", 2.0e8}};
  v.choices["eos.type"] = "mie_gruneisen";
  v.choices["failure.criterion"] = "max_stress";
  v.choices["failure.erosion"] = "zero_stress";
  PointDriver d("johnson_cook", v);
  const auto mat = make_material("johnson_cook", v);
  const char* frozen[3] = {kEosEnergyField, "temperature", "eqps"};
  int n_fail = 0;
  double at_fail[3] = {0, 0, 0}, c_fail = 0.0;
  for (int n = 1; n <= 400; ++n) {
    // Uniaxial compression at 1e5 1/s with a shear that makes the point yield before it fails.
    Mat3 F = Mat3::diag(1.0 - 1e-4 * n, 1.0, 1.0);
    F(0, 1) = 2e-4 * n;
    d.advance(F, 1e-9);
    if (d.state(kFailedField) == 0.0) continue;
    const double c = mat->wave_speed(d.store(), 0, det(d.F()));
    if (n_fail == 0) {
      n_fail = n;
      for (int k = 0; k < 3; ++k) at_fail[k] = d.state(frozen[k]);
      c_fail = c;
      continue;
    }
    for (int k = 0; k < 3; ++k) ASSERT_EQ(d.state(frozen[k]), at_fail[k]) << frozen[k] << " at step " << n;
    ASSERT_EQ(c, c_fail) << n;
  }
  EXPECT_GT(n_fail, 1);
  EXPECT_LT(n_fail, 300);
  EXPECT_GT(at_fail[2], 0.0) << "the point should have yielded before it failed";
}

// With a criterion and erosion the batch result does not depend on the number of threads.
TEST(Erosion, ThreadCountIndependent) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.004, 0.004);
  const Index n = 5000;  // above the parallel threshold
  std::vector<Mat3> F(n);
  for (auto& f : F) {
    f = Mat3::identity();
    for (double& a : f.a) a += u(rng);
  }
  auto run = [&](int threads) {
    const int saved = max_threads();
    set_threads(threads);
    PointDriver d("linear_elastic", steel("max_stress", "zero_stress", 2e9), n);
    std::vector<Mat3> out;
    for (int step = 1; step <= 3; ++step) {
      d.set_dt(1e-7);
      for (Index p = 0; p < n; ++p) d.set_F(p, Mat3::identity() + step * (F[p] - Mat3::identity()));
      d.step(1e-7);
    }
    set_threads(saved);
    int failed = 0;
    for (Index p = 0; p < n; ++p) {
      out.push_back(d.stress(p));
      out.push_back(d.F(p));
      failed += d.state(kFailedField, p) == 1.0;
    }
    EXPECT_GT(failed, 100);
    EXPECT_LT(failed, n - 100);
    return out;
  };
  const auto a = run(1), b = run(2);
  for (size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(same_bits(a[k], b[k])) << k;
}

}  // namespace test_erosion
