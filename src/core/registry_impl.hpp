#pragma once
// The members of Registry (core/registry.hpp), for the one .cpp per kind that instantiates it.
#include <algorithm>
#include <utility>

#include "core/registry.hpp"

namespace ballista {

template <class Factory, std::string Factory::*Key>
bool Registry<Factory, Key>::add(Factory factory) {
  storage().push_back(std::move(factory));
  return true;
}

template <class Factory, std::string Factory::*Key>
const std::vector<Factory>& Registry<Factory, Key>::sorted() {
  auto& r = storage();
  std::sort(r.begin(), r.end(), [](const Factory& a, const Factory& b) { return a.*Key < b.*Key; });
  return r;
}

template <class Factory, std::string Factory::*Key>
const Factory* Registry<Factory, Key>::find(const std::string& name) {
  for (const Factory& f : storage())
    if (f.*Key == name) return &f;
  return nullptr;
}

template <class Factory, std::string Factory::*Key>
std::vector<Factory>& Registry<Factory, Key>::storage() {
  static std::vector<Factory> r;  // filled during static initialisation only
  return r;
}

}  // namespace ballista
