// The water model: registration and defaults, zero deviatoric stress, exact objectivity, the
// cavitation cutoff and the acoustic (eos.type linear) variant. Its Mie-Grüneisen pressure is
// checked against Rankine-Hugoniot and the isentrope in test_eos.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "material_driver.hpp"
#include "tangent_check.hpp"
#include "materials/eos.hpp"

namespace test_water {

using namespace ballista;
using namespace ballista::test;

namespace {
double pressure(PointDriver& d) { return -trace(d.stress()) / 3.0; }

Mat3 random_rotation(std::mt19937& rng, double max_angle) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-max_angle, max_angle);
  Vec3 a{{g(rng), g(rng), g(rng)}};
  return rotation_about((1.0 / norm(a)) * a, u(rng));
}
}  // namespace

// Registered with its defaults; verification hooks: an example, no reduction (no shear stiffness).
TEST(Water, RegisteredWithDefaults) {
  const MaterialFactory* f = find_material("water");
  ASSERT_NE(f, nullptr);
  EXPECT_NE(f->example, nullptr);
  EXPECT_EQ(f->reduce_elastic, nullptr);
  EXPECT_EQ(f->reduce_j2, nullptr);
  std::map<std::string, const ParamSpec*> spec;
  for (const ParamSpec& s : f->params) spec[s.name] = &s;
  ASSERT_TRUE(spec.count("density") && spec.count("eos.type") && spec.count("eos.min_pressure") &&
              spec.count("failure.criterion"));
  EXPECT_FALSE(spec["density"]->required);
  EXPECT_EQ(spec["density"]->default_value, 998.2);
  EXPECT_EQ(spec["eos.type"]->default_choice, "mie_gruneisen");
  EXPECT_EQ(spec["eos.sound_speed"]->default_value, 1647.0);
  EXPECT_EQ(spec["eos.hugoniot_slope"]->default_value, 1.921);
  EXPECT_EQ(spec["eos.gruneisen_gamma"]->default_value, 0.35);
  EXPECT_EQ(spec["eos.min_pressure"]->default_value, -1e5);
  // Made from nothing (every default) and from its example: the same material.
  const auto a = f->create("w", {});
  const auto b = f->create("w", f->example());
  EXPECT_EQ(a->density(), 998.2);
  ASSERT_EQ(a->state_fields().size(), 1u);
  EXPECT_EQ(a->state_fields()[0].name, kEosEnergyField);
  FieldStore st;
  a->declare_fields(st);
  st.resize(1);
  EXPECT_EQ(a->wave_speed(st, 0, 0.9), b->wave_speed(st, 0, 0.9));
  EXPECT_THROW(f->create("w", {{"eos.sound_speed", 0.0}}), ParamError);
}

// A fluid carries no shear: under a general deformation with rotation the stress is -p I
// (deviator 1e-14 of p: the rotation R (-p I) R^T rounds).
TEST(Water, NoDeviatoricStress) {
  PointDriver d("water", {});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat3 F = Mat3::identity();
  for (int n = 1; n <= 200; ++n) {
    Mat3 dF = Mat3::identity();
    for (double& x : dF.a) x += 1e-3 * u(rng);
    dF(0, 0) -= 2e-3;  // net compression (no cavitation)
    F = dF * F;
    d.advance(F, 1e-7);
    const double p = pressure(d);
    ASSERT_GT(p, 0.0);
    ASSERT_LT(frobenius(deviator(d.stress())), 1e-14 * p) << n;
  }
}

