#include "points/probe_registry.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace ballista {

namespace {
std::vector<ProbeFactory>& registry_storage() {
  static std::vector<ProbeFactory> r;  // filled during static initialisation only
  return r;
}
}  // namespace

const std::vector<ProbeFactory>& probe_registry() {
  auto& r = registry_storage();
  std::sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return r;
}

const ProbeFactory* find_probe(const std::string& name) {
  for (const auto& f : registry_storage())
    if (f.name == name) return &f;
  return nullptr;
}

bool register_probe(ProbeFactory factory) {
  registry_storage().push_back(std::move(factory));
  return true;
}

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
