#pragma once
// Isotropic elastic constants from any supported pair of deck parameters.
#include "materials/material.hpp"

namespace ballista {

struct ElasticConstants {
  double bulk = 0;   ///< K, Pa
  double shear = 0;  ///< G, Pa
};

/// Deck parameters shared by every isotropic elastic model: density plus exactly one pair of
/// (youngs_modulus, poisson_ratio) or (bulk_modulus, shear_modulus).
std::vector<ParamSpec> elastic_param_specs();

/// K and G from the values given; throws ParamError if neither or both pairs are given.
/// K = E / (3(1 - 2 nu)), G = E / (2(1 + nu))  (standard isotropic relations).
ElasticConstants elastic_constants_from(const ParamValues& v);

}  // namespace ballista
