// CATALOGUE A6, finite-difference tangent check for the J2 family (j2_plasticity with every
// hardening law, kinematic hardening and the Mie-Grüneisen EOS; johnson_cook): the algorithmic
// tangent the kernel writes into PointResult::tangent must equal central differences of the
// stress update with respect to the strain increment of the step.
//
// Each evaluation (TangentPoint, tangent_check.hpp, with F_n = I) starts from the same prescribed
// state (stress, eqps, backstress, energy, temperature; R_n = I) and takes one step through the
// real adapter with
// F_{n+1} = (I - eps/2)^-1 (I + eps/2) (eps symmetric; spin_free_step_for_increment), the symmetric
// stretch whose midpoint increment (Hughes & Winget 1980, materials/strain_increment.hpp) is
// exactly eps: L is symmetric, R_{n+1} = I (polar rotation of an SPD matrix, to round-off),
// D_bar dt = eps to round-off and J_{n+1} = det F_{n+1}, which is the convention the tangent states
// (j2_return.hpp: d sigma_bar / d eps for a spin-free step of increment eps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tangent_check.hpp"
#include "materials/strain_increment.hpp"

namespace test_j2_tangent {

using namespace ballista;
using namespace ballista::test;

namespace {

// Shared material data: steel-like elastic constants, sigma_y0 = 300 MPa (yield strain 1.9e-3).
ParamValues base_j2() {
  ParamValues v = elastic_kg(7800, 160e9, 80e9);
  v["yield_stress"] = 300e6;
  return v;
}

// A general (non-proportional, all six components) strain increment of ~8e-3 deviatoric size:
// about four times the yield strain, so that every perturbed step stays plastic.
Mat3 plastic_increment() {
  const double e[6] = {6e-3, -2.5e-3, -1.0e-3, 1.5e-3, -0.7e-3, 2.2e-3};
  return sym6(e);
}
// A small increment (~1e-4) from a state well inside the yield surface: elastic.
Mat3 elastic_increment() {
  const double e[6] = {1e-4, -0.3e-4, 0.5e-4, 0.2e-4, -0.4e-4, 0.1e-4};
  return sym6(e);
}
// A start-of-step stress with pressure and a deviator of ~150 MPa (inside the initial surface).
Mat3 start_stress() {
  const double s[6] = {-80e6, -250e6, -190e6, 40e6, -30e6, 60e6};
  return sym6(s);
}

// Tolerance. The step h = 1e-7 is 1/20000 of the smallest plastic-increment scale (the trial
// overshoot of the yield surface, ~2e-3): the central-difference truncation error is
// ~ (h/scale)^2 = 2.5e-9 of the tangent; round-off is ~ 1e-16 |sigma| / (h |T|) with |sigma| ~
// 1e9 Pa and |T| ~ 2e11 Pa, i.e. ~ 5e-8 (measured: 4e-10 to 1e-9; 1e-8 for the JC elastic step
// with h = 1e-8). Both are well below the 1e-6 asserted, while a wrong term of the tangent shows up
// far above it (checked by mutation: dropping H_k from theta_bar gives 8e-3, dropping the rate
// slope of Johnson-Cook 2e-3, dropping the d s_{n+1} : eps part of the EOS energy coupling 1e-4).
constexpr double kH = 1e-7;
constexpr double kTol = 1e-6;

}  // namespace

TEST(J2Tangent, ElasticStep) {
  TangentPoint pt("j2_plasticity", base_j2());
  pt.set_stress_bar(start_stress());
  const TangentError c = fd_tangent_error(pt, elastic_increment(), 1e-6, kH);
  EXPECT_LT(c.rel_err, kTol);
  EXPECT_EQ(pt.state_after("eqps"), 0.0);  // the step really was elastic
}

TEST(J2Tangent, LinearIsotropicPlasticStep) {
  ParamValues v = base_j2();
  v["hardening_modulus"] = 2e9;
  TangentPoint pt("j2_plasticity", v);
  pt.set_stress_bar(start_stress());
  pt.set_state("eqps", 0.02);
  const TangentError c = fd_tangent_error(pt, plastic_increment(), 1e-6, kH);
  EXPECT_LT(c.rel_err, kTol);
  EXPECT_GT(pt.state_after("eqps"), 0.02);
}

TEST(J2Tangent, PerfectPlasticityStep) {
  TangentPoint pt("j2_plasticity", base_j2());
  pt.set_stress_bar(start_stress());
  EXPECT_LT(fd_tangent_error(pt, plastic_increment(), 1e-6, kH).rel_err, kTol);
}

TEST(J2Tangent, PowerLawPlasticStep) {
  for (double e0 : {0.0, 0.05}) {
    ParamValues v = base_j2();
    v.choices["hardening_law"] = "power_law";
    v["hardening_coefficient"] = 500e6;
    v["hardening_exponent"] = 0.3;
    TangentPoint pt("j2_plasticity", v);
    pt.set_stress_bar(start_stress());
    pt.set_state("eqps", e0);
    const TangentError c = fd_tangent_error(pt, plastic_increment(), 1e-6, kH);
    EXPECT_LT(c.rel_err, kTol) << "eqps_n = " << e0;
  }
}

TEST(J2Tangent, VocePlasticStep) {
  ParamValues v = base_j2();
  v.choices["hardening_law"] = "voce";
  v["hardening_modulus"] = 1e9;
  v["saturation_stress"] = 200e6;
  v["saturation_rate"] = 20.0;
  TangentPoint pt("j2_plasticity", v);
  pt.set_stress_bar(start_stress());
  pt.set_state("eqps", 0.01);
  EXPECT_LT(fd_tangent_error(pt, plastic_increment(), 1e-6, kH).rel_err, kTol);
}

// Isotropic + kinematic, starting from a non-zero (deviatoric) backstress.
TEST(J2Tangent, IsotropicPlusKinematicPlasticStep) {
  ParamValues v = base_j2();
  v["hardening_modulus"] = 1e9;
  v["kinematic_modulus"] = 5e9;
  TangentPoint pt("j2_plasticity", v);
  pt.set_stress_bar(start_stress());
  pt.set_state("eqps", 0.03);
  const double a[6] = {60e6, -20e6, -40e6, 10e6, 5e6, -15e6};
  const char* names[6] = {"backstress_11", "backstress_22", "backstress_33",
                          "backstress_23", "backstress_13", "backstress_12"};
  for (int c = 0; c < 6; ++c) pt.set_state(names[c], a[c]);
  const TangentError c = fd_tangent_error(pt, plastic_increment(), 1e-6, kH);
  EXPECT_LT(c.rel_err, kTol);
  EXPECT_NE(pt.state_after("backstress_12"), -15e6);
}

// Voce + kinematic with the Mie-Grüneisen EOS (copper-like), compressed by 1 % with non-zero
// stored energy: the pressure tangent couples to J and to the deviatoric work.
TEST(J2Tangent, VoceKinematicMieGruneisen) {
  ParamValues v = elastic_kg(8930, 8930.0 * 3940.0 * 3940.0, 47.7e9);
  v["yield_stress"] = 120e6;
  v.choices["hardening_law"] = "voce";
  v["hardening_modulus"] = 0.5e9;
  v["saturation_stress"] = 150e6;
  v["saturation_rate"] = 10.0;
  v["kinematic_modulus"] = 2e9;
  v.choices["eos.type"] = "mie_gruneisen";
  v["eos.sound_speed"] = 3940;
  v["eos.hugoniot_slope"] = 1.489;
  v["eos.gruneisen_gamma"] = 2.02;
  TangentPoint pt("j2_plasticity", v);
  pt.set_stress_bar(start_stress());
  pt.set_state("energy_density", 3e7);
  Mat3 eps = plastic_increment();
  for (int i = 0; i < 3; ++i) eps(i, i) -= 1e-2 / 3.0;
  const TangentError c = fd_tangent_error(pt, eps, 1e-6, kH);
  EXPECT_LT(c.rel_err, kTol);
  // The same check in tension (eta < 0 branch of the Hugoniot).
  for (int i = 0; i < 3; ++i) eps(i, i) += 2e-2 / 3.0;
  EXPECT_LT(fd_tangent_error(pt, eps, 1e-6, kH).rel_err, kTol);
  // And beyond the end of the Us-up line (eos.max_particle_velocity): a line ended at 10 m/s
  // (eta_f = 2.5e-3) puts the compressed step's eta ~ 1e-2 on the tangent.
  v["eos.max_particle_velocity"] = 10.0;
  TangentPoint ended("j2_plasticity", v);
  ended.set_stress_bar(start_stress());
  ended.set_state("energy_density", 3e7);
  for (int i = 0; i < 3; ++i) eps(i, i) -= 2e-2 / 3.0;
  EXPECT_LT(fd_tangent_error(ended, eps, 1e-6, kH).rel_err, kTol);
}

// Tension cutoff: while eos.min_pressure holds the pressure, dp/d eps = 0 (and the FD agrees).
TEST(J2Tangent, TensionCutoffHoldsPressure) {
  ParamValues v = base_j2();
  v.choices["eos.type"] = "linear";
  v["eos.min_pressure"] = -50e6;
  TangentPoint pt("j2_plasticity", v);
  pt.set_stress_bar(Mat3::diag(40e6, 40e6, 40e6));  // p = -40 MPa
  Mat3 eps = elastic_increment();
  for (int i = 0; i < 3; ++i) eps(i, i) += 1e-3;  // K tr(eps) = 0.5 GPa: far past the cutoff
  double T[36];
  const Mat3 s = pt.step(eps, 1e-6, T);
  EXPECT_NEAR(-trace(s) / 3.0, -50e6, 1e-6);
  EXPECT_LT(fd_tangent_error(pt, eps, 1e-6, kH).rel_err, kTol);
  // Volumetric column sums: d p/d tr(eps) = 0, so sum of the normal rows of a normal column is the
  // deviatoric part only, which is zero for a unit volumetric perturbation.
  double vol = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) vol += T[6 * i + j];
  EXPECT_NEAR(vol, 0.0, 1e-6 * 160e9);
}

