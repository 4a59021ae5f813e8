// The generalized vortex manufactured solution (points/mms_generalized_vortex.hpp, CATALOGUE B2)
// checked from its definition alone: the motion x(X, t) = Q(alpha(R, t)) X is given; velocity and
// F must be its derivatives, and the closed-form body force must satisfy the momentum balance in
// the current configuration, b = a - div(sigma) / rho, with sigma the stress of the *registered*
// neo_hookean model (Material::initial_stress, the same law the solver integrates) and every
// derivative a central finite difference of the exact motion. An error in the derivation (a
// sign, a factor, a wrong constitutive form) shows up as a residual.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "materials/material.hpp"
#include "points/mms_generalized_vortex.hpp"

namespace test_mms_generalized_vortex {

using namespace ballista;

namespace {

const mms::GeneralizedVortex kMms;

std::unique_ptr<Material> make_neo_hookean() {
  const MaterialFactory* f = find_material("neo_hookean");
  if (!f) return nullptr;
  ParamValues v = {{"density", kMms.rho0}, {"bulk_modulus", kMms.K}, {"shear_modulus", kMms.mu}};
  for (const auto& spec : f->params)
    if (!v.count(spec.name)) v[spec.name] = spec.required ? 0.0 : spec.default_value;
  v["youngs_modulus"] = std::nan("");
  v["poisson_ratio"] = std::nan("");
  return f->create("vortex", v);
}

Vec3 unit(int a) {
  Vec3 e;
  e[a] = 1.0;
  return e;
}

struct Sample {
  Vec3 X;
  double t;
};
// Random reference points in the annulus (the interior: 0.76..1.24, away from the faces where the
// one-sided stencil would leave the body) and times over a full period 2/c.
std::vector<Sample> samples(int n) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(0.76, 1.24), th(0.0, 2.0 * std::numbers::pi), t(0.0, 2.0);
  std::vector<Sample> s;
  for (int k = 0; k < n; ++k) {
    const double R = r(rng), a = th(rng);
    s.push_back({{{R * std::cos(a), R * std::sin(a), 0.0}}, t(rng) / kMms.c});
  }
  return s;
}

}  // namespace

TEST(MmsGeneralizedVortex, ShapeFunctionVanishesWithItsSlopeOnBothFaces) {
  // h = ((4R-3)(4R-5))^2: h(0.75) = h(1.25) = 0 and h'(0.75) = h'(1.25) = 0 (traction-free faces,
  // Kamojjala et al. 2015), h(1) = 1 (rotation amplitude A at mid-radius).
  for (double R : {0.75, 1.25}) {
    EXPECT_NEAR(kMms.h(R), 0.0, 1e-14);
    EXPECT_NEAR(kMms.dh(R), 0.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(kMms.h(1.0), 1.0);
  for (double R : {0.8, 0.9, 1.1, 1.2})
    EXPECT_NEAR(kMms.h(R), std::pow((4 * R - 3) * (4 * R - 5), 2), 1e-13);
}

TEST(MmsGeneralizedVortex, VelocityAndDeformationGradientAreDerivativesOfTheMotion) {
  // Central differences with step 1e-5: truncation ~ (d^3 x) dX^2 / 6 with third derivatives of
  // O(10^3) (h''' = 6144 ): ~2e-8; round-off eps / dX ~ 2e-11. Tolerance 1e-6 absolute on
  // F (entries O(1..5)) and 1e-6 relative to the speed scale A c pi R.
  const double dX = 1e-5, dt = 1e-5;
  for (const auto& s : samples(100)) {
    const Vec3 v = kMms.velocity(s.X, s.t);
    const Vec3 fd_v = (1.0 / (2 * dt)) * (kMms.position(s.X, s.t + dt) - kMms.position(s.X, s.t - dt));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], fd_v[i], 1e-6 * kMms.A * kMms.c * std::numbers::pi * 1.25) << i;
    const Mat3 F = kMms.F(s.X, s.t);
    EXPECT_NEAR(det(F), 1.0, 1e-12);  // isochoric: rigid rotation of each ring plus simple shear
    for (int j = 0; j < 2; ++j) {
      const Vec3 dx = (1.0 / (2 * dX)) * (kMms.position(s.X + dX * unit(j), s.t) - kMms.position(s.X - dX * unit(j), s.t));
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(F(i, j), dx[i], 1e-6) << i << j;
    }
  }
}

