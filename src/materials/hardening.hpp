#pragma once
// Isotropic hardening laws of the J2 family: the flow stress sigma_y(eps_p) as a function of the
// equivalent plastic strain, with its slope and its exact integral (the plastic work). Selected by
// the enumerated parameter `hardening_law`; each law is monotone non-decreasing, which the
// bracketed return of j2_return.hpp relies on.
//
//   linear     sigma_y = sigma_y0 + H eps_p
//              (Simo & Hughes, Computational Inelasticity, Springer 1998, §3.3.1 and Box 3.1:
//              K(alpha) = sigma_Y + K' alpha in their notation, alpha = eps_p)
//   power_law  sigma_y = sigma_y0 + k eps_p^n
//              (P. Ludwik, Elemente der technologischen Mechanik, Springer 1909; the A + B eps^n
//              factor of Johnson & Cook 1983 has the same form)
//   voce       sigma_y = sigma_y0 + H eps_p + Q (1 - exp(-b eps_p))
//              (E. Voce, J. Inst. Metals 74 (1948) 537-562: exponential saturation; with the linear
//              term as the "saturation hardening" law of Simo & Hughes 1998 Ch. 3 and the nonlinear
//              isotropic hardening laws of de Souza Neto, Peric & Owen, Computational Methods for
//              Plasticity, Wiley 2008, Ch. 6)
//
// Kinematic hardening (linear Prager-Ziegler backstress) is independent of the law chosen here; it
// lives in j2_return.hpp and j2_plasticity.hpp.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "materials/material.hpp"

namespace ballista {

enum class HardeningLaw { Linear, PowerLaw, Voce };

/// Flow stress of isotropic hardening; all stresses in Pa, eps_p dimensionless.
struct IsotropicHardening {
  HardeningLaw law = HardeningLaw::Linear;
  double yield0 = 0.0;      ///< sigma_y0, initial yield stress in uniaxial tension, Pa
  double modulus = 0.0;     ///< H, linear part (linear and voce), Pa
  double coefficient = 0.0; ///< k, power_law, Pa
  double exponent = 1.0;    ///< n, power_law, > 0
  double saturation = 0.0;  ///< Q, voce, Pa (>= 0)
  double rate = 0.0;        ///< b, voce, > 0

  /// sigma_y(e), Pa.
  double value(double e) const {
    switch (law) {
      case HardeningLaw::Linear: return yield0 + modulus * e;
      case HardeningLaw::PowerLaw: return yield0 + coefficient * std::pow(e, exponent);
      case HardeningLaw::Voce: return yield0 + modulus * e - saturation * std::expm1(-rate * e);
    }
    return yield0;
  }

  /// d sigma_y / d e, Pa. For power_law with n < 1 it is +inf at e = 0 (the return never evaluates
  /// it there: see j2_return.hpp).
  double slope(double e) const {
    switch (law) {
      case HardeningLaw::Linear: return modulus;
      case HardeningLaw::PowerLaw:
        if (coefficient == 0.0) return 0.0;
        return coefficient * exponent * std::pow(e, exponent - 1.0);
      case HardeningLaw::Voce: return modulus + saturation * rate * std::exp(-rate * e);
    }
    return 0.0;
  }