// Johnson-Cook: plastic step at eps_dot_p ~ 1e3/s (rate term active) and 600 K (thermal term
// active), OFHC copper of Johnson & Cook 1983 with its Mie-Grüneisen EOS; and an elastic step.
TEST(J2Tangent, JohnsonCook) {
  const MaterialFactory* f = find_material("johnson_cook");
  ASSERT_NE(f, nullptr);
  ASSERT_NE(f->example, nullptr);
  ParamValues v = f->example();
  v["initial_temperature"] = 600.0;
  TangentPoint pt("johnson_cook", v);
  pt.set_stress_bar(Mat3::diag(-1e8, -1.2e8, -0.9e8));
  pt.set_state("eqps", 0.1);
  pt.set_state("temperature", 600.0);
  // dt = 1e-5 s with Delta eps_p ~ 1e-2: rate ~ 1e3/s, ln(eps_dot*) ~ 7.
  const TangentError c = fd_tangent_error(pt, plastic_increment(), 1e-5, kH);
  EXPECT_LT(c.rel_err, kTol);
  EXPECT_GT(pt.state_after("eqps"), 0.1);
  EXPECT_GT(pt.state_after("temperature"), 600.0);  // heated
  // From eps_p = 0 (infinite hardening slope at the first yield, n = 0.31).
  pt.set_state("eqps", 0.0);
  EXPECT_LT(fd_tangent_error(pt, plastic_increment(), 1e-5, kH).rel_err, kTol);
  // Elastic step.
  pt.set_stress_bar(Mat3::diag(-1e7, -1.1e7, -0.9e7));
  EXPECT_LT(fd_tangent_error(pt, (0.1) * elastic_increment(), 1e-5, kH * 0.1).rel_err, kTol);
  EXPECT_EQ(pt.state_after("eqps"), 0.0);
}

}  // namespace test_j2_tangent
