#pragma once
// B3 (the thick cylinder under external pressure, examples/thick_cylinder.yaml) with the OTM
// solver: the same section, material, pressure ramp and damping as the MPM deck, nodes on the
// lattice of h, 2 x 2 points per cell (test_otm_b3_thick_cylinder.cpp, slow_otm_b3_locking.cpp).
#include <string>

#include "deck/deck_reader.hpp"
#include "verification/verification_support.hpp"

namespace ballista::verification {

/// The OTM deck at cell size h with bulk modulus K (shear modulus G0 = 26.23 GPa) and otm.anti_locking.
inline Scenario otm_thick_cylinder(double h, double K, const std::string& anti_locking) {
  const std::string yaml =
      "simulation: {solver: otm, dimension: plane_strain, end_time: 6.0e-3, cfl: 0.4, damping: 3000.0}\n"
      "materials:\n  aluminium_like: {model: linear_elastic, density: 2700, bulk_modulus: " + std::to_string(K) +
      ", shear_modulus: 26.23e9}\n"
      "otm: {anti_locking: " + anti_locking + "}\n"
      "grid: {lower: [0.0, 0.0], upper: [2.2, 2.2], cell_size: " + std::to_string(h) +
      ", boundary: {x_min: symmetry, y_min: symmetry}}\n"
      "bodies:\n  - {name: cylinder, material: aluminium_like, particles_per_cell: 2,\n"
      "     shape: {type: tube, center: [0, 0, 0], axis: z, radius: 2.0, inner_radius: 1.0}}\n"
      "loads:\n  - {type: pressure, body: cylinder, surface: outer, pressure: 10.0e6, "
      "curve: [[0, 0], [3.0e-3, 1.0], [1.0, 1.0]]}\n";
  return parse_deck(yaml, "otm_thick_cylinder.yaml");
}

}  // namespace ballista::verification
