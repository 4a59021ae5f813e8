#pragma once
// Test-only kernels for the failure criteria (registered in test_failure_models.cpp, so they
// exist only in the unit_materials executable). They fill the PointResult fields that the real
// plasticity models fill, with values a test can predict exactly:
//
//   test_scripted_point      fixed unrotated stress, eps_p growing at a given rate, T* given
//                            (kTracksPlasticStrain and kTracksTemperature);
//   test_scripted_plastic    the same without temperature (kTracksPlasticStrain only);
//   test_heating_j2          hypoelastic J2 with linear hardening H (H < 0 softens), Drucker's
//                            product and adiabatic heating by the plastic work (thesis eq. 6.7).
#include <cmath>
#include <vector>

#include "materials/material_adapter.hpp"

namespace ballista::test {

/// Scripted point: sigma_bar = the given stress every step; Delta eps_p = eqps_rate dt;
/// T* = tstar0 + tstar_rate t; Drucker product = the given value (J/m^3) on every step.
struct ScriptedBase {
  struct Params {
    double density = 1000.0;
    Mat3 stress;
    double eqps_rate = 0.0;   ///< 1/s
    double tstar0 = 0.0;      ///< initial homologous temperature
    double tstar_rate = 0.0;  ///< 1/s
    double drucker = 0.0;     ///< J/m^3 per step
  };
  static std::vector<ParamSpec> param_specs() {
    std::vector<ParamSpec> s;
    for (const char* n : {"density", "stress_11", "stress_22", "stress_33", "stress_12", "eqps_rate", "tstar0",
                          "tstar_rate", "drucker"})
      s.push_back({n, "", "test parameter", false, 0.0});
    s[0].default_value = 1000.0;
    return s;
  }
  static Params make(const ParamValues& v) {
    Params p;
    p.density = v.number_or("density", 1000.0);
    p.stress(0, 0) = v.number_or("stress_11", 0.0);
    p.stress(1, 1) = v.number_or("stress_22", 0.0);
    p.stress(2, 2) = v.number_or("stress_33", 0.0);
    p.stress(0, 1) = p.stress(1, 0) = v.number_or("stress_12", 0.0);
    p.eqps_rate = v.number_or("eqps_rate", 0.0);
    p.tstar0 = v.number_or("tstar0", 0.0);
    p.tstar_rate = v.number_or("tstar_rate", 0.0);
    p.drucker = v.number_or("drucker", 0.0);
    return p;
  }
  static std::vector<StateFieldSpec> state_fields() { return {{"eqps", "1", 0.0}, {"time", "s", 0.0}}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& r) {
    s = p.stress;
    r.delta_eqps = p.eqps_rate * k.dt;
    state[0] += r.delta_eqps;
    state[1] += k.dt;
    r.eqps = state[0];
    r.homologous_temperature = p.tstar0 + p.tstar_rate * state[1];
    r.temperature = 300.0 + 1000.0 * r.homologous_temperature;
    r.drucker_product = p.drucker;
  }
  static double wave_speed(const Params&, const double*, double) { return 1.0; }
};

struct ScriptedPoint : ScriptedBase {
  static constexpr const char* kName = "test_scripted_point";
  static constexpr bool kTracksPlasticStrain = true;
  static constexpr bool kTracksTemperature = true;
};

struct ScriptedPlastic : ScriptedBase {
  static constexpr const char* kName = "test_scripted_plastic";
  static constexpr bool kTracksPlasticStrain = true;
};

/// Radial return for linear hardening (Simo & Hughes 1998 Box 3.1), kept here in closed form so
/// that this test model may soften (H < 0, exact while 3G + H > 0), which the library's bracketed
/// return does not need to support.
struct LinearReturn {
  double delta_eqps = 0.0, plastic_work = 0.0;
};
inline LinearReturn linear_radial_return(Mat3& sigma, double& eqps, double G, double sy0, double H) {
  LinearReturn r;
  const double mean = trace(sigma) / 3.0;
  const Mat3 dev = deviator(sigma);
  const double q = std::sqrt(1.5 * ddot(dev, dev));
  const double sy_n = sy0 + H * eqps;
  if (!(q - sy_n > 0.0)) return r;
  r.delta_eqps = (q - sy_n) / (3.0 * G + H);
  sigma = (1.0 - 3.0 * G * r.delta_eqps / q) * dev + mean * Mat3::identity();
  r.plastic_work = (sy_n + 0.5 * H * r.delta_eqps) * r.delta_eqps;
  eqps += r.delta_eqps;
  return r;
}

/// Hypoelastic J2 with linear hardening sigma_y = sigma_y0 + H eps_p (H may be negative, see
/// linear_radial_return), Drucker's product
/// (sigma_{n+1} - sigma_n) : Delta eps^p with Delta eps^p = Delta eps_p (3/2) s_{n+1}/q_{n+1}, and
/// adiabatic heating T += chi W_p/(rho0 c_p) (thesis eq. 6.7 with the exact plastic work of the
/// step, W_p = int sigma_y d eps_p).
struct HeatingJ2 {
  static constexpr const char* kName = "test_heating_j2";
  static constexpr bool kTracksPlasticStrain = true;
  static constexpr bool kTracksTemperature = true;
  struct Params {
    double density = 0, bulk = 0, shear = 0, yield = 0, hardening = 0;
    double chi = 0.9, cp = 400.0, T0 = 300.0, Tm = 1300.0;
  };
  static std::vector<ParamSpec> param_specs() {
    std::vector<ParamSpec> s;
    for (const char* n : {"density", "bulk_modulus", "shear_modulus", "yield_stress", "hardening_modulus",
                          "taylor_quinney", "specific_heat", "reference_temperature", "melt_temperature"})
      s.push_back({n, "", "test parameter", false, 0.0});
    return s;
  }
  static Params make(const ParamValues& v) {
    Params p;
    p.density = v.at("density");
    p.bulk = v.at("bulk_modulus");
    p.shear = v.at("shear_modulus");
    p.yield = v.at("yield_stress");
    p.hardening = v.number_or("hardening_modulus", 0.0);
    p.chi = v.number_or("taylor_quinney", 0.9);
    p.cp = v.number_or("specific_heat", 400.0);
    p.T0 = v.number_or("reference_temperature", 300.0);
    p.Tm = v.number_or("melt_temperature", 1300.0);
    return p;
  }
  /// The temperature field starts at 300 K: the tests use reference_temperature = 300.
  static std::vector<StateFieldSpec> state_fields() { return {{"eqps", "1", 0.0}, {"temperature", "K", 300.0}}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& r) {
    const Mat3 s_old = s;
    const double lam = p.bulk - 2.0 * p.shear / 3.0;
    s += k.dt * (2.0 * p.shear) * k.D_bar;
    const double iso = k.dt * lam * trace(k.D_bar);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    const LinearReturn ret = linear_radial_return(s, state[0], p.shear, p.yield, p.hardening);
    r.delta_eqps = ret.delta_eqps;
    r.eqps = state[0];
    r.plastic_work_density = ret.plastic_work;
    if (ret.delta_eqps > 0.0) {
      const Mat3 dev = deviator(s);
      const double q = std::sqrt(1.5 * ddot(dev, dev));
      r.drucker_product = ddot(s - s_old, (1.5 * ret.delta_eqps / q) * dev);
    }
    state[1] += p.chi * ret.plastic_work / (p.density * p.cp);
    r.temperature = state[1];
    r.homologous_temperature = (state[1] - p.T0) / (p.Tm - p.T0);
  }
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

}  // namespace ballista::test
