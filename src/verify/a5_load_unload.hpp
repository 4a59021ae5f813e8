#pragma once
// CATALOGUE A5 (thesis seed 000 §4.1.1.4, Fig. 4.12, 4.13), on the GeoSandstone parameters
// through MaterialFactory::reduce_geo:
//  A5:       hydrostatic load-unload-reload: elastic compression (1-2), compaction on the crush
//            curve (2-3), elastic unloading into tension (3-4), dilatation at the vertex
//            I1 = PEAKI1 with the cap retracting along the dilatation branch (4-5), elastic
//            compression (5-6), compaction to near-full crush, 1 % of phi0 left (6-7). Compared step
//            by step with the exact hydrostatic response (hydrostatic_crush.hpp).
//  A5-fluid: the compaction leg 1-3 drained and with water in the pores (fluid_bulk = 2.2 GPa,
//            initial pore pressure 0): the saturated element is stiffer in total I1, loses less
//            porosity, and its pore pressure rises monotonically (trends of Fig. 4.13).
#include "materials/material.hpp"
#include "verify/hydrostatic_compare.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A5Problem {
  GeoSandstone rock;
  double evp3 = -0.05;            ///< plastic volumetric strain at the end of the first compaction (phi 0.2 -> 0.159)
  double evp5 = 0.03;             ///< after dilatation: phi 0.224 > phi0, cap X = -57.9 MPa (dilatation branch)
  double final_fraction = 0.01;   ///< porosity left at 7, fraction of phi0 (near-full crush)
  double fluid_bulk = 2.2e9;      ///< water, Pa (A5-fluid)
  int substeps = 1000;            ///< driver steps per row
  int plot_every = 5;

  double evp7() const;            ///< P3 + evp7 = -ln(1 - fraction phi0)
  /// Rows t = 0, 1, 2, 3 and the total volumetric strain there (turning points 3, 5, 7).
  std::vector<double> rows_t() const { return {0.0, 1.0, 2.0, 3.0}; }
  std::vector<double> rows_ev() const;
};

VerifyCase run_a5(const MaterialFactory& f, const A5Problem& problem = {});
VerifyCase run_a5_fluid(const MaterialFactory& f, const A5Problem& problem = {});

}  // namespace ballista
