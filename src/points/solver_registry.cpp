#include "points/solver_registry.hpp"

#include "core/registry_impl.hpp"

namespace ballista {

template class Registry<SolverFactory, &SolverFactory::name>;

}  // namespace ballista