// Objectivity: a superimposed rotation Q_n that changes every step (random axis and angle up to
// 0.05 rad per step) leaves the pressure and the energy unchanged to round-off: both depend on
// J = det F and its increments only, which rotations do not change. The energy, a sum of p dJ
// whose increments dJ = J (1 - 1/det(I + dt L)) lose ~1e-13 relative to cancellation, agrees to
// 1e-11 of the gross work sum |p dJ|; the pressure to 1e-12 relative, plus 3e-5 Pa (det(Q F) and
// det F differ by ~10 ulp since Q F rounds each entry: rho0 c0^2 1e-14 = 2.7e-5 Pa), plus Gamma0
// times the energy tolerance.
TEST(Water, ObjectiveUnderRandomRotations) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointDriver plain("water", {}), turned("water", {});
  Mat3 F = Mat3::identity(), Q = Mat3::identity();
  double gross = 0.0, p_prev = 0.0, J_prev = 1.0;
  for (int n = 1; n <= 300; ++n) {
    Mat3 dF = Mat3::identity();
    for (double& x : dF.a) x += 2e-3 * u(rng);
    F = dF * F;
    Q = random_rotation(rng, 0.05) * Q;
    plain.advance(F, 1e-7);
    turned.advance(Q * F, 1e-7);
    const double p = pressure(plain);
    gross += 0.5 * std::abs(p + p_prev) * std::abs(det(F) - J_prev);
    p_prev = p;
    J_prev = det(F);
    const double tol_E = 1e-11 * gross, tol_p = 1e-12 * std::abs(p) + 3e-5 + 0.35 * tol_E;  // Gamma0 = 0.35
    ASSERT_NEAR(turned.state(kEosEnergyField), plain.state(kEosEnergyField), tol_E) << n;
    ASSERT_NEAR(pressure(turned), p, tol_p) << n;
    ASSERT_LT(frobenius(turned.stress_bar() - plain.stress_bar()), 2.0 * tol_p) << n;
  }
  EXPECT_GT(std::abs(det(F) - 1.0), 1e-3);  // the path did change the volume
}

// Cavitation: in expansion the pressure is held at eos.min_pressure (default -1e5 Pa, exactly),
// while the Mie-Grüneisen pressure would be -rho0 c0^2 eta; a deck value overrides the default and
// min_pressure 0 gives a fluid that carries no tension at all.
TEST(Water, CavitationCutoff) {
  for (double pmin : {-1e5, -2e6, 0.0}) {
    ParamValues v;
    if (pmin != -1e5) v["eos.min_pressure"] = pmin;
    PointDriver d("water", v);
    for (int n = 1; n <= 100; ++n) {
      const double J = 1.0 + 1e-4 * n;  // rho0 c0^2 (J - 1) = 2.7e5 Pa of tension after one step
      d.advance(std::cbrt(J) * Mat3::identity(), 1e-7);
      if (n >= 8) {
        ASSERT_EQ(pressure(d), pmin) << "p_min = " << pmin << ", step " << n;
      }
    }
    // Recompression below the reference volume gives compression again.
    d.advance(std::cbrt(0.99) * Mat3::identity(), 1e-7);
    EXPECT_GT(pressure(d), 1e7);
  }
}

// The wave speed of a cavitated point (its pressure held at the cutoff) is the speed at rest, c0
// (K(1) = rho0 c0^2 exactly), not the tension branch's sqrt(K J / rho0), which for a spray point
// expanded 1,000-fold would be 41 km/s and set the run's step. Closed again (J <= 1) the speed is
// the isentrope's (test_eos.cpp), and an expanded point that is hot enough to stay above the cutoff
// keeps its own. Exact comparisons: c0 is sqrt(rho0 c0^2 / rho0) in both.
TEST(Water, CavitatedPointKeepsTheSpeedAtRest) {
  const auto w = make_material("water", {});
  FieldStore st;
  w->declare_fields(st);
  st.resize(1);
  const double rest = w->wave_speed(st, 0, 1.0);
  EXPECT_NEAR(rest, 1647.0, 1e-12 * 1647.0);
  for (double J : {1.001, 10.0, 1240.0}) EXPECT_EQ(w->wave_speed(st, 0, J), rest) << "J = " << J;
  EXPECT_GT(w->wave_speed(st, 0, 0.9), rest);  // compressed: stiffer than at rest
  // Hot enough that the Mie-Grüneisen pressure at J = 1.001 is positive: not cavitated, so the
  // tension branch's own estimate (sqrt(K J / rho0) with K >= rho0 c0^2 / 2) applies.
  st.real(kEosEnergyField)[0] = 1e9;
  EXPECT_NE(w->wave_speed(st, 0, 1.001), rest);
}

