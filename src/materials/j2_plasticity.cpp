// Registers the j2_plasticity model (kernel in j2_plasticity.hpp, which the unit tests also call directly).
#include "materials/j2_plasticity.hpp"

namespace ballista {

BALLISTA_REGISTER_MATERIAL(J2Plasticity,
                           "von Mises plasticity: linear/power-law/Voce isotropic and linear kinematic hardening, "
                           "radial return, EOS pressure, unrotated frame")

}  // namespace ballista
