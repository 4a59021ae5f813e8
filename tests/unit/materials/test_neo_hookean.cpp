#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "material_driver.hpp"
#include "tangent_check.hpp"

namespace test_neo_hookean {

using namespace ballista;
using namespace ballista::test;

namespace {

// CATALOGUE B1 constants: mu = 3846.15, K = 8333.33, rho0 = 1  ->  lambda = K - 2 mu/3.
constexpr double kK = 8333.33, kMu = 3846.15, kRho = 1.0;
constexpr double kLam = kK - 2.0 * kMu / 3.0;

ParamValues nh_params() { return elastic_kg(kRho, kK, kMu); }

// Independent closed form, CATALOGUE B1: sigma = [lambda ln J I + mu (F F^T - I)]/J.
Mat3 closed_form(const Mat3& F) {
  const double J = det(F);
  Mat3 s = (kMu / J) * (F * transpose(F) - Mat3::identity());
  const double iso = kLam * std::log(J) / J;
  for (int i = 0; i < 3; ++i) s(i, i) += iso;
  return s;
}

Mat3 random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 axis{{u(rng), u(rng), u(rng)}};
  axis = (1.0 / norm(axis)) * axis;
  return rotation_about(axis, 3.1 * u(rng));
}

// Random F = Q (I + 0.6 A) with A uniform in [-1,1]^9 (stretches roughly 0.3..2), det F > 0.
Mat3 random_F(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Mat3 A;
    for (double& a : A.a) a = 0.6 * u(rng);
    const Mat3 F = random_rotation(rng) * (Mat3::identity() + 0.5 * A);
    if (det(F) > 0.2) return F;
  }
}

// Scale for relative comparisons of a stress: its own size plus mu (so near-zero stresses are
// compared in units of the modulus).
double scale_of(const Mat3& s) { return frobenius(s) + kMu; }

}  // namespace

// One adapter step from F = I to a random F (dt = 1; the stress of a hyperelastic model does not
// depend on the path) must give the closed form. The adapter computes R of F by Newton iteration
// (round-off 1e-15) and forms R [lambda ln J I + mu (C - I)]/J R^T, so 1e-12 relative.
// initial_stress(F) uses the spatial form directly: same tolerance.
TEST(NeoHookean, StressMatchesClosedFormForRandomF) {
  std::mt19937 rng(7);
  const int n = 200;
  PointDriver d("neo_hookean", nh_params(), n);
  std::vector<Mat3> Fs(n);
  for (int p = 0; p < n; ++p) {
    Fs[p] = random_F(rng);
    d.set_F(p, Fs[p]);
  }
  d.step(1.0);
  for (int p = 0; p < n; ++p) {
    const Mat3 ref = closed_form(Fs[p]);
    EXPECT_LT(frobenius(d.stress(p) - ref) / scale_of(ref), 1e-12) << "point " << p;
    EXPECT_LT(frobenius(d.material().initial_stress(Fs[p]) - ref) / scale_of(ref), 1e-12);
    // The stress is symmetric.
    EXPECT_LT(frobenius(skew(d.stress(p))) / scale_of(ref), 1e-14);
  }
}

// Objectivity (CATALOGUE A6): sigma(Q F) = Q sigma(F) Q^T for random Q, both points in one batch.
TEST(NeoHookean, ObjectivityUnderSuperimposedRotation) {
  std::mt19937 rng(11);
  const int n = 100;
  PointDriver d("neo_hookean", nh_params(), 2 * n);
  std::vector<Mat3> Q(n);
  for (int k = 0; k < n; ++k) {
    const Mat3 F = random_F(rng);
    Q[k] = random_rotation(rng);
    d.set_F(2 * k, F);
    d.set_F(2 * k + 1, Q[k] * F);
  }
  d.step(1.0);
  for (int k = 0; k < n; ++k) {
    const Mat3& s = d.stress(2 * k);
    EXPECT_LT(frobenius(d.stress(2 * k + 1) - rotate(Q[k], s)) / scale_of(s), 1e-12);
    // Same unrotated stress (the unrotated frame removes the rotation).
    EXPECT_LT(frobenius(d.stress_bar(2 * k + 1) - d.stress_bar(2 * k)) / scale_of(s), 1e-12);
  }
}