// eos.type linear: an acoustic fluid with K = rho0 c0^2, p_{n+1} = p_n - K tr(D) dt. One step of
// spherical compression F = c I from I gives tr(D) dt = 3 (c - 1) (1e-12 relative).
TEST(Water, LinearEosIsAnAcousticFluid) {
  ParamValues v{{"eos.sound_speed", 1482.0}};
  v.choices["eos.type"] = "linear";
  PointDriver d("water", v);
  const double c = std::cbrt(0.999), K = 998.2 * 1482.0 * 1482.0;
  d.advance(c * Mat3::identity(), 1e-7);
  // p = -K tr(eps), eps the midpoint increment of the stretch c: (c - 1)/(1 + (c - 1)/2) per axis.
  EXPECT_NEAR(pressure(d), -K * 3.0 * (c - 1.0) / (1.0 + 0.5 * (c - 1.0)), 1e-12 * K * 3e-3);
  EXPECT_NEAR(d.material().wave_speed(d.store(), 0, 1.0), 1482.0, 1e-12 * 1482.0);
}

// Algorithmic tangent against central differences of the update (tangent_check.hpp, spin-free
// increments from a rotated F_n). Pressure only: rows 11, 22, 33 equal -dp/d eps, shear rows zero.
// h = 1e-6: truncation h^2 |p^(3)|/|p'| < 1e-10, round-off 1e-16 |p| / (h |dp/d eps|) < 1e-11;
// tolerance 1e-8 of max |T| (a dropped energy coupling Gamma0 p dJ/2 is ~1e-3 here and would fail).
TEST(Water, TangentMatchesFiniteDifferencesAndIsPressureOnly) {
  const Mat3 Q = rotation_about(Vec3{{0.0, 0.6, 0.8}}, 0.7);
  const double e_c[6] = {-3e-3, -1e-3, -2e-3, 0.5e-3, -0.4e-3, 0.7e-3};
  const double e_t[6] = {1e-5, 0.5e-5, 0.3e-5, 0.5e-5, -0.4e-5, 0.7e-5};  // J_{n+1} - 1 ~ 3e-5: p ~ -8e4 > p_min
  struct Case {
    const char* name;
    double J_n, p_n, energy;
    const double* eps;
  };
  // Shock-compressed (eta = 0.15, p ~ 0.7 GPa) and slightly expanded above the cutoff.
  const Case cases[] = {{"compression", 0.85, 7e8, 5e7, e_c}, {"tension", 1.00001, -3e4, 0.0, e_t}};
  for (const Case& c : cases) {
    TangentPoint pt("water", {});
    pt.set_F(std::cbrt(c.J_n) * Q);
    pt.set_stress_bar(Mat3::diag(-c.p_n, -c.p_n, -c.p_n));
    pt.set_state(kEosEnergyField, c.energy);
    const TangentError e = fd_tangent_error(pt, sym6(c.eps), 1e-6, 1e-6);
    std::printf("water %s: max |T_fd - T| / max|T| = %.2e, max |T| = %.3e Pa\n", c.name, e.rel_err, e.max_entry);
    EXPECT_LT(e.rel_err, 1e-8) << c.name;
    for (int j = 0; j < 6; ++j) {
      EXPECT_EQ(e.T[j], e.T[6 + j]) << c.name;
      EXPECT_EQ(e.T[j], e.T[12 + j]) << c.name;
      for (int i = 3; i < 6; ++i) EXPECT_EQ(e.T[6 * i + j], 0.0) << c.name;
    }
    EXPECT_GT(e.T[0], 1e9) << c.name;  // compressing raises p: d sigma_11 / d eps_11 = -dp/d eps_11 > 0
  }
}

TEST(Water, TangentIsZeroAtCavitationCutoff) {
  // Expanding at the cutoff p = p_min = -1e5 Pa: the pressure stays at p_min whatever the
  // increment, so the tangent is exactly zero and so is the change of the stress.
  TangentPoint pt("water", {});
  pt.set_F(std::cbrt(1.001) * Mat3::identity());
  pt.set_stress_bar(Mat3::diag(1e5, 1e5, 1e5));
  const double e0[6] = {1e-3, 1.2e-3, 0.9e-3, 0.1e-3, 0.0, -0.2e-3};
  double T[36];
  const Mat3 s = pt.step(sym6(e0), 1e-7, T);
  EXPECT_EQ(s(0, 0), 1e5);
  for (double t : T) EXPECT_EQ(t, 0.0);
  const Mat3 sp = pt.step(sym6(e0) + 1e-6 * Mat3::identity(), 1e-7);
  EXPECT_EQ(sp(0, 0), 1e5);
}

}  // namespace test_water
