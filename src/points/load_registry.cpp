#include "points/load_registry.hpp"

#include "core/error.hpp"
#include "core/registry_impl.hpp"

namespace ballista {

template class Registry<LoadFactory, &LoadFactory::name>;

std::vector<std::unique_ptr<Load>> make_loads(const Scenario& sc) {
  std::vector<std::unique_ptr<Load>> out;
  for (size_t k = 0; k < sc.loads.size(); ++k) {
    const LoadFactory* f = find_load(sc.loads[k].type);
    if (!f || !f->create)  // the deck reader checked it
      throw Error("load type '" + sc.loads[k].type + "' cannot be applied (loads." + std::to_string(k) + ")");
    out.push_back(f->create(sc.loads[k], static_cast<int>(k), sc));
  }
  return out;
}

}  // namespace ballista
