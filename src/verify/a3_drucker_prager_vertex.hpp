#pragma once
// CATALOGUE A3, the linear Drucker-Prager vertex test of Brannon & Leelavanichkul (Int. J. Fract.
// 163 (2010) 133-149; thesis seed 000 §4.1.1.3, eq. 4.2-4.4, Fig. 4.8-4.9; Uintah Arenisca test
// 02): K = 10000, G = 3750, r0 = 50, z0 = 50 sqrt(3) (PEAKI1 = 150, FSLOPE = 0.2357), no cap,
// non-associative flow beta = 1/2 (see drucker_prager_triaxial.hpp for why), the F table of
// A3Reference: hydrostatic compression to t = 1, a leg that reaches the surface at t = 1.5 and
// dwells to t = 2, a leg that reaches it again at t = 2.5 with a trial-stress rate parallel to
// the normal to t = 3. Compared with the published stresses at t = 1 ... 3.
#include "materials/material.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A3Problem {
  double density = 1050.0;  ///< kg/m^3 (Uintah's input; any: no inertia)
  int substeps = 1000;      ///< driver steps per table row (headline run)
  int plot_every = 10;      ///< plotted series keep every n-th step
};

/// Runs A3 on the model's reduce_geo parameters (GeoReduction::flow_beta = 1/2); not applicable
/// without the hook, or if it returns no parameters (a model without non-associative flow).
VerifyCase run_a3(const MaterialFactory& f, const A3Problem& problem = {});

}  // namespace ballista
