#include "verify/hook_material.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace ballista {

ParamValues complete_hook_params(const MaterialFactory& f, const ParamValues& values, const std::string& hook) {
  ParamValues v = values;
  auto fail = [&](const std::string& param, const std::string& what) {
    return Error(fmt::format("model '{}', verification hook {}: parameter '{}' {}", f.model, hook, param, what));
  };
  for (const ParamSpec& p : f.params) {
    if (!p.choices.empty()) {
      auto it = v.choices.find(p.name);
      if (it == v.choices.end()) {
        v.choices[p.name] = p.default_choice;
      } else {
        bool known = false;
        for (const auto& c : p.choices) known = known || c == it->second;
        if (!known) throw fail(p.name, "has unknown value '" + it->second + "'");
      }
      continue;
    }
    if (!v.given(p.name)) {
      if (p.required) throw fail(p.name, "is required but the hook does not set it");
      v[p.name] = p.default_value;  // NaN for an optional parameter without default, as the deck does
      continue;
    }
    const double x = v.at(p.name);
    const bool lo_ok = p.min_exclusive ? x > p.min : x >= p.min;
    const bool hi_ok = p.max_exclusive ? x < p.max : x <= p.max;
    if (!lo_ok || !hi_ok) throw fail(p.name, fmt::format("= {:g} is outside its range", x));
  }
  for (const auto& [name, x] : values) {
    bool declared = false;
    for (const ParamSpec& p : f.params) declared = declared || p.name == name;
    if (!declared) throw fail(name, "is not a parameter of the model");
  }
  return v;
}

std::unique_ptr<Material> make_hook_material(const MaterialFactory& f, const ParamValues& values,
                                             const std::string& hook) {
  const ParamValues v = complete_hook_params(f, values, hook);
  try {
    return f.create("verify_" + f.model, v);
  } catch (const ParamError& e) {
    throw Error(fmt::format("model '{}', verification hook {}: parameter '{}': {}", f.model, hook, e.param(),
                            e.what()));
  }
}

}  // namespace ballista
