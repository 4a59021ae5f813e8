// Registers the geomodel (kernel in geomodel.hpp, which the unit tests also call directly).
#include "materials/geomodel.hpp"

namespace ballista {

BALLISTA_REGISTER_MATERIAL(Geomodel,
                           "porous rock (sandstone): Drucker-Prager limit surface with an elliptical cap on a crush "
                           "curve, pore fluid, nonlinear elasticity, optional rate dependence")

}  // namespace ballista
