// The axis-aligned manufactured solution (points/mms_axis_aligned.hpp) checked from its
// definition alone: u(X, t) is given; velocity = du/dt, F = I + Grad u, and the body force must
// make rho0 u'' = Div P + rho0 b hold for the neo-Hookean P = mu (F - F^-T) + lambda ln J F^-T.
// Every derivative here is a central finite difference of the MMS's own functions, so an error in
// any closed form (sign, phase, a missing factor) shows up as a residual.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "materials/material.hpp"
#include "points/mms_axis_aligned.hpp"

namespace test_mms_axis_aligned {

using namespace ballista;

namespace {

const mms::AxisAligned kMms;

Mat3 piola(const Mat3& F) {
  const double J = det(F);
  const Mat3 Finvt = inverse_transpose(F);
  return kMms.mu * (F - Finvt) + (kMms.lambda() * std::log(J)) * Finvt;
}

Vec3 unit(int a) {
  Vec3 e;
  e[a] = 1.0;
  return e;
}

// Random reference points inside the unit cube and times over a few periods 2/c.
struct Sample {
  Vec3 X;
  double t;
};
std::vector<Sample> samples(int n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> s;
  for (int k = 0; k < n; ++k) s.push_back({{{u(rng), u(rng), u(rng)}}, u(rng) * 6.0 / kMms.c()});
  return s;
}

}  // namespace

TEST(MmsAxisAligned, ConstantsAreConsistent) {
  // E = 9 K mu / (3 K + mu) and lambda = K - 2 mu / 3 (isotropic elasticity), c = sqrt(E / rho0).
  const double nu = (3 * kMms.K - 2 * kMms.mu) / (2 * (3 * kMms.K + kMms.mu));
  EXPECT_NEAR(kMms.youngs(), 2 * kMms.mu * (1 + nu), 1e-12 * kMms.youngs());
  EXPECT_NEAR(kMms.lambda(), kMms.youngs() * nu / ((1 + nu) * (1 - 2 * nu)), 1e-9 * kMms.lambda());
  EXPECT_DOUBLE_EQ(kMms.c() * kMms.c() * kMms.rho0, kMms.youngs());
}

TEST(MmsAxisAligned, VelocityAndDeformationGradientAreDerivativesOfTheDisplacement) {
  // Central differences: truncation (pi dX)^2/6 ~ 2e-8 relative for dX = 1e-4 (and likewise for
  // (pi c dt)^2 with dt = 1e-4/(pi c)); round-off eps |u| / dX ~ 1e-13. Tolerance 1e-6 relative to
  // the derivative scale A pi (c).
  const double dX = 1e-4, dt = 1e-4 / (std::numbers::pi * kMms.c());
  for (const auto& s : samples(50)) {
    const Vec3 v = kMms.velocity(s.X, s.t);
    const Vec3 fd_v = (1.0 / (2 * dt)) * (kMms.displacement(s.X, s.t + dt) - kMms.displacement(s.X, s.t - dt));
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(v[i], fd_v[i], 1e-6 * kMms.A * std::numbers::pi * kMms.c()) << i;
    const Mat3 F = kMms.F(s.X, s.t);
    for (int j = 0; j < 3; ++j) {
      const Vec3 du = (1.0 / (2 * dX)) * (kMms.displacement(s.X + dX * unit(j), s.t) -
                                          kMms.displacement(s.X - dX * unit(j), s.t));
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(F(i, j), (i == j ? 1.0 : 0.0) + du[i], 1e-6 * kMms.A * std::numbers::pi) << i << j;
    }
  }
}

TEST(MmsAxisAligned, BodyForceBalancesTheMomentumEquation) {
  // rho0 u'' = Div P + rho0 b with u'' and Div P by central differences of the MMS's own u and of
  // P(F(X)). Truncation errors are (pi h)^2/12 (second time derivative, h = pi c dt = 2e-3:
  // 3e-6 relative) and (pi dX)^2/6 (dX = 1e-4: 2e-8); round-off eps |u| / dt^2 ~ 1e-8 of u''.
  // Tolerance: 2e-5 of the size of the terms, |rho0 u''| + |Div P|.
  const double dX = 1e-4, dt = 2e-3 / (std::numbers::pi * kMms.c());
  double bmax = 0.0;  // largest |rho0 b_i| / |rho0 u''_i| seen
  for (const auto& s : samples(200)) {
    const Vec3 b = kMms.body_force(s.X, s.t);
    const Vec3 u0 = kMms.displacement(s.X, s.t);
    const Vec3 acc = (1.0 / (dt * dt)) * (kMms.displacement(s.X, s.t + dt) - 2.0 * u0 +
                                          kMms.displacement(s.X, s.t - dt));
    Vec3 div;
    for (int J = 0; J < 3; ++J) {
      const Mat3 Pp = piola(kMms.F(s.X + dX * unit(J), s.t));
      const Mat3 Pm = piola(kMms.F(s.X - dX * unit(J), s.t));
      for (int i = 0; i < 3; ++i) div[i] += (Pp(i, J) - Pm(i, J)) / (2 * dX);
    }
    for (int i = 0; i < 3; ++i) {
      const double scale = std::abs(kMms.rho0 * acc[i]) + std::abs(div[i]);
      const double residual = kMms.rho0 * acc[i] - div[i] - kMms.rho0 * b[i];
      EXPECT_LE(std::abs(residual), 2e-5 * scale + 1e-9) << "X = (" << s.X[0] << ", " << s.X[1] << ", " << s.X[2]
                                                        << "), t = " << s.t << ", component " << i;
      if (std::abs(acc[i]) > 1e-3 * scale) bmax = std::max(bmax, std::abs(b[i] / acc[i]));
    }
  }
  // The body force is a sizeable part of the balance (about a third of rho0 u'' for these
  // constants), so an error of a few per cent in it exceeds the tolerance above.
  EXPECT_GT(bmax, 0.2);
}

TEST(MmsAxisAligned, StressOfTheRegisteredNeoHookeanMaterialIsThePiolaStressPushedForward) {
  // The solver starts MMS bodies with material->initial_stress(F); for the manufactured force to
  // be the right one, the neo_hookean model must be the same constitutive law:
  // sigma = P F^T / J. Tolerance: 1e-12 relative to mu (both are a few flops of O(mu) terms).
  const MaterialFactory* f = find_material("neo_hookean");
  ASSERT_NE(f, nullptr);
  ParamValues v = {{"density", kMms.rho0}, {"bulk_modulus", kMms.K}, {"shear_modulus", kMms.mu}};
  for (const auto& spec : f->params)
    if (!v.count(spec.name)) v[spec.name] = spec.required ? 0.0 : spec.default_value;
  v["youngs_modulus"] = std::nan("");
  v["poisson_ratio"] = std::nan("");
  const auto mat = f->create("mms", v);
  EXPECT_DOUBLE_EQ(mat->density(), kMms.rho0);
  for (const auto& s : samples(20)) {
    const Mat3 F = kMms.F(s.X, s.t);
    const Mat3 expected = (1.0 / det(F)) * times_transpose(piola(F), F);
    const Mat3 sigma = mat->initial_stress(F);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(sigma(i, j), expected(i, j), 1e-12 * kMms.mu) << i << j;
  }
}

}  // namespace test_mms_axis_aligned
