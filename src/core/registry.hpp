#pragma once
// The one registry behind materials, solvers, probes and loads: each kind registers a factory
// from its own file by a static initialiser (LAMMPS styles: one file, one line), so no central
// list names it; readers look it up by the name the deck uses.
#include <algorithm>
#include <string>
#include <vector>

namespace ballista {

/// Factories of one kind, keyed by the member `Key` (the deck's name of the kind).
template <class Factory, std::string Factory::*Key>
class Registry {
 public:
  /// Adds a factory; called from static initialisers only (returns true to initialise a flag).
  static bool add(Factory factory) {
    storage().push_back(std::move(factory));
    return true;
  }
  /// Every factory in name order (sorted on each call: registration order is link order).
  static const std::vector<Factory>& sorted() {
    auto& r = storage();
    std::sort(r.begin(), r.end(), [](const Factory& a, const Factory& b) { return a.*Key < b.*Key; });
    return r;
  }
  /// The factory of `name`, or nullptr.
  static const Factory* find(const std::string& name) {
    for (const Factory& f : storage())
      if (f.*Key == name) return &f;
    return nullptr;
  }
  /// "a, b, c": the registered names in order, for an error that lists the valid ones.
  static std::string names() {
    std::string out;
    for (const Factory& f : sorted()) out += (out.empty() ? "" : ", ") + f.*Key;
    return out;
  }

 private:
  static std::vector<Factory>& storage() {
    static std::vector<Factory> r;  // one per kind for the whole program (an inline function's static)
    return r;
  }
};

}  // namespace ballista
