#pragma once
// CATALOGUE A4, hydrostatic compression against a fixed cap, then with cap evolution (thesis seed
// 000 §4.1.1.4, Fig. 4.10c, 4.11; eq. 4.5-4.6): F = lambda I, lambda decreasing, on the
// GeoSandstone parameters through MaterialFactory::reduce_geo.
//  (a) fixed cap: the stress stays on the hydrostat and, once it reaches the cap, dwells at I1 = P0;
//  (b) evolving cap: once yielding, I1 = X(evp) on the crush curve and the porosity follows
//      eq. 4.5 / 4.6; compared step by step with the exact response (hydrostatic_crush.hpp).
#include "materials/material.hpp"
#include "verify/hydrostatic_compare.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A4Problem {
  GeoSandstone rock;
  double ev_fixed = -0.02;   ///< (a) final total volumetric strain (the cap is met at P0/(3K) = -3e-3)
  double evp_evolve = -0.15; ///< (b) final plastic volumetric strain: porosity 20 % -> 7.0 %
  int substeps = 1000;       ///< driver steps per run (one row each)
  int plot_every = 5;
};

/// Runs A4 (both parts); not applicable without reduce_geo.
VerifyCase run_a4(const MaterialFactory& f, const A4Problem& problem = {});

}  // namespace ballista