// sigma(I) = 0 exactly (ln 1 = 0, I - I = 0), and a rigid rotation is stress-free to round-off.
TEST(NeoHookean, ZeroStressAtIdentityAndRigidRotation) {
  PointDriver d("neo_hookean", nh_params(), 2);
  d.set_F(0, Mat3::identity());
  d.set_F(1, rotation_about(Vec3{{0.6, 0.0, 0.8}}, 2.0));
  d.step(1.0);
  for (double x : d.stress(0).a) EXPECT_EQ(x, 0.0);
  EXPECT_LT(frobenius(d.stress(1)), 1e-12 * kMu);
  for (double x : d.material().initial_stress(Mat3::identity()).a) EXPECT_EQ(x, 0.0);
}

// Uniaxial stretch F = diag(a, 1, 1), hand formula: J = a,
//   sigma11 = [lambda ln a + mu (a^2 - 1)]/a,  sigma22 = sigma33 = lambda ln a / a,
// reached along a 200-step path that also turns the element 90 deg about z (the path must not
// matter for a hyperelastic model; the rotation is removed by the unrotated frame).
TEST(NeoHookean, UniaxialStretchHandFormula) {
  for (double a : {0.5, 0.9, 1.1, 2.0}) {
    PointDriver d("neo_hookean", nh_params());
    const int N = 200;
    for (int n = 1; n <= N; ++n) {
      const double t = double(n) / N;
      d.advance(rotation_about(Vec3{{0, 0, 1}}, 0.5 * std::numbers::pi * t) * Mat3::diag(1.0 + (a - 1.0) * t, 1.0, 1.0),
                1.0 / N);
    }
    const Mat3 sb = d.stress_bar();
    const double s11 = (kLam * std::log(a) + kMu * (a * a - 1.0)) / a;
    const double s22 = kLam * std::log(a) / a;
    const double tol = 1e-12 * (std::abs(s11) + kMu);
    EXPECT_NEAR(sb(0, 0), s11, tol) << "a = " << a;
    EXPECT_NEAR(sb(1, 1), s22, tol);
    EXPECT_NEAR(sb(2, 2), s22, tol);
    EXPECT_NEAR(sb(0, 1), 0.0, tol);
    EXPECT_NEAR(sb(0, 2), 0.0, tol);
    EXPECT_NEAR(sb(1, 2), 0.0, tol);
  }
}

// Small-strain limit is isotropic linear elasticity with lambda, mu: for F = I + h A with h = 1e-6
// the stress is lambda tr(e) I + 2 mu e, e = sym(h A), up to O(h^2) terms, i.e. 1e-5 relative.
TEST(NeoHookean, SmallStrainLimitIsLinearElastic) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 1e-6;
  const auto mat = make_material("neo_hookean", nh_params());
  for (int k = 0; k < 20; ++k) {
    Mat3 A;
    for (double& a : A.a) a = u(rng);
    const Mat3 e = h * sym(A);
    Mat3 lin = (2.0 * kMu) * e;
    for (int i = 0; i < 3; ++i) lin(i, i) += kLam * trace(e);
    const Mat3 s = mat->initial_stress(Mat3::identity() + h * A);
    EXPECT_LT(frobenius(s - lin) / frobenius(lin), 1e-5);
  }
}

