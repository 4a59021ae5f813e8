#pragma once
// CATALOGUE A6 (objectivity) and the finite-difference tangent check, for every model with an
// `example` parameter set. Both run through Material::update on a MaterialBatch (PointBatch), the
// path the solvers and the single-element driver use: the driver cannot hold several points nor
// return the tangent.
#include "materials/material.hpp"
#include "verify/a6_paths.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

/// Objectivity: each random F path is run unrotated and under random superimposed rotations; the
/// unrotated stress and the state histories must agree to round-off.
VerifyCase run_a6_objectivity(const MaterialFactory& f, const A6Problem& problem = {});

/// Algorithmic tangent against central differences of the stress update, at a few steps of the
/// random paths; "no tangent" (not applicable) if the model never fills PointResult::tangent.
VerifyCase run_a6_tangent(const MaterialFactory& f, const A6Problem& problem = {});

}  // namespace ballista
