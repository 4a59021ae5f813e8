// Registers the johnson_cook model (kernel in johnson_cook.hpp, which the unit tests also call directly).
#include "materials/johnson_cook.hpp"

namespace ballista {

BALLISTA_REGISTER_MATERIAL(JohnsonCook,
                           "Johnson-Cook thermo-viscoplasticity (strain, rate, temperature), adiabatic heating, melt, "
                           "EOS pressure")

}  // namespace ballista
