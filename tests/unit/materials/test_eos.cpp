// Mie-Grüneisen EOS through the models that compose it (water, linear_elastic with
// eos.type mie_gruneisen), checked against closed forms that do not use the code's formula:
// the Rankine-Hugoniot jump conditions of the Us-up line, the Grüneisen relation off the
// Hugoniot, an independent ODE integration of the isentrope, and the stored deviatoric energy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "material_driver.hpp"
#include "materials/eos.hpp"

namespace test_eos {

using namespace ballista;
using namespace ballista::test;

namespace {

// Water: the model's defaults (Steinberg 1996, see water.cpp). Copper-like solid for
// linear_elastic: rho0 8930, c0 3940 m/s, s 1.49, Gamma0 2.0 (of the order of Steinberg's Cu).
struct MG {
  double rho0, c0, s, gamma0;
};
constexpr MG kWater{998.2, 1647.0, 1.921, 0.35};
constexpr MG kCopper{8930.0, 3940.0, 1.49, 2.0};
constexpr double kCuK = 137e9, kCuG = 45e9;

ParamValues water_values() { return {}; }  // all defaults

ParamValues copper_values() {
  ParamValues v{{"density", kCopper.rho0},      {"bulk_modulus", kCuK},
                {"shear_modulus", kCuG},        {"eos.sound_speed", kCopper.c0},
                {"eos.hugoniot_slope", kCopper.s}, {"eos.gruneisen_gamma", kCopper.gamma0}};
  v.choices["eos.type"] = "mie_gruneisen";
  return v;
}

/// Pressure of point 0 at F with energy E per reference volume: one step with L = 0 and
/// F_old = F_new, after which p_{n+1} = p(J, E) (eos_update with dJ = 0 and no work).
double pressure_at(PointDriver& d, const Mat3& F, double E) {
  d.state(kEosEnergyField) = E;
  d.F() = F;
  d.set_F(0, F);
  d.store().view<Mat3>("L")[0] = Mat3{};
  d.step(1e-9, {0});
  return -trace(d.stress()) / 3.0;
}

/// The Mie-Grüneisen pressure written from the Us-up line (independently of eos.hpp):
/// p_H = rho0 c0^2 eta / (1 - s eta)^2, p = p_H (1 - Gamma0 eta / 2) + Gamma0 E.
double mg_pressure(const MG& m, double J, double E) {
  const double eta = 1.0 - J;
  const double pH = m.rho0 * m.c0 * m.c0 * eta / ((1.0 - m.s * eta) * (1.0 - m.s * eta));
  return pH * (1.0 - 0.5 * m.gamma0 * eta) + m.gamma0 * E;
}

/// Isentrope through (J, E) = (1, 0): dE/dJ = -p(J, E) (E per reference volume: dE = -p dJ),
/// classical RK4 with 20000 steps (error ~ h^4, far below the tolerances used).
double isentrope_energy(const MG& m, double J_end) {
  const int n = 20000;
  const double h = (J_end - 1.0) / n;
  double J = 1.0, E = 0.0;
  auto f = [&](double j, double e) { return -mg_pressure(m, j, e); };
  for (int i = 0; i < n; ++i) {
    const double k1 = f(J, E), k2 = f(J + 0.5 * h, E + 0.5 * h * k1), k3 = f(J + 0.5 * h, E + 0.5 * h * k2),
                 k4 = f(J + h, E + h * k3);
    E += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    J += h;
  }
  return E;
}

/// Pressure after compressing spherically from J = 1 to J_end in N equal steps of J.
double compressed_pressure(const std::string& model, const ParamValues& v, double J_end, int N) {
  PointDriver d(model, v);
  for (int n = 1; n <= N; ++n) {
    const double J = 1.0 + (J_end - 1.0) * n / N;
    d.advance(std::cbrt(J) * Mat3::identity(), 1e-8);
  }
  return -trace(d.stress()) / 3.0;
}

}  // namespace

// On the Hugoniot: for a particle velocity up, Us = c0 + s up, the jump conditions give
// eta = 1 - rho0/rho = up/Us, p = rho0 Us up and E - E0 = rho0 up^2 / 2 per reference volume.
// The model's pressure at (J = 1 - eta, E_H) is p to 1e-12 relative (eta is recomputed from J
// with an absolute round-off of 1e-16, i.e. 2e-14 relative at the smallest eta = 0.006).
// The state is a uniaxial strain F = diag(J, 1, 1), as behind a plane shock.
TEST(Eos, HugoniotMatchesRankineHugoniot) {
  for (const bool solid : {false, true}) {
    const MG m = solid ? kCopper : kWater;
    PointDriver d(solid ? "linear_elastic" : "water", solid ? copper_values() : water_values());
    for (double up : {10.0, 100.0, 500.0, 1000.0, 2000.0, 3000.0}) {
      const double Us = m.c0 + m.s * up;
      const double eta = up / Us, p = m.rho0 * Us * up, E = 0.5 * m.rho0 * up * up;
      const double p_model = pressure_at(d, Mat3::diag(1.0 - eta, 1.0, 1.0), E);
      EXPECT_NEAR(p_model, p, 1e-12 * p) << (solid ? "copper" : "water") << ", up = " << up;
      // The same through the EOS functions directly.
      Eos e;
      e.kind = Eos::Kind::MieGruneisen;
      e.rho0 = m.rho0, e.c0 = m.c0, e.s = m.s, e.gamma0 = m.gamma0;
      EXPECT_NEAR(eos_mg_pressure(e, 1.0 - eta, E), p, 1e-12 * p);
    }
  }
}

// Off the Hugoniot the Grüneisen relation p - p_H = Gamma rho (e - e_H) = Gamma0 (E - E_H) holds
// (Gamma rho = Gamma0 rho0; E per reference volume), at any energy offset (1e-12 relative).
TEST(Eos, OffHugoniotGruneisenRelation) {
  PointDriver d("water", water_values());
  const MG m = kWater;
  for (double up : {200.0, 1500.0}) {
    const double Us = m.c0 + m.s * up;
    const double eta = up / Us, pH = m.rho0 * Us * up, EH = 0.5 * m.rho0 * up * up;
    for (double dE : {-0.5 * EH, 0.3 * EH, 2.0 * EH, 1e6}) {
      const double p = pressure_at(d, Mat3::diag(1.0 - eta, 1.0, 1.0), EH + dE);
      EXPECT_NEAR(p - pH, m.gamma0 * dE, 1e-12 * pH) << "up = " << up << ", dE = " << dE;
    }
  }
}

// Energy consistency of eos_update: quasi-static spherical compression to J = 0.8 in N steps,
// driven through the adapter, converges to the isentrope (independent RK4 integration of
// dE/dJ = -p(J, E)), with an error of order 2 in the step (trapezoidal energy rule). Observed
// orders over N = 20, 40, 80, 160 must lie in [1.9, 2.1]; the finest error must be below 1e-4 of
// the pressure.
TEST(Eos, IsentropicCompressionConvergesSecondOrder) {
  const double J_end = 0.8;
  for (const bool solid : {false, true}) {
    const MG m = solid ? kCopper : kWater;
    const std::string model = solid ? "linear_elastic" : "water";
    const ParamValues v = solid ? copper_values() : water_values();
    const double p_exact = mg_pressure(m, J_end, isentrope_energy(m, J_end));
    double err_prev = 0.0;
    for (int N : {20, 40, 80, 160}) {
      const double err = std::abs(compressed_pressure(model, v, J_end, N) - p_exact);
      if (err_prev > 0.0) {
        const double order = std::log2(err_prev / err);
        std::printf("[ order    ] %s: N = %d, |p - p_isentrope| / p = %.3e, observed order %.3f\n", model.c_str(), N,
                    err / p_exact, order);
        EXPECT_GT(order, 1.9) << model << " N = " << N;
        EXPECT_LT(order, 2.1) << model << " N = " << N;
      }
      err_prev = err;
      if (N == 160) {
        EXPECT_LT(err, 1e-4 * p_exact) << model;
      }
    }
  }
}

// The deviatoric elastic work of linear_elastic + Mie-Grüneisen enters the EOS energy exactly: on
// an isochoric path (J = 1), E_{n+1} - E_n = s_mid : (s_{n+1} - s_n)/(2G) telescopes to
// |s|^2/(4G), so p = Gamma0 |s|^2/(4G) at every step whatever the path and step size (random
// isochoric stretches under a turning rotation). det F = 1 only to round-off: the remaining
// eta = 1 - det F ~ 1e-16 adds its Hugoniot pressure rho0 c0^2 eta (~1e-5 Pa), included in the
// expectation; then 1e-9 relative (the energy sums 500 increments with round-off 1e-16 each),
// plus the rounding of that Hugoniot term itself: det F computed here and in the library may
// differ by a few ulps (other contraction into fused multiply-adds), 8e-16 rho0 c0^2 = 1.1e-4 Pa.
TEST(Eos, DeviatoricWorkIsStoredInTheEnergy) {
  PointDriver d("linear_elastic", copper_values());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double a = 1.0, b = 1.0;
  for (int n = 1; n <= 500; ++n) {
    a *= 1.0 + 2e-5 * u(rng);
    b *= 1.0 + 2e-5 * u(rng);
    const Mat3 F = rotation_about(Vec3{{0.48, 0.6, 0.64}}, 2e-3 * n) * Mat3::diag(a, b, 1.0 / (a * b));
    d.advance(F, 1e-7);
    const Mat3 s = deviator(d.stress());
    const double stored = ddot(s, s) / (4.0 * kCuG);
    const double p = -trace(d.stress()) / 3.0;
    ASSERT_NEAR(d.state(kEosEnergyField), stored, 1e-9 * stored) << n;
    const double hugoniot = kCopper.rho0 * kCopper.c0 * kCopper.c0 * (1.0 - det(d.F()));
    const double hugoniot_rounding = 8e-16 * kCopper.rho0 * kCopper.c0 * kCopper.c0;
    ASSERT_NEAR(p, kCopper.gamma0 * stored + hugoniot, 1e-9 * kCopper.gamma0 * stored + hugoniot_rounding) << n;
  }
  EXPECT_GT(von_mises(d.stress()), 1e7);  // a real deviatoric stress was built up
}

// The isentropic bulk modulus used for the wave speed (eos_bulk_modulus) is rho dp/drho along the
// isentrope: compare with a centred difference of the RK4 isentrope p(J) (c^2 = -J^2/rho0 dp/dJ),
// 1e-6 relative (difference step 1e-5 in J).
TEST(Eos, WaveSpeedIsTheIsentropicSoundSpeed) {
  const MG m = kWater;
  const auto water = make_material("water", water_values());
  FieldStore st;
  water->declare_fields(st);
  st.resize(1);
  for (double J : {1.0, 0.95, 0.85}) {
    const double h = 1e-5;
    auto p_of = [&](double j) { return mg_pressure(m, j, isentrope_energy(m, j)); };
    const double dpdJ = (p_of(J + h) - p_of(J - h)) / (2.0 * h);
    const double c_exact = std::sqrt(-J * J / m.rho0 * dpdJ);
    st.real(kEosEnergyField)[0] = isentrope_energy(m, J);
    EXPECT_NEAR(water->wave_speed(st, 0, J), c_exact, 1e-6 * c_exact) << "J = " << J;
  }
  st.real(kEosEnergyField)[0] = 0.0;
  EXPECT_NEAR(water->wave_speed(st, 0, 1.0), m.c0, 1e-12 * m.c0);  // bulk sound speed at rest
}

// eos.max_particle_velocity u_f ends the Us-up line at the Hugoniot's compression for that shock,
// eta_f = u_f / (c0 + s u_f). Up to it nothing changes (the Hugoniot of the test above, bitwise);
// beyond it p_H follows the line's tangent at eta_f, written here from the jump conditions: at
// eta_f, p_f = rho0 Us u_f and dp_H/deta = rho0 c0^2 (1 + s eta_f)/(1 - s eta_f)^3 (the derivative
// of rho0 c0^2 eta/(1 - s eta)^2). So the pressure stays finite at and past the line's pole
// eta = 1/s, and the wave speed of a point squeezed there is the tangent's, not unbounded. The
// tolerances: 1e-12 relative, as above (closed forms of the same doubles).
TEST(Eos, TheUsUpLineEndsAtItsLastParticleVelocity) {
  const MG m = kCopper;
  const double uf = 4000.0;
  ParamValues v = copper_values();
  v["eos.max_particle_velocity"] = uf;
  PointDriver ended("linear_elastic", v), full("linear_elastic", copper_values());
  const double Usf = m.c0 + m.s * uf, eta_f = uf / Usf, pf = m.rho0 * Usf * uf;
  const double k0 = m.rho0 * m.c0 * m.c0;
  const double slope = k0 * (1.0 + m.s * eta_f) / std::pow(1.0 - m.s * eta_f, 3);
  // On the line, below eta_f: the same pressure as without the key, to the bit.
  for (double up : {500.0, 2000.0, 3999.0}) {
    const double eta = up / (m.c0 + m.s * up), E = 0.5 * m.rho0 * up * up;
    const Mat3 F = Mat3::diag(1.0 - eta, 1.0, 1.0);
    EXPECT_EQ(pressure_at(ended, F, E), pressure_at(full, F, E)) << "up = " << up;
  }
  // Beyond it, up to and past the pole 1/s = 0.671: the tangent, (1 - Gamma0 eta / 2) and Gamma0 E.
  for (double eta : {eta_f + 1e-3, 0.55, 1.0 / m.s, 0.75}) {
    const double E = 3.0e10;
    const double pH = pf + slope * (eta - eta_f);
    const double p = pH * (1.0 - 0.5 * m.gamma0 * eta) + m.gamma0 * E;
    EXPECT_NEAR(pressure_at(ended, Mat3::diag(1.0 - eta, 1.0, 1.0), E), p, 1e-12 * std::abs(p)) << "eta = " << eta;
  }
  // The wave speed: continuous at eta_f (the tangent's slope is the line's there) and, past it,
  // the isentropic modulus with the tangent's slope (eos.hpp), finite where the line's is not.
  const auto cu = make_material("linear_elastic", v);
  const auto cu_full = make_material("linear_elastic", copper_values());
  FieldStore st;
  cu->declare_fields(st);
  st.resize(1);
  st.real(kEosEnergyField)[0] = 0.5 * m.rho0 * uf * uf;
  const double c_below = cu->wave_speed(st, 0, 1.0 - eta_f + 1e-9), c_above = cu->wave_speed(st, 0, 1.0 - eta_f - 1e-9);
  EXPECT_NEAR(c_above, c_below, 1e-6 * c_below);
  EXPECT_NEAR(cu_full->wave_speed(st, 0, 1.0 - eta_f + 1e-9), c_below, 1e-12 * c_below);
  const double J_near_pole = 1.0 - 0.99 / m.s;  // the line's stiffness there is 1e6 times its value at rest
  EXPECT_TRUE(std::isfinite(cu->wave_speed(st, 0, 1.0 - 1.0 / m.s)));
  EXPECT_LT(cu->wave_speed(st, 0, J_near_pole), 0.1 * cu_full->wave_speed(st, 0, J_near_pole));
  // A key without a Mie-Grüneisen EOS to act on is an error, not ignored.
  ParamValues lin{{"density", m.rho0}, {"bulk_modulus", kCuK}, {"shear_modulus", kCuG},
                  {"eos.max_particle_velocity", uf}};
  EXPECT_THROW(make_material("linear_elastic", lin), ParamError);
}

// Material::reference_wave_speeds (the linear term of the bulk viscosity under
// mpm.bulk_viscosity_sound_speed: reference) is each point's wave speed with its EOS energy read as
// zero: a heated point gets the speed of the same point unheated, a cold one its own, bitwise (the
// same expression on the same doubles), and the stored energy is left as it was. The heat raises
// the Mie-Grüneisen speed (the Gamma0 E term of eos_bulk_modulus): by more than 10 % here, so the
// test fails if the energy is read.
// The reference wave speed (the bulk viscosity's `reference` sound speed) is the model's own speed
// with the EOS energy read as zero, leaving the stored energy alone: for a model whose energy is
// its only state (linear_elastic) and one whose energy follows other state (Johnson-Cook: eqps,
// temperature, energy), so that a wrong slot would show. Heat raises the Mie-Grueneisen speed
// (Gamma0 E term) by more than 10 % at 3.3 MJ/kg, so the current speed must differ.
void expect_reference_speed_reads_energy_as_zero(const std::string& model, const ParamValues& v) {
  const auto cu = make_material(model, v);
  FieldStore st;
  st.declare(kDeformationGradient, "1");
  cu->declare_fields(st);
  st.resize(3);
  const double J[3] = {0.9, 1.0, 1.6};
  for (int p = 0; p < 3; ++p) st.view(kDeformationGradient)[p] = Mat3::diag(J[p], 1.0, 1.0);
  const double heat = 3.0e10;  // J/m^3 of reference volume: 3.3 MJ/kg in copper
  double* E = st.real(kEosEnergyField);
  E[0] = heat, E[1] = 0.0, E[2] = 4.0 * heat;
  const Index all[3] = {0, 1, 2};
  double c[3], c_ref[3];
  cu->wave_speeds(st, all, 3, c);
  cu->reference_wave_speeds(st, all, 3, c_ref);
  EXPECT_EQ(E[0], heat) << model;
  EXPECT_EQ(E[2], 4.0 * heat) << model;
  double c_cold[3];
  E[0] = E[2] = 0.0;
  cu->wave_speeds(st, all, 3, c_cold);
  for (int p = 0; p < 3; ++p) EXPECT_EQ(c_ref[p], c_cold[p]) << model << " " << p;
  EXPECT_EQ(c_ref[1], c[1]) << model;
  EXPECT_GT(c[0], 1.1 * c_ref[0]) << model;
  EXPECT_GT(c[2], 1.1 * c_ref[2]) << model;
}

TEST(Eos, ReferenceWaveSpeedReadsTheEnergyAsZero) {
  expect_reference_speed_reads_energy_as_zero("linear_elastic", copper_values());
  ParamValues jc = copper_values();
  jc["jc_a"] = 90e6, jc["jc_b"] = 292e6, jc["jc_n"] = 0.31, jc["jc_c"] = 0.025, jc["jc_m"] = 1.09;
  jc["melt_temperature"] = 1356.0, jc["specific_heat"] = 383.0;  // OFHC copper (data/materials.yaml)
  expect_reference_speed_reads_energy_as_zero("johnson_cook", jc);
}

// Without an EOS energy (the linear EOS) there is nothing to read as zero: the two speeds agree.
TEST(Eos, ReferenceWaveSpeedWithoutAnEnergyIsTheWaveSpeed) {
  const auto steel = make_material("linear_elastic", {{"density", 7850.0}, {"bulk_modulus", 160e9},
                                                      {"shear_modulus", 80e9}});
  FieldStore st;
  st.declare(kDeformationGradient, "1");
  steel->declare_fields(st);
  st.resize(2);
  st.view(kDeformationGradient)[0] = Mat3::diag(0.9, 1.0, 1.0);
  st.view(kDeformationGradient)[1] = Mat3::diag(1.2, 1.0, 1.0);
  const Index all[2] = {0, 1};
  double c[2], c_ref[2];
  steel->wave_speeds(st, all, 2, c);
  steel->reference_wave_speeds(st, all, 2, c_ref);
  for (int p = 0; p < 2; ++p) EXPECT_EQ(c_ref[p], c[p]) << p;
}

}  // namespace test_eos
