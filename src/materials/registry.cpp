#include "materials/material.hpp"

#include "core/registry_impl.hpp"

namespace ballista {

template class Registry<MaterialFactory, &MaterialFactory::model>;

}  // namespace ballista