TEST(MmsGeneralizedVortex, BodyForceBalancesTheMomentumEquationOfTheRegisteredNeoHookean) {
  // a by a second central difference in time of x(X, t) (dt = 1e-4: truncation dt^2 x''''/12 with
  // x'''' ~ (c pi)^4 |x| ~ 1e2: ~1e-7; round-off eps |x| / dt^2 ~ 3e-8); div sigma in the current
  // configuration, d sigma_ij / d x_j = (d sigma_ij / d X_K) F^-1_Kj, with d/dX_K by central
  // differences (dX = 1e-5: round-off eps mu / dX ~ 1e-8 of mu), rho = rho0 / J. Tolerance 1e-5
  // of the size of the terms |a| + |div sigma| / rho: measured worst 7.4e-7, while a 1 % error in mu
  // inside b fails every one of the 400 comparisons.
  const auto mat = make_neo_hookean();
  ASSERT_NE(mat, nullptr);
  const double dX = 1e-5, dt = 1e-4;
  double bmax = 0.0, worst = 0.0;
  for (const auto& s : samples(200)) {
    const Vec3 b = kMms.body_force(s.X, s.t);
    const Vec3 acc = (1.0 / (dt * dt)) * (kMms.position(s.X, s.t + dt) - 2.0 * kMms.position(s.X, s.t) +
                                          kMms.position(s.X, s.t - dt));
    const Mat3 F = kMms.F(s.X, s.t);
    const Mat3 Finv = inverse(F);
    const double rho = kMms.rho0 / det(F);
    Mat3 dsig[2];  // d sigma / d X_K for K = 0, 1 (plane strain: nothing depends on X_2)
    for (int K = 0; K < 2; ++K) {
      const Mat3 sp = mat->initial_stress(kMms.F(s.X + dX * unit(K), s.t));
      const Mat3 sm = mat->initial_stress(kMms.F(s.X - dX * unit(K), s.t));
      dsig[K] = (1.0 / (2 * dX)) * (sp - sm);
    }
    Vec3 div;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int K = 0; K < 2; ++K) div[i] += dsig[K](i, j) * Finv(K, j);
    for (int i = 0; i < 2; ++i) {
      const double scale = std::abs(acc[i]) + std::abs(div[i] / rho);
      const double residual = acc[i] - div[i] / rho - b[i];
      EXPECT_LE(std::abs(residual), 1e-5 * scale + 1e-9)
          << "X = (" << s.X[0] << ", " << s.X[1] << "), t = " << s.t << ", component " << i;
      worst = std::max(worst, std::abs(residual) / (scale + 1e-300));
      if (scale > 1e-3) bmax = std::max(bmax, std::abs(b[i]) / scale);
    }
    EXPECT_NEAR(b[2], 0.0, 1e-15);
  }
  // The manufactured force is not a negligible correction: somewhere it is at least a fifth of
  // the larger of inertia and stress divergence, so an error of a few per cent in it would fail.
  EXPECT_GT(bmax, 0.2);
  RecordProperty("worst_relative_residual", std::to_string(worst));
  std::printf("worst relative residual %.3g, largest |b| / scale %.3g\n", worst, bmax);
}

TEST(MmsGeneralizedVortex, BodyForceMatchesUintahsFactoredForm) {
  // Uintah MMS.cc writes b_r, b_t with h = ((4R-3)(4R-5))^2 factored out (transcribed here as an
  // independent closed form): b_r = -R A^2 cos^2 c^2 pi^2 (4R-3)^4 (4R-5)^4
  //   + (4096 / rho0) (4R-5)^2 (R-1)^2 (4R-3)^2 A^2 sin^2 R mu,
  // b_t = -A sin (R c^2 pi^2 (4R-3)^2 (4R-5)^2 + (64 mu / rho0)(96 R^3 - 240 R^2 + 188 R - 45)).
  // Same algebra, different grouping: agreement to round-off (1e-12 of the terms).
  using std::numbers::pi;
  const double A = kMms.A, c = kMms.c, mu = kMms.mu, rho0 = kMms.rho0;
  for (const auto& s : samples(50)) {
    const double R = std::hypot(s.X[0], s.X[1]);
    const double sn = std::sin(c * pi * s.t), cs = std::cos(c * pi * s.t);
    const double p = 4 * R - 3, q = 4 * R - 5;
    const double br = -R * A * A * cs * cs * c * c * pi * pi * std::pow(p, 4) * std::pow(q, 4) +
                      (4096.0 / rho0) * q * q * (R - 1) * (R - 1) * p * p * A * A * sn * sn * R * mu;
    const double bt = -A * sn * (R * c * c * pi * pi * p * p * q * q + (64.0 * mu / rho0) * (96 * R * R * R - 240 * R * R + 188 * R - 45));
    const double beta = std::atan2(s.X[1], s.X[0]) + kMms.angle(R, s.t).a;
    const Vec3 b = kMms.body_force(s.X, s.t);
    const double scale = 1e-12 * (std::abs(br) + std::abs(bt) + 1.0);
    EXPECT_NEAR(b[0], std::cos(beta) * br - std::sin(beta) * bt, scale);
    EXPECT_NEAR(b[1], std::sin(beta) * br + std::cos(beta) * bt, scale);
  }
}

}  // namespace test_mms_generalized_vortex
