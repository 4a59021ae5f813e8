#include "points/solver_registry.hpp"

#include <algorithm>

namespace ballista {

namespace {
std::vector<SolverFactory>& registry_storage() {
  static std::vector<SolverFactory> r;  // filled during static initialisation only
  return r;
}
}  // namespace

const std::vector<SolverFactory>& solver_registry() {
  auto& r = registry_storage();
  std::sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return r;
}

const SolverFactory* find_solver(const std::string& name) {
  for (const auto& f : registry_storage())
    if (f.name == name) return &f;
  return nullptr;
}

bool register_solver(SolverFactory factory) {
  registry_storage().push_back(std::move(factory));
  return true;
}

}  // namespace ballista
