// A high explosive with program burn (seed 001, "EMU Detonation Model"): unreacted until its
// lighting time, then detonation products (JWL or ideal gas, materials/explosive_eos.hpp) that
// expand adiabatically. The lighting times are computed once before time stepping by Huygens'
// construction (points/program_burn.hpp, from the deck's `detonation` section) into the state
// field `lighting_time` (s; -1: never lit). Strengthless: sigma = -p I.
//
//  * Unreacted (t < lighting time): a hypoelastic pressure p_{n+1} = p_n - K_u tr(D) dt with the
//    unreacted bulk modulus K_u (default rho0 (D/3)^2: unreacted explosives have a bulk sound speed
//    near D/3, e.g. TNT 2.4 km/s beside D = 6.93 km/s). The front moves at D, faster than any wave
//    in the unreacted material, so this state only matters for material that never lights.
//  * Burn (seed 001 "Volume Burn Algorithm", spread over a burn time as hydrocode programmed
//    burns do): from the lighting time on, the burn fraction F = min(1, (t - t_light) / tau)
//    grows to 1 over tau = burn_time (a state field the program burn fills: detonation.burn_cells
//    lattice spacings / D, the front's transit of a few points), and the point releases Q dF of
//    chemical energy at its current volume. With tau -> 0 this is the seed's volume burn: the
//    detonation energy Q per unit initial volume released at once, whose isentrope does the work
//    of the detonation path (for the ideal gas P = P_CJ / 2). A burn over a few steps instead of
//    one keeps the stress jump per step small, so the explicit force and the trapezoidal
//    stress-power bookkeeping agree (an instantaneous burn leaves 1/2 P dV of one step per point
//    unbooked: 3.4 % of Q in the Gurney sandwich at CFL 0.3).
//  * Products: E per unit initial volume follows dE = Q dF - p dX (X = J), p = F P_0(X) + (w/X) E
//    (P = P_0(X) + (w / X) E for both forms, the products' share F of the pressure), by the
//    trapezoidal rule, linear in p_{n+1}, hence in closed form:
//      E_{n+1} (1 + w dX / (2 X)) = E_n + Q dF - (p_n + F_{n+1} P_0(X)) dX / 2.
// Energy audit: the chemical energy Q V0 enters as the products' E; the run's internal energy is
// the stress power integral, so the products' expansion work shows as internal energy falling
// while the kinetic energy rises, and their sum stays constant (docs/materials.md).
#include <cmath>
#include <limits>

