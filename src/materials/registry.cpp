#include <algorithm>

#include "materials/material.hpp"

namespace ballista {

namespace {
std::vector<MaterialFactory>& registry_storage() {
  static std::vector<MaterialFactory> r;  // filled during static initialisation only
  return r;
}
}  // namespace

const std::vector<MaterialFactory>& material_registry() {
  auto& r = registry_storage();
  std::sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.model < b.model; });
  return r;
}

const MaterialFactory* find_material(const std::string& model) {
  for (const auto& f : registry_storage())
    if (f.model == model) return &f;
  return nullptr;
}

bool register_material(MaterialFactory factory) {
  registry_storage().push_back(std::move(factory));
  return true;
}

}  // namespace ballista
