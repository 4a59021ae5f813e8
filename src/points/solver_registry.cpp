#include "points/solver_registry.hpp"

#include "core/registry.hpp"

namespace ballista {

namespace {
using SolverRegistry = Registry<SolverFactory, &SolverFactory::name>;
}  // namespace

const std::vector<SolverFactory>& solver_registry() { return SolverRegistry::sorted(); }

const SolverFactory* find_solver(const std::string& name) { return SolverRegistry::find(name); }

bool register_solver(SolverFactory factory) { return SolverRegistry::add(std::move(factory)); }

}  // namespace ballista