#include "materials/explosive_eos.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct Explosive {
  static constexpr const char* kName = "explosive";
  /// Lit at its program-burn time whatever its neighbours do (Material::changes_at_rest).
  static constexpr bool kChangesAtRest = true;
  struct Params {
    double density = 0.0;  ///< kg/m^3, unreacted
    ProductsEos eos;
    double Q = 0.0;        ///< J/m^3 per initial volume, the detonation energy
    double k_unreacted = 0.0;  ///< Pa
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    ParamSpec products{"products", "", "detonation products' equation of state: jwl or ideal_gas (seed 001)", false};
    products.choices = {"jwl", "ideal_gas"};
    products.default_choice = "jwl";
    return {
        {"density", "kg/m^3", "unreacted density rho0", true, 0.0, 0.0, inf, true, false},
        {"detonation_speed", "m/s", "detonation speed D (program burn; CJ state)", true, 0.0, 0.0, inf, true, false},
        products,
        {"cj_pressure", "Pa", "Chapman-Jouguet pressure P_CJ (jwl; the ideal gas takes rho0 D^2/(gamma+1))", false,
         std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
        {"jwl.a", "Pa", "JWL A", false, std::numeric_limits<double>::quiet_NaN(), 0.0, inf, false, false},
        {"jwl.b", "Pa", "JWL B", false, std::numeric_limits<double>::quiet_NaN(), 0.0, inf, false, false},
        {"jwl.r1", "1", "JWL R1", false, std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
        {"jwl.r2", "1", "JWL R2", false, std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
        {"jwl.omega", "1", "JWL omega (Grüneisen coefficient of the products)", false,
         std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
        {"gamma", "1", "ideal-gas products: ratio of specific heats (default 3)", false,
         std::numeric_limits<double>::quiet_NaN(), 1.0, inf, true, false},
        {"detonation_energy", "J/m^3",
         "published detonation energy per unit initial volume E0 (jwl: checked against the CJ state's Q within 3 %)",
         false, std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
        {"unreacted_bulk_modulus", "Pa", "bulk modulus of the unreacted explosive (default rho0 (D/3)^2)", false,
         std::numeric_limits<double>::quiet_NaN(), 0.0, inf, true, false},
    };
  }

  static Params make(const ParamValues& given) {
    const ParamValues v = with_defaults(given, param_specs());
    Params p;
    const double rho0 = v.at("density"), D = v.at("detonation_speed");
    p.density = rho0;
    if (!(rho0 > 0.0)) throw ParamError("density", "density must be > 0");
    if (!(D > 0.0)) throw ParamError("detonation_speed", "detonation_speed must be > 0");
    // A parameter of the other products form is a deck slip, not something to ignore.
    const bool ideal = v.choice("products") == "ideal_gas";
    for (const char* key : {"cj_pressure", "jwl.a", "jwl.b", "jwl.r1", "jwl.r2", "jwl.omega", "detonation_energy"})
      if (ideal && v.given(key))
        throw ParamError(key, std::string(key) + " belongs to products: jwl; the ideal gas takes P_CJ = rho0 D^2 / "
                                                 "(gamma + 1) and Q from it");
    if (!ideal && v.given("gamma")) throw ParamError("gamma", "gamma belongs to products: ideal_gas");
    if (ideal) {
      p.eos = ideal_gas_products(rho0, D, v.given("gamma") ? v.at("gamma") : 3.0);
    } else {
      for (const char* key : {"cj_pressure", "jwl.a", "jwl.b", "jwl.r1", "jwl.r2", "jwl.omega"})
        if (!v.given(key)) throw ParamError(key, std::string("products: jwl needs ") + key);
      ProductsEos& e = p.eos;
      e.kind = ProductsEos::Kind::Jwl;
      e.rho0 = rho0;
      e.D = D;
      e.p_cj = v.at("cj_pressure");
      e.A = v.at("jwl.a");
      e.B = v.at("jwl.b");
      e.R1 = v.at("jwl.r1");
      e.R2 = v.at("jwl.r2");
      e.omega = v.at("jwl.omega");
      if (!(e.p_cj < rho0 * D * D))
        throw ParamError("cj_pressure", "cj_pressure must be below rho0 D^2 (the CJ volume would not be positive)");
      if (!(jwl_cj_isentrope_constant(e) > 0.0))
        throw ParamError("cj_pressure", "the JWL exponential terms alone exceed cj_pressure at the CJ volume: the "
                                        "set is inconsistent (C of the CJ isentrope would be negative)");
      // The CJ isentrope must be tangent to the Rayleigh line (slope -rho0 D^2) at the CJ state:
      // published sets are within 0.03 % (docs/material_data.md); 2 % catches a mistyped digit.
      const double Xcj = cj_volume(e);
      const double tangency = products_isentropic_slope(e, Xcj, cj_isentrope_energy(e, Xcj)) / (-rho0 * D * D);
      if (!(std::abs(tangency - 1.0) <= 0.02))
        throw ParamError("cj_pressure", "the JWL isentrope through the CJ state is not tangent to the Rayleigh line "
                                        "(slope ratio " + std::to_string(tangency) + ", must be within 2 % of 1): "
                                        "check detonation_speed, cj_pressure and the JWL constants");
    }
    p.Q = detonation_energy(p.eos);
    if (!(p.Q > 0.0)) throw ParamError("cj_pressure", "the CJ state gives no positive detonation energy");
    if (v.given("detonation_energy") && p.eos.kind == ProductsEos::Kind::Jwl) {
      const double E0 = v.at("detonation_energy");
      if (std::abs(p.Q / E0 - 1.0) > 0.03)
        throw ParamError("detonation_energy",
                         "detonation_energy " + std::to_string(E0) + " J/m^3 disagrees with the CJ state's " +
                             std::to_string(p.Q) + " J/m^3 by more than 3 %: check the JWL set");
    }
    p.k_unreacted = v.given("unreacted_bulk_modulus") ? v.at("unreacted_bulk_modulus") : rho0 * D * D / 9.0;
    return p;
  }

  // Verification hooks (`ballista verify` A1, A2, A6): an unlit charge of TNT's magnitude.
  static ParamValues example_params() {
    ParamValues v{{"density", 1630.0}, {"detonation_speed", 6930.0}, {"cj_pressure", 21.0e9},
                  {"jwl.a", 371.2e9},  {"jwl.b", 3.231e9},          {"jwl.r1", 4.15},
                  {"jwl.r2", 0.95},    {"jwl.omega", 0.30}};
    v.choices["products"] = "jwl";
    return v;
  }

  /// lighting_time (s, -1: never), burn_time (s), burn_fraction, the products' energy per initial
  /// volume (the first two are filled by the program burn, points/explosive_lighting.hpp).
  static std::vector<StateFieldSpec> state_fields() {
    return {{kLightingTime.name(), "s", -1.0, false},  // -1 for never: not an average of two points'
            {kBurnTime.name(), "s", 0.0, false},
            {"burn_fraction", "1", 0.0},
            {"products_energy", "J/m^3", 0.0},
            {kChemicalEnergyField, "J/m^3", 0.0}};
  }

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult&) {
    const double p_old = -trace(s) / 3.0;
    const double t_light = state[0], tau = state[1];
    double pressure;
    if (!(t_light >= 0.0 && t_light <= k.time)) {
      pressure = p_old - p.k_unreacted * trace(k.D_bar) * k.dt;  // unreacted, hypoelastic
    } else {
      const double F = tau > 0.0 ? std::min(1.0, (k.time - t_light) / tau) : 1.0;
      const double dF = F - state[2];
      // p_n of the products' update: the unreacted pressure in the step the point lights.
      const double X = k.J_new, dX = k.J_new - k.J_old;
      const double w_over_X = p.eos.omega / X;  // omega = gamma - 1 for the ideal gas
      const double P0 = F * products_pressure(p.eos, X, 0.0);  // the E-independent part, products' share
      // The denominator falls below 1/2 only if the volume halves in one step (w <= 2): no stable
      // step does that, so a NaN pressure stops the run with the point's diagnostic.
      const double denominator = 1.0 + 0.5 * w_over_X * dX;
      if (!(denominator > 0.5)) {
        s = Mat3::diag(std::nan(""), std::nan(""), std::nan(""));
        return;
      }
      state[3] = (state[3] + p.Q * dF - 0.5 * (p_old + P0) * dX) / denominator;
      state[2] = F;
      state[4] = p.Q * F;
      pressure = P0 + w_over_X * state[3];
    }
    s = Mat3::diag(-pressure, -pressure, -pressure);
  }

  static double wave_speed(const Params& p, const double* state, double J) {
    // A burning point's pressure is F P(X, E/F), so its own isentropic tangent gives sqrt(F) c(X, E/F);
    // the step takes c(X, E/F), the sound speed of the products at the energy the burn is bringing
    // them to, on purpose: with the tangent's the energy the burn releases within a step outruns
    // the step near the front (measured: the PD Gurney cylinder's residual 1.5 % -> 2.4 % of the
    // chemical energy, over the 2 % bound of tests/verification/test_pd_gas.cpp).
    if (state[2] > 0.0) return products_sound_speed(p.eos, J, state[3] / state[2]);
    return std::sqrt(p.k_unreacted * J / p.eos.rho0);
  }
};

BALLISTA_REGISTER_MATERIAL(Explosive,
                           "explosive: program-burned high explosive, unreacted until lit, then JWL or ideal-gas "
                           "detonation products (seed 001)")

}  // namespace ballista
