#pragma once
// Which deck materials use a given model (e.g. "explosive": the program burn, the solvers that
// refuse or need something for it).
#include <string>

#include "scenario/scenario.hpp"

namespace ballista {

/// The first deck material whose model is `model`, or null.
inline const MaterialSpec* first_material_of_model(const Scenario& sc, const std::string& model) {
  for (const MaterialSpec& m : sc.materials)
    if (m.model == model) return &m;
  return nullptr;
}

}  // namespace ballista
