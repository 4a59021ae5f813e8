#pragma once
// Which deck materials, and bodies, use a given model (e.g. "explosive": the program burn, the
// solvers that refuse or need something for it, the charge that is not a perforated layer).
#include <string>

#include "scenario/scenario.hpp"

namespace ballista {

/// The first deck material whose model is `model`, or null.
inline const MaterialSpec* first_material_of_model(const Scenario& sc, const std::string& model) {
  for (const MaterialSpec& m : sc.materials)
    if (m.model == model) return &m;
  return nullptr;
}

/// Whether body `b` is made of a deck material whose model is `model`.
inline bool body_of_model(const Scenario& sc, const BodySpec& b, const std::string& model) {
  for (const MaterialSpec& m : sc.materials)
    if (m.name == b.material && m.model == model) return true;
  return false;
}

}  // namespace ballista
