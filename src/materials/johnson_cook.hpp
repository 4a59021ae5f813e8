#pragma once
// Johnson-Cook thermo-viscoplasticity: von Mises plasticity whose flow stress depends on plastic
// strain, plastic strain rate and temperature, with adiabatic heating and an equation of state.
//
// Flow stress (G.R. Johnson & W.H. Cook, "A constitutive model and data for metals subjected to
// large strains, high strain rates and high temperatures", Proc. 7th Int. Symp. Ballistics, The
// Hague 1983, pp. 541-547, eq. 1):
//   sigma_y = (A + B eps_p^n) (1 + C ln eps_dot*) (1 - T*^m),
//   eps_dot* = eps_dot_p / eps_dot_0,   T* = (T - T0)/(Tm - T0).
// Choices where the paper is silent (docs/materials.md):
//   * eps_dot* < 1: the logarithm is clamped at 0 (rate factor 1), i.e. the rate term only
//     strengthens: Abaqus Analysis User's Guide, "Johnson-Cook plasticity" / "Rate-dependent
//     yield" (R = 1 + C ln(eps_dot/eps_dot_0) for eps_dot >= eps_dot_0, static yield below).
//     Without it the flow stress would drop towards -inf as the rate vanishes and the return would
//     have no solution for small increments.
//   * T* < 0 (below the reference temperature): clamped to 0, no strengthening below T0 (Abaqus
//     "transition temperature": no temperature dependence at or below it); T*^m with non-integer
//     m is undefined for T* < 0 anyway.
//   * eps_p = 0 with n < 1: the slope n B eps_p^(n-1) is infinite at the first yield; the return
//     (j2_return.hpp) brackets the root and never evaluates the slope at Delta = 0.
// The plastic strain rate is the backward-Euler rate Delta/dt of the step (implicit in the return,
// so the rate term enters the Newton iteration and the tangent); temperature is explicit: the
// flow stress of a step uses T_n, and T is updated afterwards.
//
// Adiabatic heating (thesis seed 000 eq. 6.7; G.I. Taylor & H. Quinney, Proc. R. Soc. A 143 (1934)
// 307): Delta T = chi sigma_y Delta eps_p / (rho C_p), rho = rho0/J_{n+1}, with sigma_y Delta eps_p
// taken as the exact integral of the flow stress over the increment (rate and temperature frozen
// at their step values), which is also the plastic work of the step.
// Melting: T >= Tm means T* >= 1 and no deviatoric strength. A point whose T_n >= Tm has a zero
// deviator and accumulates no plastic strain (a fluid); a point that reaches Tm within a step
// loses its deviator at the end of that step. Pressure always comes from the EOS.
//
// Elastic predictor, pressure split and EOS composition as j2_plasticity (thesis §2.3, eq. 2.6;
// eos.hpp). State: eqps, temperature (K) [, energy_density with eos.type mie_gruneisen].
#include <cmath>

#include <fmt/format.h>

