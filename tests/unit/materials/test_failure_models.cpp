// Registers the test-only kernels of test_failure_models.hpp (unit_materials executable only), so
// that the tests can drive them by name through PointDriver and decks.
#include "test_failure_models.hpp"

namespace ballista::test {
BALLISTA_REGISTER_MATERIAL(ScriptedPoint, "test only: scripted stress, plastic strain and temperature")
BALLISTA_REGISTER_MATERIAL(ScriptedPlastic, "test only: scripted stress and plastic strain, no temperature")
BALLISTA_REGISTER_MATERIAL(HeatingJ2, "test only: J2 with linear hardening or softening and adiabatic heating")
}  // namespace ballista::test
