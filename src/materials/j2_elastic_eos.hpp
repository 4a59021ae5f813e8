#pragma once
// The elastic and pressure part of the parameters of the J2 family (j2_plasticity, johnson_cook).
// Both models read rho0, K and G from the elastic deck keys (elastic_param_specs()), take the
// pressure from an EOS (eos.hpp) whose energy, when stored, sits at a state slot of their own,
// and bound the time step by the same elastic wave speed. Those fields, their reading and the wave
// speed were written out in each model line for line; their Params derive from J2ElasticEos so
// that this lives in one place (the EOS is made, and its slot chosen, in each model's make(); the
// deviatoric part, the state layout and the return stay each model's own).
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/eos.hpp"

namespace ballista {

struct J2ElasticEos {
  double density = 0;    ///< rho0, kg/m^3
  double bulk = 0;       ///< K, Pa
  double shear = 0;      ///< G, Pa
  Eos eos;               ///< pressure law
  int energy_slot = -1;  ///< index of energy_density in the state, -1 if not stored

  /// density, bulk and shear from the deck (throws ParamError as elastic_constants_from).
  void read_elastic(const ParamValues& v) {
    const ElasticConstants e = elastic_constants_from(v);
    density = v.at("density");
    bulk = e.bulk;
    shear = e.shear;
  }

  /// Dilatational wave speed sqrt((K_s + 4G/3)/rho), rho = rho0/J, K_s the EOS bulk modulus (K for
  /// the linear EOS). Plastic flow only slows the deviatoric part, so the elastic speed bounds it.
  double wave_speed(const double* state, double J) const {
    const double Ks = energy_slot >= 0 ? eos_bulk_modulus(eos, J, state[energy_slot]) : eos.bulk;
    return std::sqrt((Ks + 4.0 * shear / 3.0) * J / density);
  }
};

}  // namespace ballista