#include "materials/elastic_constants.hpp"
#include "materials/j2_elastic_eos.hpp"
#include "materials/j2_return.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct JohnsonCook {
  static constexpr const char* kName = "johnson_cook";
  static constexpr bool kTracksPlasticStrain = true;  // fills PointResult eqps, delta_eqps, drucker_product
  static constexpr bool kTracksTemperature = true;    // fills temperature, homologous_temperature
  /// density, bulk, shear, eos and energy_slot: J2ElasticEos (shared with j2_plasticity).
  struct Params : J2ElasticEos {
    double A = 0;           ///< jc_a, Pa
    double B = 0;           ///< jc_b, Pa
    double n = 1;           ///< jc_n
    double C = 0;           ///< jc_c
    double m = 1;           ///< jc_m
    double rate0 = 1;       ///< reference_strain_rate, 1/s
    double T_ref = 294;     ///< reference_temperature T0, K
    double T_melt = 0;      ///< melt_temperature Tm, K
    double T_init = 294;    ///< initial_temperature, K
    double cp = 0;          ///< specific_heat, J/(kg K)
    double chi = 0.9;       ///< taylor_quinney
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<ParamSpec> s = elastic_param_specs();
    const std::vector<ParamSpec> jc{
        {"jc_a", "Pa", "Johnson-Cook A: yield stress at eps_p = 0, reference rate and temperature", true, 0.0, 0.0,
         inf, true, false},
        {"jc_b", "Pa", "Johnson-Cook B: strain hardening coefficient of B eps_p^n", true, 0.0, 0.0, inf, false, false},
        {"jc_n", "1", "Johnson-Cook n: strain hardening exponent", true, 0.0, 0.0, inf, true, false},
        {"jc_c", "1", "Johnson-Cook C: strain-rate coefficient of 1 + C ln(eps_dot_p/eps_dot_0)", true, 0.0, 0.0, inf,
         false, false},
        {"jc_m", "1", "Johnson-Cook m: thermal softening exponent of 1 - T*^m", true, 0.0, 0.0, inf, true, false},
        {"reference_strain_rate", "1/s", "eps_dot_0 of eps_dot* = eps_dot_p/eps_dot_0", false, 1.0, 0.0, inf, true,
         false},
        {"reference_temperature", "K", "T0 of T* = (T - T0)/(Tm - T0); no softening at or below it", false, 294.0, 0.0,
         inf, true, false},
        {"melt_temperature", "K", "Tm: no deviatoric strength at or above it", true, 0.0, 0.0, inf, true, false},
        {"initial_temperature", "K", "initial temperature (default: reference_temperature)", false, nan, 0.0, inf,
         true, false},
        {"specific_heat", "J/(kg K)", "specific heat C_p of the adiabatic heating dT = chi sigma_y deps_p/(rho C_p)",
         true, 0.0, 0.0, inf, true, false},
        {"taylor_quinney", "1", "Taylor-Quinney coefficient chi: fraction of plastic work turned into heat", false, 0.9,
         0.0, 1.0, false, false},
    };
    s.insert(s.end(), jc.begin(), jc.end());
    for (ParamSpec& e : eos_param_specs()) s.push_back(std::move(e));
    return s;
  }

  static Params make(const ParamValues& v) {
    Params p;
    p.read_elastic(v);
    auto need = [&](const char* key) {
      if (!v.given(key)) throw ParamError(key, std::string(key) + " is required");
      return v.at(key);
    };
    p.A = need("jc_a");
    p.B = need("jc_b");
    p.n = need("jc_n");
    p.C = need("jc_c");
    p.m = need("jc_m");
    if (!(p.A > 0.0)) throw ParamError("jc_a", "jc_a must be > 0");
    if (!(p.B >= 0.0)) throw ParamError("jc_b", "jc_b must be >= 0");
    if (!(p.n > 0.0)) throw ParamError("jc_n", "jc_n must be > 0");
    if (!(p.C >= 0.0)) throw ParamError("jc_c", "jc_c must be >= 0");
    if (!(p.m > 0.0)) throw ParamError("jc_m", "jc_m must be > 0");
    p.rate0 = v.number_or("reference_strain_rate", 1.0);
    if (!(p.rate0 > 0.0)) throw ParamError("reference_strain_rate", "reference_strain_rate must be > 0");
    p.T_ref = v.number_or("reference_temperature", 294.0);
    if (!(p.T_ref > 0.0)) throw ParamError("reference_temperature", "reference_temperature must be > 0 K");
    p.T_melt = need("melt_temperature");
    if (!(p.T_melt > p.T_ref))
      throw ParamError("melt_temperature", "melt_temperature must exceed reference_temperature (" +
                                               fmt::format("{:.6g}", p.T_ref) + " K)");
    p.T_init = v.number_or("initial_temperature", p.T_ref);
    if (!(p.T_init > 0.0)) throw ParamError("initial_temperature", "initial_temperature must be > 0 K");
    p.cp = need("specific_heat");
    if (!(p.cp > 0.0)) throw ParamError("specific_heat", "specific_heat must be > 0");
    p.chi = v.number_or("taylor_quinney", 0.9);
    if (!(p.chi >= 0.0 && p.chi <= 1.0)) throw ParamError("taylor_quinney", "taylor_quinney must be in [0, 1]");
    p.eos = make_eos(v, p.bulk, p.density);
    if (p.eos.kind == Eos::Kind::MieGruneisen) p.energy_slot = 2;
    return p;
  }

  // Verification hooks (MaterialFactory).
  /// OFHC copper: Johnson & Cook 1983 Table 1 (density, specific heat, melting temperature, A, B,
  /// n, C, m); Mie-Grüneisen EOS and shear modulus from D.J. Steinberg, Equation of State and
  /// Strength Properties of Selected Materials, LLNL UCRL-MA-106439 (1996): c0 = 3940 m/s,
  /// s = 1.489, Gamma0 = 2.02, G0 = 47.7 GPa (Steinberg's rho0 is 8930 kg/m^3; the EOS here uses
  /// the model density 8960). Bulk modulus rho0 c0^2, consistent with the EOS.
  static ParamValues example_params() {
    ParamValues v{{"density", 8960.0},        {"bulk_modulus", 8960.0 * 3940.0 * 3940.0},
                  {"shear_modulus", 47.7e9},  {"jc_a", 90e6},
                  {"jc_b", 292e6},            {"jc_n", 0.31},
                  {"jc_c", 0.025},            {"jc_m", 1.09},
                  {"melt_temperature", 1356}, {"specific_heat", 383.0},
                  {"eos.sound_speed", 3940},  {"eos.hugoniot_slope", 1.489},
                  {"eos.gruneisen_gamma", 2.02}};
    v.choices["eos.type"] = "mie_gruneisen";
    return v;
  }
  /// Elastic reduction: a yield stress no A1 path can reach, no heating.
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"jc_a", 1e30}, {"jc_b", 0.0},
            {"jc_n", 1.0},    {"jc_c", 0.0},       {"jc_m", 1.0},       {"melt_temperature", 1e4},
            {"specific_heat", 1.0}, {"taylor_quinney", 0.0}};
  }
  /// J2 with linear isotropic hardening: A = sigma_y0, B = H_iso, n = 1, C = 0, chi = 0 (T stays at
  /// the reference temperature, so T* = 0). No kinematic hardening: empty if h_kin != 0.
  static ParamValues reduce_to_j2(double rho, double K, double G, double sy, double h_iso, double h_kin) {
    if (h_kin != 0.0) return {};
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"jc_a", sy}, {"jc_b", h_iso},
            {"jc_n", 1.0},    {"jc_c", 0.0},       {"jc_m", 1.0},       {"melt_temperature", 1e4},
            {"specific_heat", 1.0}, {"taylor_quinney", 0.0}};
  }

  /// All state fields the model can have (registry); the temperature's initial value there is NaN
  /// ("the material's initial_temperature").
  static std::vector<StateFieldSpec> state_fields() {
    return {{"eqps", "1", 0.0}, {"temperature", "K", std::numeric_limits<double>::quiet_NaN()}, eos_state_field()};
  }
  /// The fields of one material: the temperature starts at its initial_temperature (solvers set it
  /// per material with Material::initialise_state, since materials share the field). A NaN that
  /// still reaches update() is replaced there as well.
  static std::vector<StateFieldSpec> state_fields(const Params& p) {
    std::vector<StateFieldSpec> f = state_fields();
    f[1].initial = p.T_init;
    if (p.energy_slot < 0) f.pop_back();
    return f;
  }

  /// (1 - T*^m) with T* clamped to [0, 1] (the clamps of the header comment).
  static double thermal_factor(const Params& p, double T) {
    const double Ts = (T - p.T_ref) / (p.T_melt - p.T_ref);
    if (!(Ts > 0.0)) return 1.0;
    if (Ts >= 1.0) return 0.0;
    return 1.0 - std::pow(Ts, p.m);
  }

  /// The kinematics kLanes points at a time (material_lanes.hpp), this kernel lane by lane.
  static bool lanes_apply(const Params&) { return true; }

  static void update(const Params& p, const PointKinematics& k, Mat3& sigma, double* state, PointResult& res) {
    const double G = p.shear;
    double& eqps = state[0];
    double& temperature = state[1];
    if (temperature != temperature) temperature = p.T_init;  // first update of the point
    const double T_n = temperature;
    const Mat3 eps = k.dt * k.D_bar;
    double p_old;
    const Mat3 s_old = split_pressure(sigma, p_old);
    Mat3 s = deviatoric_trial(s_old, eps, G);
    DevTangent tangent = elastic_tangent(G);
    const double theta = thermal_factor(p, T_n);
    if (T_n >= p.T_melt) {
      // Melted (T* >= 1): a fluid, no deviatoric stress, no plastic strain, no dissipation.
      s = Mat3{};
      tangent = DevTangent{};
    } else {
      const double e0 = eqps;
      // A virgin point's hardening is A: pow(0, n) = +0 for n > 0, so A + B 0^n is A bitwise, and
      // most points of a run have not yielded yet (a NaN eqps still propagates).
      const double hard0 = e0 == 0.0 ? p.A : p.A + p.B * std::pow(e0, p.n);
      J2Return r = j2_trial(s, nullptr, hard0 * theta);
      if (r.plastic) {
        // Rate factor R(Delta) = 1 + C ln(max(Delta/(dt eps_dot_0), 1)); dt <= 0 (no time) is
        // treated as rate-independent.
        const double inv_rate_dt = k.dt > 0.0 ? 1.0 / (k.dt * p.rate0) : 0.0;
        // With C = 0 the factor is 1 + 0 ln x = 1 bitwise: the logarithm is not taken.
        auto rate_factor = [&](double d, double& dR) {
          const double x = d * inv_rate_dt;
          if (x > 1.0 && p.C != 0.0) {
            dR = p.C / d;
            return 1.0 + p.C * std::log(x);
          }
          dR = 0.0;
          return 1.0;
        };
        auto flow = [&](double d) {
          const double e = e0 + d;  // > 0 in practice: the return does not evaluate d = 0
          const double Ben = p.B * std::pow(e, p.n);
          const double hard = p.A + Ben;
          const double dhard = e > 0.0 ? p.n * Ben / e : 0.0;  // n B e^(n-1) (bracket keeps Newton safe)
          double dR;
          const double R = rate_factor(d, dR);
          return FlowStress{hard * R * theta, (dhard * R + hard * dR) * theta};
        };
        r.delta_eqps = j2_solve_increment(r.q_trial, r.f_trial, 3.0 * G, flow, r.slope);
        const double d = r.delta_eqps;
        const Mat3 dep = j2_apply(r, s, nullptr, G, 0.0);
        // Plastic work: exact integral of sigma_y over [e0, e0 + d] at the step's rate and T_n:
        // R theta [A d + B ((e0 + d)^(n+1) - e0^(n+1))/(n+1)] (expm1/log1p as hardening.hpp).
        double dR;
        const double R = rate_factor(d, dR);
        const double m1 = p.n + 1.0;
        const double diff = e0 > 0.0 ? std::pow(e0, m1) * std::expm1(m1 * std::log1p(d / e0)) : std::pow(d, m1);
        res.plastic_work_density = R * theta * (p.A * d + p.B * diff / m1);
        res.delta_eqps = d;
        res.drucker_product = ddot(s - s_old, dep);
        eqps += d;
        // Thesis eq. 6.7 with rho = rho0/J_{n+1}: dT = chi W_p J / (rho0 C_p).
        temperature += p.chi * res.plastic_work_density * k.J_new / (p.density * p.cp);
        if (res.tangent) tangent = plastic_tangent(r, G, 0.0);
      }
      if (temperature >= p.T_melt) {  // melted within this step
        s = Mat3{};
        tangent = DevTangent{};
      }
    }
    res.eqps = eqps;
    res.temperature = temperature;
    res.homologous_temperature = (temperature - p.T_ref) / (p.T_melt - p.T_ref);
    double scratch = 0.0;
    double& energy = p.energy_slot >= 0 ? state[p.energy_slot] : scratch;
    sigma = j2_compose_eos(p.eos, k, eps, p_old, s_old, s, energy, p.energy_slot >= 0, tangent, res);
  }

  /// Dilatational wave speed of the elastic part (J2ElasticEos::wave_speed); the elastic shear
  /// modulus is kept after melting (an upper bound, safe for the time step).
  static double wave_speed(const Params& p, const double* state, double J) { return p.wave_speed(state, J); }
};

}  // namespace ballista
