#pragma once
// The one registry behind materials, solvers, probes and loads: each kind registers a factory
// from its own file by a static initialiser (LAMMPS styles: one file, one line), so no central
// list names it; readers look it up by the name the deck uses.
#include <string>
#include <vector>

namespace ballista {

/// Factories of one kind, keyed by the member `Key` (the deck's name of the kind). The members are
/// defined in core/registry_impl.hpp and instantiated once per kind, in that kind's registry .cpp
/// (`template class Registry<...>;`): a file that registers or looks up a factory calls them out
/// of line, so the code of a model's or solver's own file (and how it is optimised) is its own.
template <class Factory, std::string Factory::*Key>
class Registry {
 public:
  /// Adds a factory; called from static initialisers only (returns true to initialise a flag).
  static bool add(Factory factory);
  /// Every factory in name order (sorted on each call: registration order is link order).
  static const std::vector<Factory>& sorted();
  /// The factory of `name`, or nullptr.
  static const Factory* find(const std::string& name);

 private:
  static std::vector<Factory>& storage();
};

}  // namespace ballista

#define BALLISTA_REGISTRY_CONCAT_(a, b) a##b
#define BALLISTA_REGISTRY_CONCAT(a, b) BALLISTA_REGISTRY_CONCAT_(a, b)
/// Registers a factory in `registry` (a Registry<...> type) from a .cpp by a static initialiser.
/// The flag is named by __COUNTER__, not __LINE__: files compiled in one unity batch
/// (cmake/layers.cmake) may register on the same line.
#define BALLISTA_REGISTER(registry, ...)                                                            \
  namespace {                                                                                       \
  [[maybe_unused]] const bool BALLISTA_REGISTRY_CONCAT(ballista_registered_, __COUNTER__) = \
      registry::add(__VA_ARGS__);                                                                   \
  }
