#include "points/initial_state_registry.hpp"

#include "core/registry_impl.hpp"

namespace ballista {

template class Registry<InitialStateFactory, &InitialStateFactory::name>;

}  // namespace ballista
