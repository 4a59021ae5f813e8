#pragma once
// Equations of state: the pressure part of every strength model (the deviatoric part is the
// model's own). A model that supports them appends eos_param_specs() to its parameters, declares
// the state field kEosEnergyField and, per step, splits sigma_bar = s - p I, updates s itself and
// calls eos_update() for p. This is how the Mie-Grüneisen EOS composes with any deviatoric model.
//
// eos.type = linear (default): hypoelastic pressure, p_{n+1} = p_n - K tr(D_bar) dt (the volumetric
// half of the hypoelastic update of thesis seed 000 §2.3).
//
// eos.type = mie_gruneisen: Mie-Grüneisen with a linear Us-up Hugoniot as reference curve
// (M.A. Meyers, Dynamic Behavior of Materials, Wiley 1994, §4.3 eq. 4.17 and §5.3; the same form
// as Uintah's MieGruneisen EOS and LS-DYNA *EOS_GRUNEISEN with a = 0, S2 = S3 = 0):
//   eta = 1 - J = 1 - rho0/rho                      (compression > 0)
//   p_H(eta) = rho0 c0^2 eta / (1 - s eta)^2         (eta >= 0; Rankine-Hugoniot with Us = c0 + s up)
//   p_H(eta) = rho0 c0^2 eta                         (eta < 0: linear in tension, no Hugoniot there)
//   p(J, E) = p_H (1 - Gamma0 eta / 2) + Gamma0 E    (Gamma rho = Gamma0 rho0;
//                                                    E = internal energy per reference volume)
// On the Hugoniot E = E_H = p_H eta / 2 (energy jump from a stress-free state), so p = p_H there.
// Energy is integrated with the trapezoidal rule on the pressure work, which is linear in p_{n+1}
// and solved in closed form (no iteration):
//   E_{n+1} = E_n + W_dev - (p_n + p_{n+1}) (J_{n+1} - J_n) / 2       (dE = J sigma : D dt)
// A compression beyond the Hugoniot pole eta = 1/s is outside the model: the pressure is NaN and
// the solver stops with its non-finite-stress diagnostic.
// eos.max_particle_velocity u_f (default none) ends the Us-up line where its data end, or above
// the strongest shock the problem can produce: beyond the
// Hugoniot's compression at that particle velocity, eta_f = u_f / (c0 + s u_f) (eta = up/Us,
// Meyers 1994 §4.3), p_H continues along its tangent,
//   p_H(eta) = p_H(eta_f) + p_H'(eta_f) (eta - eta_f)                      (eta > eta_f),
// instead of rising to the pole at eta = 1/s, where the stiffness and the wave speed grow without
// bound. The pole is an artefact of extrapolating a straight Us-up line (the line's limiting
// compression s/(s-1) is not a property of the material), and a point squeezed there by the
// grid, not by a shock, would set the whole run's stable step.
// eos.min_pressure (default -inf) caps tension (cavitation / spall cutoff): p >= p_min;
// eos.tension_cap: cohesive_limit sets p_min to the solid's cohesive limit (cohesive_limit.hpp).
#include <cmath>
#include <limits>
#include <vector>

#include "materials/material.hpp"