// Wave speed. At J = 1 it is sqrt((lambda + 2 mu)/rho0). Under a spherical deformation F = s I
// it must be the exact longitudinal speed, c^2 = s^2 (dP11/dF11)/rho0 (referential acoustic
// modulus of the first Piola stress P = J sigma F^{-T}, mapped to the current length scale),
// evaluated here by a central difference (h = 1e-6: truncation O(h^2) and round-off ~1e-16/h
// relative, so 1e-7 relative). In tension the estimate never drops below the reference speed.
TEST(NeoHookean, WaveSpeed) {
  PointDriver d("neo_hookean", nh_params());
  const Material& m = d.material();
  EXPECT_NEAR(m.wave_speed(d.store(), 0, 1.0), std::sqrt((kLam + 2 * kMu) / kRho), 1e-12 * std::sqrt(kLam + 2 * kMu));
  auto P11 = [&](const Mat3& F) { return (det(F) * m.initial_stress(F) * inverse_transpose(F))(0, 0); };
  for (double J : {0.5, 0.7, 0.9, 0.99}) {
    const double s = std::cbrt(J), h = 1e-6;
    const Mat3 Fp = Mat3::diag(s + h, s, s), Fm = Mat3::diag(s - h, s, s);
    const double A = (P11(Fp) - P11(Fm)) / (2 * h);
    const double c_exact = std::sqrt(s * s * A / kRho);
    EXPECT_NEAR(m.wave_speed(d.store(), 0, J), c_exact, 1e-7 * c_exact) << "J = " << J;
  }
  for (double J : {1.01, 1.3, 2.0})
    EXPECT_GE(m.wave_speed(d.store(), 0, J), std::sqrt((kLam + 2 * kMu) / kRho) * (1 - 1e-15));
}

// E, nu input: lambda = E nu/((1+nu)(1-2nu)), mu = E/(2(1+nu)) (standard relations).
TEST(NeoHookean, YoungPoissonInput) {
  const double E = 9 * kK * kMu / (3 * kK + kMu), nu = (3 * kK - 2 * kMu) / (2 * (3 * kK + kMu));
  const auto a = make_material("neo_hookean", {{"density", 1.0}, {"youngs_modulus", E}, {"poisson_ratio", nu}});
  const Mat3 F = Mat3::diag(1.2, 0.9, 1.05);
  EXPECT_LT(rel_diff(a->initial_stress(F), closed_form(F)), 1e-12);
}

// Algorithmic tangent: the exact derivative of sigma_bar_{n+1} with respect to the strain
// increment of a spin-free step, including the change of R_{n+1} (neo_hookean.cpp), against
// central differences through the real adapter (tangent_check.hpp). h = 1e-6: the stress is smooth
// on the scale of the strain (~1), so truncation h^2 ~ 1e-12; round-off 1e-16 |sigma| / (h |T|)
// < 1e-9 at stretches ~1.5 (the polar fixed point of the step adds ~1e-15 |eps|); tolerance 1e-7
// of max |T|. Dropping the rotation term (Omega = 0) gives 3e-3 to 4e-2 on these samples (measured)
// and would fail.
TEST(NeoHookean, TangentAtReferenceIsLinearElasticModuli) {
  TangentPoint pt("neo_hookean", nh_params());
  double T[36];
  pt.step(Mat3{}, 1e-3, T);
  // d sigma = lambda tr(d eps) I + 2 mu d eps (tensor shears) at F = I (Bonet & Wood eq. 6.29).
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double want = 0.0;
      if (i < 3 && j < 3) want = kLam + (i == j ? 2.0 * kMu : 0.0);
      if (i >= 3 && i == j) want = 2.0 * kMu;
      EXPECT_NEAR(T[6 * i + j], want, 1e-12 * kK) << i << "," << j;
    }
}

TEST(NeoHookean, TangentMatchesFiniteDifferencesAtLargeStrain) {
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int checked = 0;
  for (int trial = 0; trial < 8; ++trial) {
    // F_n: identity plus O(0.4) random entries (stretch, shear and rotation).
    Mat3 F_n = Mat3::identity();
    for (double& x : F_n.a) x += 0.4 * u(rng);
    if (det(F_n) < 0.3) continue;
    double e[6];
    for (double& x : e) x = 0.02 * u(rng);
    TangentPoint pt("neo_hookean", nh_params());
    pt.set_F(F_n);
    const TangentError err = fd_tangent_error(pt, sym6(e), 1e-3, 1e-6);
    worst = std::max(worst, err.rel_err);
    ++checked;
    EXPECT_LT(err.rel_err, 1e-7) << "trial " << trial << " J_n = " << det(F_n);
  }
  EXPECT_GE(checked, 4);
  std::printf("neo_hookean: %d samples, worst max |T_fd - T| / max|T| = %.2e\n", checked, worst);
}

}  // namespace test_neo_hookean
