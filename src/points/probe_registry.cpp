#include "points/probe_registry.hpp"

#include "core/error.hpp"
#include "core/registry_impl.hpp"

namespace ballista {

template class Registry<ProbeFactory, &ProbeFactory::name>;

std::vector<std::unique_ptr<Probe>> make_probes(const Scenario& sc) {
  std::vector<std::unique_ptr<Probe>> out;
  for (const auto& spec : sc.probes) {
    const ProbeFactory* f = find_probe(spec.type);
    if (!f) throw Error("unknown probe type '" + spec.type + "'");  // the deck reader checked it
    out.push_back(f->create(spec, sc));
  }
  return out;
}

int probe_body(const ProbeSpec& spec, const Scenario& sc) {
  const std::string name = spec.params.choice("body");
  return name.empty() ? -1 : body_index(sc, name);
}

}  // namespace ballista
