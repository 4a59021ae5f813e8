#pragma once
// Materials built from the verification hooks of a MaterialFactory (example, reduce_elastic,
// reduce_j2) the way the deck builds them: parameters the hook leaves out get their ParamSpec
// default (NaN for optional ones, default_choice for words), required ones must be present and
// every number must lie in its declared range. A hook that produces an invalid set is a bug of
// the model, reported by name.
#include <memory>
#include <string>

#include "materials/material.hpp"

namespace ballista {

/// `values` completed with the factory's defaults and checked against its ParamSpecs; throws
/// Error naming the model, the hook and the parameter.
ParamValues complete_hook_params(const MaterialFactory& f, const ParamValues& values, const std::string& hook);

/// f.create("verify_<model>", complete_hook_params(...)); ParamError from the model is rethrown as
/// Error naming the hook.
std::unique_ptr<Material> make_hook_material(const MaterialFactory& f, const ParamValues& values,
                                             const std::string& hook);

}  // namespace ballista
