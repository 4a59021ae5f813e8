#include "materials/material.hpp"

#include "core/registry.hpp"

namespace ballista {

namespace {
using MaterialRegistry = Registry<MaterialFactory, &MaterialFactory::model>;
}  // namespace

const std::vector<MaterialFactory>& material_registry() { return MaterialRegistry::sorted(); }

const MaterialFactory* find_material(const std::string& name) { return MaterialRegistry::find(name); }

bool register_material(MaterialFactory factory) { return MaterialRegistry::add(std::move(factory)); }

}  // namespace ballista
