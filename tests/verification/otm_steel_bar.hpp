#pragma once
// The elastic steel bar of the OTM impact tests (test_otm_elastic_impact.cpp, test_otm_contact.cpp):
// axisymmetric, R = 5 mm, L = 50 mm, E = 200 GPa, rho = 7850 kg/m^3, nu = 0.3, 1 mm nodal spacing,
// 2 points per cell and direction, CFL 0.9.
#include <string>

namespace ballista::otm_steel_bar {

/// The simulation and material sections, to `end_time` (s, as written in the deck).
inline std::string head(const std::string& end_time, const std::string& cfl = "0.9") {
  return "simulation: {solver: otm, dimension: axisymmetric, end_time: " + end_time + ", cfl: " + cfl + "}\n"
         "materials:\n"
         "  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}\n";
}

/// The bar at 10 m/s onto the rigid wall y = 0 (otm.wall_model `wall_model`; `otm_extra`: more
/// otm keys, ", key: value").
inline std::string on_wall(const std::string& wall_model, const std::string& end_time, const std::string& cfl = "0.9",
                           const std::string& otm_extra = "") {
  return head(end_time, cfl) + "otm: {wall_model: " + wall_model + otm_extra + "}\n" + R"(
grid: {lower: [0, 0], upper: [0.02, 0.06], cell_size: 1.0e-3, boundary: {x_min: symmetry, y_min: wall}}
bodies:
  - {name: bar, material: steel, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 5.0e-3, length: 0.05},
     particles_per_cell: 2, velocity: [0, -10.0, 0]}
)";
}

}  // namespace ballista::otm_steel_bar