  /// Exact integral of sigma_y over [e0, e0 + de], J/m^3 (the plastic work of an increment, so
  /// that summed over steps it equals int sigma_y d eps_p whatever the step size). Written with
  /// expm1/log1p so that a small increment on top of a large e0 loses no digits.
  double integral(double e0, double de) const {
    switch (law) {
      case HardeningLaw::Linear: return (yield0 + modulus * (e0 + 0.5 * de)) * de;
      case HardeningLaw::PowerLaw: {
        // k/(n+1) [(e0 + de)^(n+1) - e0^(n+1)]
        const double m = exponent + 1.0;
        const double diff = e0 > 0.0 ? std::pow(e0, m) * std::expm1(m * std::log1p(de / e0)) : std::pow(de, m);
        return yield0 * de + coefficient * diff / m;
      }
      case HardeningLaw::Voce: {
        // H (e0 de + de^2/2) + Q [de - exp(-b e0) (1 - exp(-b de)) / b]
        const double sat = de + std::exp(-rate * e0) * std::expm1(-rate * de) / rate;
        return (yield0 + modulus * (e0 + 0.5 * de)) * de + saturation * sat;
      }
    }
    return 0.0;
  }
};

/// Deck parameters of the hardening laws beyond yield_stress and hardening_modulus (which the
/// models declare themselves): hardening_law, hardening_coefficient, hardening_exponent,
/// saturation_stress, saturation_rate.
inline std::vector<ParamSpec> hardening_param_specs() {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParamSpec law{"hardening_law", "",
                "isotropic hardening: linear (sigma_y0 + H e), power_law (sigma_y0 + k e^n) or voce "
                "(sigma_y0 + H e + Q (1 - exp(-b e)))",
                false};
  law.choices = {"linear", "power_law", "voce"};
  law.default_choice = "linear";
  return {
      law,
      {"hardening_coefficient", "Pa", "power_law: coefficient k of sigma_y = sigma_y0 + k eps_p^n", false, nan, 0.0,
       inf, false, false},
      {"hardening_exponent", "1", "power_law: exponent n (> 0; n < 1 gives an infinite initial slope)", false, nan,
       0.0, inf, true, false},
      {"saturation_stress", "Pa", "voce: saturation stress Q of Q (1 - exp(-b eps_p))", false, nan, 0.0, inf, false,
       false},
      {"saturation_rate", "1", "voce: saturation rate b of Q (1 - exp(-b eps_p))", false, nan, 0.0, inf, true, false},
  };
}

/// Builds the hardening law from yield_stress, hardening_modulus and the parameters above. A
/// parameter that the chosen law does not use is an error (it would be silently ignored).
inline IsotropicHardening make_hardening(const ParamValues& v) {
  IsotropicHardening h;
  if (!v.given("yield_stress")) throw ParamError("yield_stress", "yield_stress is required");
  h.yield0 = v.at("yield_stress");
  if (!(h.yield0 > 0.0)) throw ParamError("yield_stress", "yield_stress must be > 0");
  h.modulus = v.number_or("hardening_modulus", 0.0);
  if (!(h.modulus >= 0.0)) throw ParamError("hardening_modulus", "hardening_modulus must be >= 0");
  const std::string law = v.choice("hardening_law", "linear");
  auto unused = [&](const char* key) {
    if (v.given(key))
      throw ParamError(key, std::string(key) + " is not used by hardening_law " + law +
                                " (power_law uses hardening_coefficient, hardening_exponent; voce uses "
                                "hardening_modulus, saturation_stress, saturation_rate)");
  };
  auto required = [&](const char* key) {
    if (!v.given(key)) throw ParamError(key, std::string(key) + " is required when hardening_law is " + law);
    return v.at(key);
  };
  if (law == "linear") {
    h.law = HardeningLaw::Linear;
    for (const char* k : {"hardening_coefficient", "hardening_exponent", "saturation_stress", "saturation_rate"})
      unused(k);
  } else if (law == "power_law") {
    h.law = HardeningLaw::PowerLaw;
    for (const char* k : {"saturation_stress", "saturation_rate"}) unused(k);
    if (h.modulus != 0.0)
      throw ParamError("hardening_modulus",
                       "hardening_modulus is not used by hardening_law power_law (sigma_y = sigma_y0 + k eps_p^n); "
                       "use voce for a linear term");
    h.coefficient = required("hardening_coefficient");
    h.exponent = required("hardening_exponent");
    if (!(h.coefficient >= 0.0)) throw ParamError("hardening_coefficient", "hardening_coefficient must be >= 0");
    if (!(h.exponent > 0.0)) throw ParamError("hardening_exponent", "hardening_exponent must be > 0");
  } else if (law == "voce") {
    h.law = HardeningLaw::Voce;
    for (const char* k : {"hardening_coefficient", "hardening_exponent"}) unused(k);
    h.saturation = required("saturation_stress");
    h.rate = required("saturation_rate");
    if (!(h.saturation >= 0.0)) throw ParamError("saturation_stress", "saturation_stress must be >= 0");
    if (!(h.rate > 0.0)) throw ParamError("saturation_rate", "saturation_rate must be > 0");
  } else {
    throw ParamError("hardening_law", "unknown hardening_law '" + law + "' (expected linear, power_law or voce)");
  }
  return h;
}

}  // namespace ballista