namespace ballista {

/// State field holding E, the internal energy per unit reference volume (J/m^3).
inline constexpr FieldKey<double> kEosEnergy{"energy_density"};
inline constexpr const char* kEosEnergyField = kEosEnergy.name();

struct Eos {
  enum class Kind { Linear, MieGruneisen };
  Kind kind = Kind::Linear;
  double bulk = 0.0;    ///< K, Pa (linear; also the reference modulus rho0 c0^2 of Mie-Grüneisen)
  double rho0 = 0.0;    ///< kg/m^3
  double c0 = 0.0;      ///< bulk sound speed, intercept of the Us-up line, m/s
  double s = 0.0;       ///< slope of the Us-up line, 1
  double gamma0 = 0.0;  ///< Grüneisen coefficient at the reference state, 1
  double p_min = -std::numeric_limits<double>::infinity();  ///< tension cutoff, Pa
  /// Compression eta_f where the Us-up line ends (eos.max_particle_velocity); +inf: to the pole.
  double eta_fit = std::numeric_limits<double>::infinity();
  double p_fit = 0.0;   ///< p_H(eta_f) on the line, Pa
  double dp_fit = 0.0;  ///< p_H'(eta_f) on the line, Pa
};

/// eos.type, eos.sound_speed, eos.hugoniot_slope, eos.gruneisen_gamma, eos.min_pressure,
/// eos.max_particle_velocity.
std::vector<ParamSpec> eos_param_specs();

/// Reads the eos.* parameters; `bulk` is the model's elastic bulk modulus (used by eos.type
/// linear), `density` its rho0. Throws ParamError naming the missing or inconsistent key.
Eos make_eos(const ParamValues& v, double bulk, double density);

/// State fields the EOS needs (the energy density).
inline StateFieldSpec eos_state_field() {
  return {kEosEnergyField, "J/m^3", 0.0};
}

/// p_H beyond the end of the Us-up line (eta > eta_f): its tangent there. Out of line, so that the
/// line's own path compiles as it did without the key (its results bitwise unchanged).
[[gnu::noinline]] double eos_hugoniot_tangent(const Eos& e, double eta);

/// The Us-up line's Hugoniot pressure rho0 c0^2 eta / (1 - s eta)^2 at 0 <= eta, Pa; NaN beyond its
/// pole eta = 1/s.
inline double eos_line_pressure(const Eos& e, double eta) {
  const double k0 = e.rho0 * e.c0 * e.c0;
  const double den = 1.0 - e.s * eta;
  if (!(den > 0.0)) return std::numeric_limits<double>::quiet_NaN();  // beyond the Hugoniot pole
  return k0 * eta / (den * den);
}

/// Reference (Hugoniot) pressure p_H(J) of the Mie-Grüneisen EOS, Pa.
inline double eos_hugoniot_pressure(const Eos& e, double J) {
  const double eta = 1.0 - J;
  if (eta < 0.0) return e.rho0 * e.c0 * e.c0 * eta;
  if (eta > e.eta_fit) [[unlikely]] return eos_hugoniot_tangent(e, eta);
  return eos_line_pressure(e, eta);
}

/// Mie-Grüneisen pressure p(J, E), E the energy per reference volume, before the tension cutoff.
inline double eos_mg_pressure(const Eos& e, double J, double energy) {
  const double eta = 1.0 - J;
  return eos_hugoniot_pressure(e, J) * (1.0 - 0.5 * e.gamma0 * eta) + e.gamma0 * energy;
}

/// Pressure at t_{n+1} from p_n, J_n -> J_{n+1} (k.J_old, k.J_new), and the energy update.
/// `energy` is E (J/m^3 of reference volume) in and out; `dev_work` is the deviatoric work over
/// the step per reference volume, J_mid s_mid : D_bar dt.
inline double eos_update(const Eos& e, const PointKinematics& k, double p_old, double& energy, double dev_work) {
  const double dJ = k.J_new - k.J_old;
  double p_new;
  if (e.kind == Eos::Kind::Linear) {
    p_new = p_old - e.bulk * trace(k.D_bar) * k.dt;
  } else {
    // p_{n+1} = A + Gamma0 E_{n+1}, E_{n+1} = E_n + W_dev - (p_n + p_{n+1}) dJ / 2, solved for p.
    const double eta = 1.0 - k.J_new;
    const double A = eos_hugoniot_pressure(e, k.J_new) * (1.0 - 0.5 * e.gamma0 * eta);
    p_new = (A + e.gamma0 * (energy + dev_work - 0.5 * p_old * dJ)) / (1.0 + 0.5 * e.gamma0 * dJ);
  }
  if (p_new < e.p_min) p_new = e.p_min;
  energy += dev_work - 0.5 * (p_old + p_new) * dJ;
  return p_new;
}

/// Slope dp_H/deta of the Us-up line at 0 <= eta < 1/s: the derivative of rho0 c0^2 eta / (1 - s eta)^2,
/// rho0 c0^2 (1 + s eta) / (1 - s eta)^3.
inline double eos_line_slope(const Eos& e, double eta) {
  const double k0 = e.rho0 * e.c0 * e.c0;
  const double den = 1.0 - e.s * eta;
  return k0 * (1.0 + e.s * eta) / (den * den * den);
}

/// Isentropic bulk modulus rho dp/drho at (J, E), Pa, given the reference curve's slope p_H' there.
/// Along an isentrope dE = p d(eta), so
///   dp/deta|_s = p_H' (1 - Gamma0 eta/2) - Gamma0 p_H / 2 + Gamma0 p,   rho dp/drho = (1 - eta) dp/deta;
/// bounded below by the reference rho0 c0^2 / 2 so that tension never gives a vanishing speed.
inline double eos_modulus_with_slope(const Eos& e, double J, double energy, double dpH) {
  const double eta = 1.0 - J;
  const double k0 = e.rho0 * e.c0 * e.c0;
  const double p = eos_mg_pressure(e, J, energy);
  const double dp = dpH * (1.0 - 0.5 * e.gamma0 * eta) - 0.5 * e.gamma0 * eos_hugoniot_pressure(e, J) + e.gamma0 * p;
  return std::max((1.0 - eta) * dp, 0.5 * k0);
}

/// eos_bulk_modulus beyond the end of the Us-up line (eta > eta_f), with the tangent's slope; out of
/// line for the same reason as eos_hugoniot_tangent.
[[gnu::noinline]] double eos_bulk_modulus_tangent(const Eos& e, double J, double energy);

/// Isentropic bulk modulus rho dp/drho at (J, E), Pa, for the time-step estimate
/// (eos_modulus_with_slope): p_H' = rho0 c0^2 in tension, the line's slope up to eta_f, its value at
/// eta_f beyond; infinite past the line's pole when the line does not end.
inline double eos_bulk_modulus(const Eos& e, double J, double energy) {
  if (e.kind == Eos::Kind::Linear) return e.bulk;
  const double eta = 1.0 - J;
  if (eta > e.eta_fit) [[unlikely]] return eos_bulk_modulus_tangent(e, J, energy);
  double dpH = e.rho0 * e.c0 * e.c0;
  if (eta >= 0.0) {
    if (!(1.0 - e.s * eta > 0.0)) return std::numeric_limits<double>::infinity();
    dpH = eos_line_slope(e, eta);
  }
  return eos_modulus_with_slope(e, J, energy, dpH);
}

}  // namespace ballista
