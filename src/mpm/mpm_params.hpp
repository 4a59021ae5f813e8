#pragma once
// The deck's mpm.* parameters (their spec list; the solver reads them by name).
#include <vector>

#include "materials/material.hpp"

namespace ballista {

/// The spec of every mpm.* key, in the order docs/deck.md lists them.
std::vector<ParamSpec> mpm_params();

}  // namespace ballista
